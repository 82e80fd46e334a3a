/**
 * Reads a Doom-format ("vanilla") map from its lumps (https://doomwiki.org/wiki/Map_format):
 * THINGS (10-byte records), LINEDEFS (14), SIDEDEFS (30), VERTEXES (4), SECTORS (26), all
 * little-endian. The node lumps are not needed: the geometry is built from sectors and lines.
 * Hexen-format and UDMF maps are recognised (wad.ts) and refused rather than misread.
 *
 * Broken references, and what happens to them:
 * - a lump missing, or not a whole number of records: the map is refused (nothing sensible can be
 *   read from it);
 * - a linedef whose vertex or sidedef index is out of range, or whose sidedef names a sector out of
 *   range: that linedef is dropped with a warning. Real-world PWADs do contain the odd broken line,
 *   and one missing wall is better than no map. Sidedefs with a bad sector are removed and the
 *   remaining ones renumbered, so every index in the result is valid;
 * - light levels outside 0..255 are clamped, as the game's renderer does (Freedoom has 256s);
 * - a map left with no linedefs or no sectors is refused.
 * Every index in the returned DoomMap is therefore in range (sidedefs may also be NO_SIDEDEF).
 */
import { LanternError } from '../../errors.ts';
import { checkLimit } from '../../budgets.ts';
import type { DoomMap, Linedef, MapVertex, Sector, Sidedef, Thing } from './map-types.ts';
import { NO_SIDEDEF } from './map-types.ts';
import { readName, type MapLumps, type WadStack } from './wad.ts';

export interface ReadMapOptions {
  onWarning?: (message: string) => void;
}

const RECORD_SIZE = { THINGS: 10, LINEDEFS: 14, SIDEDEFS: 30, VERTEXES: 4, SECTORS: 26 } as const;
type MapLumpName = keyof typeof RECORD_SIZE;

/** At most this many dropped-line warnings are itemised; the rest are counted. */
const MAX_ITEMISED = 10;

export function readMap(stack: WadStack, mapName: string, options: ReadMapOptions = {}): DoomMap {
  const map = stack.mapLumps(mapName);
  if (!map) throw missingMap(stack, mapName);
  const { name, format, file } = map.info;
  const where = `${name} in ${file}`;
  if (format === 'hexen') throw new LanternError(`${where} is a Hexen-format map; Lantern reads Doom-format maps only`);
  if (format === 'udmf') throw new LanternError(`${where} is a UDMF (text) map; Lantern reads Doom-format maps only`);

  const records = (lump: MapLumpName) => lumpRecords(map, lump, where);
  const vertices = readVertices(records('VERTEXES'));
  const sectors = readSectors(records('SECTORS'));
  const { sidedefs, renumber, badSectors } = readSidedefs(records('SIDEDEFS'), sectors.length);
  const { linedefs, dropped } = readLinedefs(records('LINEDEFS'), vertices.length, renumber);
  const things = readThings(records('THINGS'));

  const warn = (m: string) => options.onWarning?.(`${where}: ${m}`);
  if (badSectors > 0) warn(`removed ${badSectors} sidedef(s) whose sector index is out of range (the map has ${sectors.length} sectors)`);
  for (const d of dropped.slice(0, MAX_ITEMISED)) warn(`dropped linedef ${d}`);
  if (dropped.length > MAX_ITEMISED) warn(`dropped ${dropped.length - MAX_ITEMISED} more broken linedef(s)`);
  if (linedefs.length === 0) throw new LanternError(`${where} has no usable linedefs`, dropped.length > 0 ? 'every linedef refers to a missing vertex, sidedef or sector' : undefined);
  if (sectors.length === 0) throw new LanternError(`${where} has no sectors`);
  return { name, vertices, linedefs, sidedefs, sectors, things };
}

function missingMap(stack: WadStack, mapName: string): LanternError {
  const names = stack.maps().map((m) => m.name);
  if (names.length === 0) return new LanternError(`${stack.describe()} contains no maps`, 'load an IWAD or a PWAD with maps');
  const shown = names.length > 40 ? [...names.slice(0, 40), `… (${names.length} in all)`] : names;
  return new LanternError(`there is no map ${mapName.toUpperCase()} in ${stack.describe()}`, `its maps are ${shown.join(', ')}`);
}

/** A lump's bytes as a DataView over whole records, with the record count. */
interface Records {
  readonly view: DataView;
  readonly bytes: Uint8Array;
  readonly count: number;
  readonly size: number;
}

function lumpRecords(map: MapLumps, lump: MapLumpName, where: string): Records {
  const bytes = map.lump(lump);
  if (!bytes) throw new LanternError(`${where} has no ${lump} lump`, 'the map is incomplete');
  const size = RECORD_SIZE[lump];
  if (bytes.length % size !== 0) {
    throw new LanternError(
      `${where}: the ${lump} lump is ${bytes.length} bytes, not a whole number of ${size}-byte records`,
      'the map is corrupt or not in the Doom format',
    );
  }
  checkLimit('mapRecords', bytes.length / size, `${where}: ${lump} records`);
  return { view: new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength), bytes, count: bytes.length / size, size };
}

