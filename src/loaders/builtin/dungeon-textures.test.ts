import { describe, expect, it } from 'vitest';
import type { Texture } from '../../scene/types.ts';
import { ceilingTexture, floorTexture, wallTexture } from './dungeon-textures.ts';

/** Mean absolute difference (0–255, RGB) between columns a and b, or rows when `rows`. */
function seam(t: Texture, a: number, b: number, rows = false): number {
  let sum = 0;
  for (let i = 0; i < t.width; i++) {
    const pa = rows ? (a * t.width + i) * 4 : (i * t.width + a) * 4, pb = rows ? (b * t.width + i) * 4 : (i * t.width + b) * 4;
    for (let k = 0; k < 3; k++) sum += Math.abs(t.rgba[pa + k]! - t.rgba[pb + k]!);
  }
  return sum / (3 * t.width);
}

describe('dungeon textures', () => {
  it.each([['wall', wallTexture()], ['floor', floorTexture()], ['ceiling', ceilingTexture()]] as const)('%s tiles without a seam and has blocks that differ', (_name, t) => {
    expect(t.width).toBe(t.height);
    expect(t.rgba.length).toBe(t.width * t.height * 4);
    const n = t.width;
    // Across the wrap, neighbouring texels differ no more than neighbours inside do, on average.
    let inside = 0, insideRows = 0;
    for (let i = 0; i + 1 < n; i++) {
      inside += seam(t, i, i + 1) / (n - 1);
      insideRows += seam(t, i, i + 1, true) / (n - 1);
    }
    expect(seam(t, n - 1, 0)).toBeLessThan(2 * inside);
    expect(seam(t, n - 1, 0, true)).toBeLessThan(2 * insideRows);
    // (Columns 40 apart differ several times more: the test would see a seam.)
    expect(seam(t, n / 2 - 20, n / 2 + 20)).toBeGreaterThan(2 * inside);
    // Not flat: the texels spread over a good part of the range, and it is opaque.
    let lo = 255, hi = 0;
    for (let i = 0; i < n * n; i++) {
      lo = Math.min(lo, t.rgba[i * 4 + 1]!);
      hi = Math.max(hi, t.rgba[i * 4 + 1]!);
    }
    expect(t.rgba.every((v, i) => i % 4 !== 3 || v === 255)).toBe(true);
    expect(hi - lo).toBeGreaterThan(40);
    // Deterministic.
    expect(wallTexture().rgba).toEqual(wallTexture().rgba);
  });
});
