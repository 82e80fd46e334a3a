import { describe, expect, it } from 'vitest';
import { builtinScene } from '../../loaders/builtin/index.ts';
import { giSize, haltonJitter, hybridBytesPerPixel, radicalInverse, rasterDraws } from './hybrid.ts';
import { prepareScene } from '../prepare.ts';

describe('the hybrid recipe, host side', () => {
  it("jitters by Halton (2, 3): stratified in both axes over the period, centred on the pixel", () => {
    expect([1, 2, 3, 4].map((i) => radicalInverse(i, 2))).toEqual([0.5, 0.25, 0.75, 0.125]);
    expect([1, 2, 3].map((i) => radicalInverse(i, 3))).toEqual([1 / 3, 2 / 3, 1 / 9]);
    const points = Array.from({ length: 16 }, (_, f) => haltonJitter(f));
    for (const [x, y] of points) {
      expect(x).toBeGreaterThanOrEqual(-0.5);
      expect(x).toBeLessThan(0.5);
      expect(y).toBeGreaterThanOrEqual(-0.5);
      expect(y).toBeLessThan(0.5);
    }
    // Each quarter of the pixel along x gets four of the sixteen points (base 2 is a (0,1)-sequence).
    for (let q = 0; q < 4; q++) expect(points.filter(([x]) => Math.floor((x + 0.5) * 4) === q)).toHaveLength(4);
    const mean = points.reduce((m, [x, y]) => [m[0]! + x / 16, m[1]! + y / 16], [0, 0]);
    expect(Math.abs(mean[0]!)).toBeLessThan(0.05);
    expect(Math.abs(mean[1]!)).toBeLessThan(0.05);
    expect(haltonJitter(16)).toEqual(haltonJitter(0));
  });

  it('sizes the GI target by whole blocks and states its memory per pixel', () => {
    expect(giSize(1920, 1080, 1)).toEqual([1920, 1080]);
    expect(giSize(1920, 1080, 0.5)).toEqual([960, 540]);
    expect(giSize(1921, 1081, 0.25)).toEqual([481, 271]);
    // 8 vec4f buffers, visibility and depth: 140 B; per GI texel two illumination pairs, a surface record, the filter's scratch: 40 B.
    expect(hybridBytesPerPixel(1)).toBe(180);
    expect(hybridBytesPerPixel(0.5)).toBe(150);
    expect(hybridBytesPerPixel(0.25)).toBe(142.5);
  });

  it('draws every primitive once: the static world, then each moving instance through its mesh', () => {
    const still = prepareScene(builtinScene('cornell'));
    expect(rasterDraws(still)).toEqual([{ first: 0, count: still.triangles.count, instance: 0 }]);
    const moving = prepareScene(builtinScene('dungeon'));
    const draws = rasterDraws(moving);
    const levels = moving.levels!;
    expect(draws).toHaveLength(levels.dynamic.length + 1);
    expect(draws[0]).toEqual({ first: 0, count: moving.bvh.triIndices.length, instance: 0 });
    draws.slice(1).forEach((d, k) => {
      const mesh = moving.scene.instances[levels.dynamic[k]!]!.mesh;
      expect(d.instance).toBe(k + 1);
      expect(d.count).toBe(levels.blas.get(mesh)!.triangles.count);
    });
  });
});
