/**
 * What moves on Doom's walls and floors without moving geometry, as vanilla Doom plays it
 * (p_spec.c, p_lights.c; https://doomwiki.org/wiki/Animated_flat, /wiki/Linedef_type#Scrollers,
 * /wiki/Sector#Sector_specials):
 * - animated flats and wall textures: the built-in table (animdefs in p_spec.c) or a BOOM ANIMATED
 *   lump. A cycle runs over every flat (or texture) between its first and last name in WAD order
 *   (flat lump order; TEXTURE1 then TEXTURE2 order), 8 tics a frame at 35 tics a second, and a
 *   surface showing any member of a cycle animates, starting at its own frame;
 * - scrolling walls: linedef special 48 moves its front side's texture offset by one unit per tic,
 *   so the textures slide left as seen from the front;
 * - sector light specials: the thinkers of p_lights.c step the sector's light level once per tic
 *   (world/material-animation.ts plays a LightPattern); this file turns a sector's special into
 *   the pattern's parameters (P_SpawnSpecials and its P_Spawn* helpers).
 * Pure.
 */
import { LanternError } from '../../errors.ts';
import type { LightPattern } from '../../scene/dynamics-types.ts';
import { LINEDEF_FLAGS, NO_SIDEDEF, type DoomMap } from './map-types.ts';

/** Doom's game clock. */
export const TICS_PER_SECOND = 35;
/** Linedef special 48: scroll the front side's textures left, one unit per tic. */
export const SCROLL_LEFT_SPECIAL = 48;

/** One animation definition: a cycle from `first` to `last` (inclusive, in WAD order). */
export interface AnimationDef {
  readonly kind: 'flat' | 'texture';
  readonly first: string;
  readonly last: string;
  readonly ticsPerFrame: number;
}

const flat = (first: string, last: string): AnimationDef => ({ kind: 'flat', first, last, ticsPerFrame: 8 });
const wall = (first: string, last: string): AnimationDef => ({ kind: 'texture', first, last, ticsPerFrame: 8 });

/**
 * The table compiled into Doom (p_spec.c animdefs, Doom and Doom II), in its order. Note FIRELAVA's
 * cycle starts at FIRELAV3 and FIREWALL's at FIREWALA: what lies between depends on the WAD's order.
 */
export const DOOM_ANIMATIONS: readonly AnimationDef[] = [
  flat('NUKAGE1', 'NUKAGE3'),
  flat('FWATER1', 'FWATER4'),
  flat('SWATER1', 'SWATER4'),
  flat('LAVA1', 'LAVA4'),
  flat('BLOOD1', 'BLOOD3'),
  flat('RROCK05', 'RROCK08'),
  flat('SLIME01', 'SLIME04'),
  flat('SLIME05', 'SLIME08'),
  flat('SLIME09', 'SLIME12'),
  wall('BLODGR1', 'BLODGR4'),
  wall('SLADRIP1', 'SLADRIP3'),
  wall('BLODRIP1', 'BLODRIP4'),
  wall('FIREWALA', 'FIREWALL'),
  wall('GSTFONT1', 'GSTFONT3'),
  wall('FIRELAV3', 'FIRELAVA'),
  wall('FIREMAG1', 'FIREMAG3'),
  wall('FIREBLU1', 'FIREBLU2'),
  wall('ROCKRED1', 'ROCKRED3'),
  wall('BFALL1', 'BFALL4'),
  wall('SFALL1', 'SFALL4'),
  wall('WFALL1', 'WFALL4'),
  wall('DBRAIN1', 'DBRAIN4'),
];

/** Bytes per record of BOOM's ANIMATED lump: type (1), last name (9), first name (9), speed (int32). */
const ANIMATED_RECORD = 23;
/** The type byte that ends the list. */
const ANIMATED_END = 0xff;

/**
 * A BOOM ANIMATED lump (https://doomwiki.org/wiki/ANIMATED): 23-byte records of a type byte (bit 0:
 * wall texture, else flat; other bits are ZDoom's and ignored), the last and the first name
 * (9 bytes, NUL-padded) and the tics per frame (little-endian int32), ended by a type byte of 255.
 * When a WAD has one it replaces the built-in table, as in BOOM.
 */
export function readAnimatedLump(bytes: Uint8Array, source = 'ANIMATED'): AnimationDef[] {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const name = (at: number) => {
    let s = '';
    for (let i = 0; i < 9 && bytes[at + i]! !== 0; i++) s += String.fromCharCode(bytes[at + i]!);
    return s.trim().toUpperCase();
  };
  const out: AnimationDef[] = [];
  for (let at = 0; ; at += ANIMATED_RECORD) {
    if (at >= bytes.length) throw new LanternError(`${source}: the list is not ended by a record of type 255`, 'The lump may be cut short; remove it to use the built-in animations.');
    const type = bytes[at]!;
    if (type === ANIMATED_END) break;
    if (at + ANIMATED_RECORD > bytes.length) throw new LanternError(`${source}: record ${out.length} is cut short (${bytes.length - at} of ${ANIMATED_RECORD} bytes)`);
    const [last, first] = [name(at + 1), name(at + 10)];
    const ticsPerFrame = view.getInt32(at + 19, true);
    if (!(ticsPerFrame > 0)) throw new LanternError(`${source}: record ${out.length} (${first}–${last}) has ${ticsPerFrame} tics per frame`);
    out.push({ kind: type & 1 ? 'texture' : 'flat', first, last, ticsPerFrame });
  }
  return out;
}

