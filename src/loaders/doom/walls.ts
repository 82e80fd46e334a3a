/**
 * Wall quads with Doom's texture alignment rules (vanilla r_segs.c, R_StoreWallRange and
 * R_RenderMaskedSegRange; https://doomwiki.org/wiki/Texture_alignment,
 * https://doomwiki.org/wiki/Sidedef).
 *
 * Every linedef side that faces a sector gets its sections:
 * - one-sided line: the middle texture, floor to ceiling;
 * - two-sided line: the lower texture where the other sector's floor is higher, the upper texture
 *   where its ceiling is lower, and the middle texture, if named, as a masked (see-through) texture
 *   drawn once in the opening between the two sectors.
 *
 * Texture coordinates, in texels: u runs along the line from the side's start vertex (v1 for the
 * front side, v2 for the back side, so that u grows left to right as seen from the side's sector)
 * plus the sidedef's x offset. v runs downward from a reference height ("pegging") plus the y offset:
 * row(h) = reference + yOffset − h. Heights are in map units, one texel per unit.
 */
import { LINEDEF_FLAGS, NO_SIDEDEF, SKY_FLAT, type DoomMap, type Sector, type Sidedef } from './map-types.ts';

export type WallSection = 'middle' | 'upper' | 'lower' | 'masked';

/**
 * What a quad shows: a wall texture; the sky (where Doom shows the sky instead of a wall); or a
 * texture that should be there but is not ('-' or absent from the WAD), which still needs geometry
 * so the map stays closed.
 */
export type WallSurface =
  | { readonly kind: 'texture'; readonly name: string }
  | { readonly kind: 'sky' }
  | { readonly kind: 'missing'; readonly name: string };

export interface WallQuad {
  readonly line: number;
  readonly side: 'front' | 'back';
  /** The sector the quad faces: its sidedef's sector. */
  readonly sector: number;
  readonly section: WallSection;
  readonly surface: WallSurface;
  /**
   * The quad's bottom edge runs from (x0, y0) to (x1, y1) on the map: start to end as seen from
   * `sector`, which lies to the right of that direction. Its corners, counter-clockwise seen from the
   * sector: (x0, y0, bottom), (x1, y1, bottom), (x1, y1, top), (x0, y0, top).
   */
  readonly x0: number;
  readonly y0: number;
  readonly x1: number;
  readonly y1: number;
  readonly bottom: number;
  readonly top: number;
  /** Texture coordinates (texels / texture size): u at the start and end, v at the top and bottom. */
  readonly u0: number;
  readonly u1: number;
  readonly vTop: number;
  readonly vBottom: number;
  /**
   * Present when the quad follows a moving sector's floor or ceiling (a door or lift): how its
   * heights and v coordinates change per unit that sector's floor and ceiling rise, [per floor unit,
   * per ceiling unit]. The numbers above are then the quad at rest (and v is not shifted by whole
   * repeats, so that it stays linear in the heights).
   */
  readonly motion?: QuadMotion;
}

export interface QuadMotion {
  readonly sector: number;
  readonly bottom: readonly [number, number];
  readonly top: readonly [number, number];
  readonly vTop: readonly [number, number];
  readonly vBottom: readonly [number, number];
}

/**
 * How far a moving sector's floor and ceiling may go from their rest heights, as [lowest, highest]
 * displacement (both include 0). A quad whose corners depend on such a sector is emitted when it has
 * height anywhere in that range, so the quads, and the triangle count, never change while it moves.
 */
export interface SectorMotionRange {
  readonly floor: readonly [number, number];
  readonly ceiling: readonly [number, number];
}

/**
 * A height that may follow one moving sector: at + perFloor · Δfloor + perCeiling · Δceiling, where
 * Δ is how far that sector's floor or ceiling has moved from rest. Static heights have both rates 0.
 */
interface Level {
  readonly at: number;
  readonly perFloor: number;
  readonly perCeiling: number;
}

const fixed = (at: number): Level => ({ at, perFloor: 0, perCeiling: 0 });
const isFixed = (l: Level): boolean => l.perFloor === 0 && l.perCeiling === 0;
const plus = (l: Level, k: number): Level => ({ ...l, at: l.at + k });
const minus = (a: Level, b: Level): Level => ({ at: a.at - b.at, perFloor: a.perFloor - b.perFloor, perCeiling: a.perCeiling - b.perCeiling });

export interface TextureSize {
  readonly width: number;
  readonly height: number;
}

/** Size used for the texture coordinates of a missing texture: any size works, it is never sampled. */
const MISSING_SIZE: TextureSize = { width: 64, height: 64 };

export const isSky = (flat: string): boolean => flat === SKY_FLAT;
const hasTexture = (name: string): boolean => name !== '-' && name !== '';

/**
 * All wall quads of a map. `textureSize` gives the size of a wall texture by name, or undefined
 * when the WAD has none by that name; `warn` hears once per missing texture name. `moving` names the
 * sectors whose floor or ceiling moves (doors, lifts) with their ranges: quads whose corners depend
 * on one of them carry `motion` (a line between two moving sectors follows its front sector's).
 */