/** An 8-character texture or flat name: upper-cased, without NUL padding or stray spaces. */
function textureName(r: Records, at: number): string {
  return readName(r.bytes, at).trim();
}

function readVertices(r: Records): MapVertex[] {
  const out: MapVertex[] = [];
  for (let i = 0, at = 0; i < r.count; i++, at += r.size) out.push({ x: r.view.getInt16(at, true), y: r.view.getInt16(at + 2, true) });
  return out;
}

function readSectors(r: Records): Sector[] {
  const sectors: Sector[] = [];
  for (let i = 0, at = 0; i < r.count; i++, at += r.size) {
    // Vanilla clamps too: light >> 4 indexes 16 light tables, out-of-range indices take the end ones.
    const lightLevel = Math.min(255, Math.max(0, r.view.getInt16(at + 20, true)));
    sectors.push({
      floorHeight: r.view.getInt16(at, true),
      ceilingHeight: r.view.getInt16(at + 2, true),
      floorFlat: textureName(r, at + 4),
      ceilingFlat: textureName(r, at + 12),
      lightLevel,
      special: r.view.getUint16(at + 22, true),
      tag: r.view.getUint16(at + 24, true),
    });
  }
  return sectors;
}

/** Sidedefs with a valid sector, and for each original index its new one (-1: removed). */
function readSidedefs(r: Records, sectorCount: number): { sidedefs: Sidedef[]; renumber: Int32Array; badSectors: number } {
  const sidedefs: Sidedef[] = [];
  const renumber = new Int32Array(r.count).fill(-1);
  let badSectors = 0;
  for (let i = 0, at = 0; i < r.count; i++, at += r.size) {
    const sector = r.view.getUint16(at + 28, true);
    if (sector >= sectorCount) {
      badSectors++;
      continue;
    }
    renumber[i] = sidedefs.length;
    sidedefs.push({
      xOffset: r.view.getInt16(at, true),
      yOffset: r.view.getInt16(at + 2, true),
      upper: textureName(r, at + 4),
      lower: textureName(r, at + 12),
      middle: textureName(r, at + 20),
      sector,
    });
  }
  return { sidedefs, renumber, badSectors };
}

/**
 * Indices are read unsigned, as limit-removing ports do (vanilla's signed shorts cap maps at 32767
 * of each), with 0xFFFF meaning "no sidedef".
 */
function readLinedefs(r: Records, vertexCount: number, renumber: Int32Array): { linedefs: Linedef[]; dropped: string[] } {
  const linedefs: Linedef[] = [];
  const dropped: string[] = [];
  for (let i = 0, at = 0; i < r.count; i++, at += r.size) {
    const v1 = r.view.getUint16(at, true);
    const v2 = r.view.getUint16(at + 2, true);
    const rawFront = r.view.getUint16(at + 10, true);
    const rawBack = r.view.getUint16(at + 12, true);
    const front = sidedefIndex(rawFront, renumber);
    const back = sidedefIndex(rawBack, renumber);
    let problem: string | undefined;
    if (v1 >= vertexCount || v2 >= vertexCount) problem = `vertex ${Math.max(v1, v2)} does not exist (the map has ${vertexCount})`;
    else if (front === undefined) problem = `its front ${describeSidedef(rawFront, renumber)}`;
    else if (back === undefined) problem = `its back ${describeSidedef(rawBack, renumber)}`;
    if (problem !== undefined || front === undefined || back === undefined) {
      dropped.push(`${i}: ${problem}`);
      continue;
    }
    linedefs.push({
      v1,
      v2,
      flags: r.view.getUint16(at + 4, true),
      special: r.view.getUint16(at + 6, true),
      tag: r.view.getUint16(at + 8, true),
      front,
      back,
    });
  }
  return { linedefs, dropped };
}

/** The new index of a sidedef (NO_SIDEDEF for 0xFFFF), or undefined when it is missing or was removed. */
function sidedefIndex(raw: number, renumber: Int32Array): number | undefined {
  if (raw === 0xffff) return NO_SIDEDEF;
  const index = renumber[raw];
  return index !== undefined && index >= 0 ? index : undefined;
}

function describeSidedef(raw: number, renumber: Int32Array): string {
  return raw >= renumber.length ? `sidedef ${raw} does not exist (the map has ${renumber.length})` : `sidedef ${raw} has a bad sector`;
}

function readThings(r: Records): Thing[] {
  const out: Thing[] = [];
  for (let i = 0, at = 0; i < r.count; i++, at += r.size) {
    out.push({
      x: r.view.getInt16(at, true),
      y: r.view.getInt16(at + 2, true),
      angle: r.view.getInt16(at + 4, true),
      type: r.view.getUint16(at + 6, true),
      flags: r.view.getUint16(at + 8, true),
    });
  }
  return out;
}
