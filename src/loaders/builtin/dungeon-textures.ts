/**
 * The dungeon's stone, drawn in code: coursed wall blocks, floor flagstones and a rough ceiling. Each
 * is an sRGB texture that tiles (the noise wraps with the image), made of blocks with a tint of their
 * own, dark mortar joints, a bevel that darkens each block toward its edges and value noise for the
 * grain. Deterministic (a hash, no random state). Pure.
 */
import type { Texture } from '../../scene/types.ts';

/** A hash of integers to [0, 1) (a 32-bit integer mix, after Wang / "lowbias32"). */
export function hash01(...values: number[]): number {
  let h = 0x9e3779b9;
  for (const v of values) {
    h = Math.imul(h ^ (v | 0), 0x85ebca6b);
    h ^= h >>> 16;
    h = Math.imul(h, 0x7feb352d);
    h ^= h >>> 15;
    h = Math.imul(h, 0x846ca68b);
    h ^= h >>> 16;
  }
  return (h >>> 0) / 4294967296;
}

/** Smooth value noise of period `period` cells (so a texture of period·cell pixels tiles), in [0, 1). */
function valueNoise(x: number, y: number, period: number, seed: number): number {
  const xi = Math.floor(x), yi = Math.floor(y);
  const fx = x - xi, fy = y - yi;
  const sx = fx * fx * (3 - 2 * fx), sy = fy * fy * (3 - 2 * fy);
  const at = (i: number, j: number) => hash01(((i % period) + period) % period, ((j % period) + period) % period, seed);
  const a = at(xi, yi), b = at(xi + 1, yi), c = at(xi, yi + 1), d = at(xi + 1, yi + 1);
  return a + (b - a) * sx + (c - a) * sy + (a - b - c + d) * sx * sy;
}

/** Three octaves of value noise over a `size`-pixel tiling image, in [0, 1). */
function grain(px: number, py: number, size: number, seed: number): number {
  let sum = 0, weight = 0;
  for (let o = 0; o < 3; o++) {
    const cells = 8 << o;
    const w = 1 / (1 << o);
    sum += w * valueNoise((px / size) * cells, (py / size) * cells, cells, seed + o);
    weight += w;
  }
  return sum / weight;
}

/** Which block a pixel lies in, and how far (pixels) from the block's nearest edge. */
interface BlockHit {
  readonly id: number;
  readonly edge: number;
}

type Layout = (px: number, py: number) => BlockHit;

/**
 * Paints a tiling texture: stone colour × per-block tint × bevel × grain, mortar where the pixel is
 * within `mortar` pixels of a block edge.
 */
function paint(name: string, size: number, layout: Layout, stone: readonly [number, number, number], mortar: number, seed: number): Texture {
  const rgba = new Uint8Array(size * size * 4);
  for (let py = 0; py < size; py++) {
    for (let px = 0; px < size; px++) {
      const { id, edge } = layout(px, py);
      const g = grain(px, py, size, seed);
      let shade: number;
      let tint: readonly [number, number, number];
      if (edge < mortar) {
        shade = 0.32 + 0.12 * g;
        tint = [0.9, 0.88, 0.85];
      } else {
        const block = 0.8 + 0.4 * hash01(id, seed);
        const warm = 0.06 * (hash01(id, seed + 1) - 0.5);
        const bevel = Math.min(1, 0.78 + 0.22 * ((edge - mortar) / 3));
        // A few darker pits and lighter flecks.
        const fleck = hash01(px, py, seed + 2);
        shade = block * bevel * (0.78 + 0.36 * g) * (fleck < 0.02 ? 0.75 : fleck > 0.99 ? 1.15 : 1);
        tint = [1 + warm, 1, 1 - warm];
      }
      const i = (py * size + px) * 4;
      for (let k = 0; k < 3; k++) rgba[i + k] = Math.max(0, Math.min(255, Math.round(stone[k]! * tint[k]! * shade)));
      rgba[i + 3] = 255;
    }
  }
  return { name, width: size, height: size, rgba, encoding: 'srgb' };
}

/** Running bond: courses of `course` pixels, blocks `block` wide, every other course shifted by half a block. */
function runningBond(size: number, block: number, course: number): Layout {
  return (px, py) => {
    const row = Math.floor(py / course);
    const shifted = (px + (row % 2) * (block / 2)) % size;
    const column = Math.floor(shifted / block);
    const x = shifted - column * block, y = py - row * course;
    return { id: row * 97 + column, edge: Math.min(x, block - 1 - x, y, course - 1 - y) };
  };
}

/** A square grid of `block`-pixel stones. */
function grid(block: number): Layout {
  return (px, py) => {
    const column = Math.floor(px / block), row = Math.floor(py / block);
    const x = px - column * block, y = py - row * block;
    return { id: row * 131 + column, edge: Math.min(x, block - 1 - x, y, block - 1 - y) };
  };
}

/** Wall blocks: 128 × 128 pixels for one tile's width of wall (two blocks a course, four courses). */
export const wallTexture = (): Texture => paint('dungeon-wall', 128, runningBond(128, 64, 32), [124, 112, 98], 2, 11);

/** Floor: 256 × 256 pixels, 4 × 4 flagstones; a floor tile shows four of them, chosen per tile. */
export const FLOOR_STONES_PER_SIDE = 4;
export const floorTexture = (): Texture => paint('dungeon-floor', 256, grid(64), [112, 104, 94], 3, 23);

/** Ceiling: rough, darker, larger blocks. */
export const ceilingTexture = (): Texture => paint('dungeon-ceiling', 128, runningBond(128, 128, 64), [84, 79, 74], 2, 37);