/** A resolved cycle: its frames' names in WAD order. */
export interface DoomCycle {
  readonly kind: 'flat' | 'texture';
  readonly names: readonly string[];
  readonly ticsPerFrame: number;
}

/** The cycles of a WAD stack, and which cycle (and frame) each flat or texture name belongs to. */
export class DoomCycles {
  private readonly member = new Map<string, { cycle: DoomCycle; frame: number }>();

  constructor(readonly cycles: readonly DoomCycle[]) {
    // A name in two cycles animates with the later one (Doom's translation tables are written in
    // table order, the later definition's writes last).
    for (const cycle of cycles) cycle.names.forEach((n, frame) => this.member.set(`${cycle.kind}:${n}`, { cycle, frame }));
  }

  /** The cycle a flat or texture belongs to and its frame there, or undefined when it does not animate. */
  of(kind: 'flat' | 'texture', name: string): { readonly cycle: DoomCycle; readonly frame: number } | undefined {
    return this.member.get(`${kind}:${name}`);
  }
}

/**
 * The cycles of `defs` over the WAD's names (flats in lump order, textures in definition order).
 * A definition whose first or last name is absent is skipped quietly (Doom II's cycles in a Doom 1
 * WAD: vanilla skips them too); one whose last name comes before its first is skipped with a
 * warning (vanilla stops with an error).
 */
export function resolveCycles(defs: readonly AnimationDef[], names: { readonly flats: readonly string[]; readonly textures: readonly string[] }, warn: (m: string) => void = () => {}): DoomCycles {
  const cycles: DoomCycle[] = [];
  for (const d of defs) {
    const list = d.kind === 'flat' ? names.flats : names.textures;
    const [a, b] = [list.indexOf(d.first), list.indexOf(d.last)];
    if (a < 0 || b < 0) continue;
    if (b <= a) {
      warn(`animated ${d.kind} ${d.first}–${d.last}: ${d.last} comes ${b === a ? 'at' : 'before'} ${d.first} in the WAD, so there is nothing to cycle; not animated`);
      continue;
    }
    cycles.push({ kind: d.kind, names: list.slice(a, b + 1), ticsPerFrame: d.ticsPerFrame });
  }
  return new DoomCycles(cycles);
}

/** p_lights.c constants. */
const GLOW_SPEED = 8;
const STROBE_BRIGHT = 5;
const FAST_DARK = 15;
const SLOW_DARK = 35;
const FLASH_MAX_TIME = 64;
const FLASH_MIN_TIME = 7;

/** The light specials a sector special may carry (BOOM's generalised specials keep them in bits 0–4). */
export function sectorLightSpecial(special: number): number {
  return special >= 32 ? special & 31 : special;
}

/** Which sectors each sector touches across two-sided lines (P_FindMinSurroundingLight's getNextSector). */
export function sectorNeighbours(map: DoomMap): number[][] {
  const out = map.sectors.map(() => new Set<number>());
  for (const line of map.linedefs) {
    if (!(line.flags & LINEDEF_FLAGS.TWO_SIDED) || line.front === NO_SIDEDEF || line.back === NO_SIDEDEF) continue;
    const a = map.sidedefs[line.front]?.sector;
    const b = map.sidedefs[line.back]?.sector;
    if (a === undefined || b === undefined || !out[a] || !out[b]) continue;
    out[a].add(b);
    out[b].add(a);
  }
  return out.map((s) => [...s]);
}

/**
 * The light pattern of sector `index` (P_SpawnSpecials), or undefined when its special is not a
 * light special. `neighbours` comes from sectorNeighbours; `seed` seeds the random patterns.
 *
 * Vanilla's numbers: 1 flash (P_SpawnLightFlash); 2 and 4 fast strobe, 3 slow strobe, each starting
 * after a random 1–8 tics; 12 slow and 13 fast strobe, in sync (vanilla p_spec.c: case 12 is
 * SLOWDARK, case 13 FASTDARK, though some lists of sector types swap their descriptions); 8 glow;
 * 17 fire flicker. "Min light" is the darkest neighbour's level or the sector's own, whichever is
 * lower; a strobe with no darker neighbour goes dark to 0, a flicker flickers down to 16 above it.
 */
export function sectorLightPattern(map: DoomMap, index: number, neighbours: readonly (readonly number[])[], seed: number): LightPattern | undefined {
  const sector = map.sectors[index];
  if (!sector) return undefined;
  const max = sector.lightLevel;
  const minSurrounding = () => Math.min(max, ...(neighbours[index] ?? []).map((n) => map.sectors[n]!.lightLevel));
  const strobe = (darkTics: number, inSync: boolean): LightPattern => {
    const min = minSurrounding();
    return { kind: 'strobe', maxLevel: max, minLevel: min === max ? 0 : min, brightTics: STROBE_BRIGHT, darkTics, inSync, seed };
  };
  switch (sectorLightSpecial(sector.special)) {
    case 1:
      return { kind: 'flash', maxLevel: max, minLevel: minSurrounding(), maxTime: FLASH_MAX_TIME, minTime: FLASH_MIN_TIME, seed };
    case 2:
    case 4:
      return strobe(FAST_DARK, false);
    case 3:
      return strobe(SLOW_DARK, false);
    case 8:
      return { kind: 'glow', maxLevel: max, minLevel: minSurrounding(), step: GLOW_SPEED };
    case 12:
      return strobe(SLOW_DARK, true);
    case 13:
      return strobe(FAST_DARK, true);
    case 17:
      return { kind: 'flicker', maxLevel: max, minLevel: minSurrounding() + 16, seed };
    default:
      return undefined;
  }
}