export function buildWalls(
  map: DoomMap,
  textureSize: (name: string) => TextureSize | undefined,
  warn: (message: string) => void = () => {},
  moving: ReadonlyMap<number, SectorMotionRange> = new Map(),
): WallQuad[] {
  const quads: WallQuad[] = [];
  // Missing textures are reported once per name, with how often they were needed.
  const missingUses = new Map<string, { first: string; count: number; consequence: string }>();
  const missing = (name: string, where: string, consequence = 'drawn with a plain material') => {
    const key = hasTexture(name) ? name : '-';
    const seen = missingUses.get(key);
    if (seen) seen.count++;
    else missingUses.set(key, { first: where, count: 1, consequence });
  };

  map.linedefs.forEach((line, index) => {
    const v1 = map.vertices[line.v1];
    const v2 = map.vertices[line.v2];
    if (!v1 || !v2) return;
    const length = Math.hypot(v2.x - v1.x, v2.y - v1.y);
    if (length === 0) return;
    const frontSide = sideOf(map, line.front);
    const backSide = sideOf(map, line.back);
    // The moving sector this line's quads follow, if any, and its range's corners and middle.
    const mover = [frontSide, backSide].map((side) => side?.sidedef.sector).find((s) => s !== undefined && moving.has(s));
    const range = mover === undefined ? undefined : moving.get(mover)!;
    const corners = range ? range.floor.flatMap((f) => range.ceiling.map((c) => [f, c] as const)) : [];
    const middle = range ? [(range.floor[0] + range.floor[1]) / 2, (range.ceiling[0] + range.ceiling[1]) / 2] as const : [0, 0] as const;
    const value = (l: Level, [f, c]: readonly [number, number]) => l.at + l.perFloor * f + l.perCeiling * c;
    /** Above zero at rest (static heights) or anywhere in the mover's range. */
    const positive = (l: Level) => (isFixed(l) ? l.at > 0 : corners.some((corner) => value(l, corner) > 0));
    // Minimum and maximum stay linear: the branch that holds in the middle of the range is kept.
    const max = (a: Level, b: Level): Level => (isFixed(a) && isFixed(b) ? fixed(Math.max(a.at, b.at)) : value(a, middle) >= value(b, middle) ? a : b);
    const min = (a: Level, b: Level): Level => (isFixed(a) && isFixed(b) ? fixed(Math.min(a.at, b.at)) : value(a, middle) <= value(b, middle) ? a : b);
    const floorOf = (side: { sidedef: Sidedef; sector: Sector }): Level =>
      side.sidedef.sector === mover ? { at: side.sector.floorHeight, perFloor: 1, perCeiling: 0 } : fixed(side.sector.floorHeight);
    const ceilingOf = (side: { sidedef: Sidedef; sector: Sector }): Level =>
      side.sidedef.sector === mover ? { at: side.sector.ceilingHeight, perFloor: 0, perCeiling: 1 } : fixed(side.sector.ceilingHeight);

    for (const [side, own, other] of [['front', frontSide, backSide], ['back', backSide, frontSide]] as const) {
      if (!own) continue;
      const [start, end] = side === 'front' ? [v1, v2] : [v2, v1];
      const where = `linedef ${index} (${side})`;
      const emit = (section: WallSection, bottom: Level, top: Level, surface: WallSurface, reference: Level, size: TextureSize) => {
        if (!positive(minus(top, bottom))) return;
        // Whole repeats of the texture are invisible (it wraps); dropping them keeps the numbers small.
        const u = own.sidedef.xOffset / size.width;
        const shiftU = Math.floor(u);
        const row = (h: Level): Level => ({
          at: (reference.at + own.sidedef.yOffset - h.at) / size.height,
          perFloor: (reference.perFloor - h.perFloor) / size.height,
          perCeiling: (reference.perCeiling - h.perCeiling) / size.height,
        });
        const [rowTop, rowBottom] = [row(top), row(bottom)];
        const moves = ![bottom, top, rowTop, rowBottom].every(isFixed);
        // A moving quad's v keeps its whole repeats, so it stays linear in the heights.
        const shiftV = moves ? 0 : Math.floor(rowTop.at);
        const rates = (l: Level) => [l.perFloor, l.perCeiling] as const;
        quads.push({
          line: index, side, sector: own.sidedef.sector, section, surface,
          x0: start.x, y0: start.y, x1: end.x, y1: end.y, bottom: bottom.at, top: top.at,
          u0: u - shiftU, u1: u - shiftU + length / size.width,
          vTop: rowTop.at - shiftV, vBottom: rowBottom.at - shiftV,
          ...(moves && { motion: { sector: mover!, bottom: rates(bottom), top: rates(top), vTop: rates(rowTop), vBottom: rates(rowBottom) } }),
        });
      };
      // A texture that the section needs: when it is missing, the quad is still emitted.
      const needed = (name: string, section: WallSection): [WallSurface, TextureSize] => {
        const size = hasTexture(name) ? textureSize(name) : undefined;
        if (size) return [{ kind: 'texture', name }, size];
        missing(name, `${where} ${section}`);
        return [{ kind: 'missing', name }, MISSING_SIZE];
      };
      const flags = line.flags;
      const s = own.sector;
      const [sFloor, sCeiling] = [floorOf(own), ceilingOf(own)];

      if (!other) {
        // One-sided: the middle texture's top at the ceiling, or with "lower unpegged" its bottom at
        // the floor (so a door frame's texture stays put when the door sector moves).
        const [surface, size] = needed(own.sidedef.middle, 'middle');
        const reference = flags & LINEDEF_FLAGS.LOWER_UNPEGGED ? plus(sFloor, size.height) : sCeiling;
        emit('middle', sFloor, sCeiling, surface, reference, size);
        continue;
      }

      const o = other.sector;
      const [oFloor, oCeiling] = [floorOf(other), ceilingOf(other)];
      const bothSky = isSky(s.ceilingFlat) && isSky(o.ceilingFlat);
      // Doom's sky hack: between two sky ceilings no upper texture is drawn and the sky shows
      // instead; vanilla does it by treating this side's ceiling as the other's (worldtop =
      // worldhigh), which also moves the reference of a lower-unpegged lower texture.
      const top = bothSky ? oCeiling : sCeiling;

      if (positive(minus(top, oCeiling))) {
        // Upper: its bottom at the lower (other) ceiling, or with "upper unpegged" its top at this
        // sector's ceiling. Drawn down to the other ceiling, but not below this floor.
        const bottom = max(oCeiling, sFloor);
        const name = own.sidedef.upper;
        if (!hasTexture(name) && (isSky(o.ceilingFlat) || isSky(s.ceilingFlat))) {
          // No upper texture next to a sky: the sky shows there. Below the other sector's sky
          // ceiling, vanilla fills the gap with that sky plane; under this sector's sky it would
          // smear the other ceiling's flat, and ports draw sky instead, which is what mappers meant
          // (a roof line against the sky).
          emit('upper', bottom, top, { kind: 'sky' }, top, MISSING_SIZE);
        } else {
          const [surface, size] = needed(name, 'upper');
          const reference = flags & LINEDEF_FLAGS.UPPER_UNPEGGED ? top : plus(oCeiling, size.height);
          emit('upper', bottom, top, surface, reference, size);
        }
      } else if (bothSky && positive(minus(sCeiling, oCeiling))) {
        // The sky hack's gap, seen from the higher sky: sky. Geometry here keeps rays inside the map.
        emit('upper', max(oCeiling, sFloor), sCeiling, { kind: 'sky' }, sCeiling, MISSING_SIZE);
      }

      if (positive(minus(oFloor, sFloor))) {
        // Lower: its top at the higher (other) floor, or with "lower unpegged" aligned as if it
        // started at this sector's ceiling (so it lines up with a one-sided wall beside it).
        const [surface, size] = needed(own.sidedef.lower, 'lower');
        const reference = flags & LINEDEF_FLAGS.LOWER_UNPEGGED ? top : oFloor;
        emit('lower', sFloor, min(oFloor, sCeiling), surface, reference, size);
      }

      const masked = own.sidedef.middle;
      if (hasTexture(masked)) {
        // Masked middle: drawn once (not tiled vertically), its top at the lower ceiling, or with
        // "lower unpegged" its bottom at the higher floor; clipped to the opening between the two
        // sectors. Optional, so a missing one is only reported.
        const size = textureSize(masked);
        if (!size) {
          missing(masked, `${where} masked middle`, 'left out');
          continue;
        }
        const openBottom = max(sFloor, oFloor);
        const openTop = min(sCeiling, oCeiling);
        const reference = flags & LINEDEF_FLAGS.LOWER_UNPEGGED ? plus(openBottom, size.height) : openTop;
        const textureTop = plus(reference, own.sidedef.yOffset);
        emit('masked', max(openBottom, plus(textureTop, -size.height)), min(openTop, textureTop), { kind: 'texture', name: masked }, reference, size);
      }
    }
  });
  for (const [name, { first, count, consequence }] of missingUses) {
    const times = count > 1 ? `${count} wall sections, the first` : 'one wall section,';
    warn(hasTexture(name)
      ? `texture ${name} is not in the WAD (${times} ${first}); ${consequence}`
      : `${times} ${first}, need${count > 1 ? '' : 's'} a texture but name${count > 1 ? '' : 's'} none; ${consequence}`);
  }
  return quads;
}

function sideOf(map: DoomMap, index: number): { sidedef: Sidedef; sector: Sector } | undefined {
  if (index === NO_SIDEDEF) return undefined;
  const sidedef = map.sidedefs[index];
  const sector = sidedef && map.sectors[sidedef.sector];
  return sidedef && sector ? { sidedef, sector } : undefined;
}
