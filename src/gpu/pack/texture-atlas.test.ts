import { describe, expect, it } from 'vitest';
import type { Texture } from '../../scene/types.ts';
import { meanLinearColor, packTextureAtlas } from './texture-atlas.ts';

function texture(name: string, width: number, height: number, seed: number): Texture {
  const rgba = new Uint8Array(width * height * 4);
  for (let i = 0; i < rgba.length; i++) rgba[i] = (i * 31 + seed * 17) & 255;
  return { name, width, height, rgba };
}

describe('texture atlas', () => {
  it('places every texel of every texture, without overlaps, inside its page', () => {
    const textures = [texture('a', 64, 64, 1), texture('b', 256, 128, 2), texture('c', 17, 300, 3), texture('d', 2048, 8, 4), texture('e', 1, 1, 5)];
    for (let i = 0; i < 60; i++) textures.push(texture(`f${i}`, 64 + (i % 5) * 32, 128, i));
    const atlas = packTextureAtlas(textures, 4096);
    const owner = atlas.pages.map(() => new Int32Array(atlas.pageSize * atlas.pageSize).fill(-1));
    textures.forEach((t, i) => {
      const r = atlas.rects[i]!;
      expect([r.width, r.height]).toEqual([t.width, t.height]);
      expect(r.x + r.width).toBeLessThanOrEqual(atlas.pageSize);
      expect(r.y + r.height).toBeLessThanOrEqual(atlas.pageSize);
      for (let y = 0; y < t.height; y++) {
        for (let x = 0; x < t.width; x++) {
          const p = (r.y + y) * atlas.pageSize + r.x + x;
          // A plain check per texel (an expect per texel made this test 10 s of the unit project's time).
          if (owner[r.page]![p] !== -1) throw new Error(`texel ${x},${y} of ${t.name} overlaps ${textures[owner[r.page]![p]!]!.name}`);
          owner[r.page]![p] = i;
          for (let c = 0; c < 4; c++) {
            if (atlas.pages[r.page]![p * 4 + c] !== t.rgba[(y * t.width + x) * 4 + c]) throw new Error(`texel ${x},${y} of ${t.name} differs`);
          }
        }
      }
    });
  });

  it('uses the smallest page that holds everything, and more pages when the largest is full', () => {
    expect(packTextureAtlas([texture('a', 64, 64, 1), texture('b', 64, 64, 2)], 8192).pageSize).toBe(128);
    const textures = Array.from({ length: 20 }, (_, i) => texture(`t${i}`, 1024, 1024, i));
    const atlas = packTextureAtlas(textures, 2048);
    expect(atlas.pageSize).toBe(2048);
    expect(atlas.pages.length).toBe(5);
  });

  it('gives a scene without textures a one-texel page, not megabytes', () => {
    const atlas = packTextureAtlas([], 8192);
    expect(atlas.pageSize).toBe(1);
    expect(atlas.pages).toHaveLength(1);
  });

  it('refuses a texture larger than a page may be, naming it', () => {
    expect(() => packTextureAtlas([texture('HUGE', 9000, 4, 1)], 8192)).toThrow(/'HUGE' \(9000×4\)/);
  });

  it('averages colour in linear space over opaque texels', () => {
    const rgba = new Uint8Array([255, 255, 255, 255, 0, 0, 0, 255, 10, 200, 30, 0]);
    const [r, g, b] = meanLinearColor({ name: 'x', width: 3, height: 1, rgba });
    expect(r).toBeCloseTo(0.5, 6);
    expect(g).toBeCloseTo(0.5, 6);
    expect(b).toBeCloseTo(0.5, 6);
  });
});

describe('pages for wide textures', () => {
  it('grows the page to hold a texture wider than the smallest page that would hold its height (a mip chain)', () => {
    const wide = { name: 'mips', width: 384, height: 256, rgba: new Uint8Array(384 * 256 * 4) };
    const atlas = packTextureAtlas([wide], 8192);
    expect(atlas.pageSize).toBe(512);
    expect(atlas.rects[0]).toEqual({ page: 0, x: 0, y: 0, width: 384, height: 256 });
  });
});
