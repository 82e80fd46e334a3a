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
}

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
 * when the WAD has none by that name; `warn` hears once per missing texture name.
 */
export function buildWalls(map: DoomMap, textureSize: (name: string) => TextureSize | undefined, warn: (message: string) => void = () => {}): WallQuad[] {
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
    for (const [side, own, other] of [['front', frontSide, backSide], ['back', backSide, frontSide]] as const) {
      if (!own) continue;
      const [start, end] = side === 'front' ? [v1, v2] : [v2, v1];
      const where = `linedef ${index} (${side})`;
      const emit = (section: WallSection, bottom: number, top: number, surface: WallSurface, reference: number, size: TextureSize) => {
        if (!(top > bottom)) return;
        // Whole repeats of the texture are invisible (it wraps); dropping them keeps the numbers small.
        const u = own.sidedef.xOffset / size.width;
        const shiftU = Math.floor(u);
        const row = (h: number) => (reference + own.sidedef.yOffset - h) / size.height;
        const shiftV = Math.floor(row(top));
        quads.push({
          line: index, side, sector: own.sidedef.sector, section, surface,
          x0: start.x, y0: start.y, x1: end.x, y1: end.y, bottom, top,
          u0: u - shiftU, u1: u - shiftU + length / size.width,
          vTop: row(top) - shiftV, vBottom: row(bottom) - shiftV,
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

      if (!other) {
        // One-sided: the middle texture's top at the ceiling, or with "lower unpegged" its bottom at
        // the floor (so a door frame's texture stays put when the door sector moves).
        const [surface, size] = needed(own.sidedef.middle, 'middle');
        const reference = flags & LINEDEF_FLAGS.LOWER_UNPEGGED ? s.floorHeight + size.height : s.ceilingHeight;
        emit('middle', s.floorHeight, s.ceilingHeight, surface, reference, size);
        continue;
      }

      const o = other.sector;
      const bothSky = isSky(s.ceilingFlat) && isSky(o.ceilingFlat);
      // Doom's sky hack: between two sky ceilings no upper texture is drawn and the sky shows
      // instead; vanilla does it by treating this side's ceiling as the other's (worldtop =
      // worldhigh), which also moves the reference of a lower-unpegged lower texture.
      const top = bothSky ? o.ceilingHeight : s.ceilingHeight;

      if (o.ceilingHeight < top) {
        // Upper: its bottom at the lower (other) ceiling, or with "upper unpegged" its top at this
        // sector's ceiling. Drawn down to the other ceiling, but not below this floor.
        const bottom = Math.max(o.ceilingHeight, s.floorHeight);
        const name = own.sidedef.upper;
        if (!hasTexture(name) && (isSky(o.ceilingFlat) || isSky(s.ceilingFlat))) {
          // No upper texture next to a sky: the sky shows there. Below the other sector's sky
          // ceiling, vanilla fills the gap with that sky plane; under this sector's sky it would
          // smear the other ceiling's flat, and ports draw sky instead, which is what mappers meant
          // (a roof line against the sky).
          emit('upper', bottom, top, { kind: 'sky' }, top, MISSING_SIZE);
        } else {
          const [surface, size] = needed(name, 'upper');
          const reference = flags & LINEDEF_FLAGS.UPPER_UNPEGGED ? top : o.ceilingHeight + size.height;
          emit('upper', bottom, top, surface, reference, size);
        }
      } else if (bothSky && o.ceilingHeight < s.ceilingHeight) {
        // The sky hack's gap, seen from the higher sky: sky. Geometry here keeps rays inside the map.
        emit('upper', Math.max(o.ceilingHeight, s.floorHeight), s.ceilingHeight, { kind: 'sky' }, s.ceilingHeight, MISSING_SIZE);
      }

      if (o.floorHeight > s.floorHeight) {
        // Lower: its top at the higher (other) floor, or with "lower unpegged" aligned as if it
        // started at this sector's ceiling (so it lines up with a one-sided wall beside it).
        const [surface, size] = needed(own.sidedef.lower, 'lower');
        const reference = flags & LINEDEF_FLAGS.LOWER_UNPEGGED ? top : o.floorHeight;
        emit('lower', s.floorHeight, Math.min(o.floorHeight, s.ceilingHeight), surface, reference, size);
      }

      const middle = own.sidedef.middle;
      if (hasTexture(middle)) {
        // Masked middle: drawn once (not tiled vertically), its top at the lower ceiling, or with
        // "lower unpegged" its bottom at the higher floor; clipped to the opening between the two
        // sectors. Optional, so a missing one is only reported.
        const size = textureSize(middle);
        if (!size) {
          missing(middle, `${where} masked middle`, 'left out');
          continue;
        }
        const openBottom = Math.max(s.floorHeight, o.floorHeight);
        const openTop = Math.min(s.ceilingHeight, o.ceilingHeight);
        const reference = flags & LINEDEF_FLAGS.LOWER_UNPEGGED ? openBottom + size.height : openTop;
        const textureTop = reference + own.sidedef.yOffset;
        emit('masked', Math.max(openBottom, textureTop - size.height), Math.min(openTop, textureTop), { kind: 'texture', name: middle }, reference, size);
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
