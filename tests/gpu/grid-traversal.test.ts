/**
 * The grid traversal on the GPU (scene/grid.wgsl inside scene/bvh.wgsl's trace_closest and
 * trace_any, STATIC_ACCEL = ACCEL_GRID) against the CPU oracle (bvh/levels.ts traceScene with the grid,
 * bvh/grid.ts), with and without moving instances; and a tile scene rendered through the grid and
 * through the BVH with the same seed gives the same image. The GPU computes in f32 and the oracle in
 * f64: distances agree to a relative tolerance, and a different primitive is accepted only where it
 * is a genuine tie (the oracle hits it at the same distance) or the ray grazes an edge.
 */
import { describe, expect, it } from 'vitest';
import { tileMapScene } from '../../src/bvh/grid-test-scenes.ts';
import { movingTestScene, randomSoup, soupScene } from '../../src/bvh/test-scenes.ts';
import { prepareScene } from '../../src/renderer/prepare.ts';
import type { Scene } from '../../src/scene/types.ts';
import { expectHeatMatchesOracle, expectHitsMatchOracle, makeRays, traceOnGpu } from './accel-rays.ts';
import { testGpu } from './gpu-context.ts';
import { renderScene } from './scene-render.ts';
import { traceGrid } from '../../src/bvh/grid.ts';
import { Renderer } from '../../src/renderer/renderer.ts';



const SCENES: [string, () => Scene][] = [
  ['a tile map on its own grid (32 × 32 tiles split into sub-cells)', () => tileMapScene({ n: 32, seed: 5 })],
  ['a tile map with a moving door and ball (the top level after the grid)', () => tileMapScene({ n: 24, seed: 9, moving: true })],
  ['a random soup on an automatic grid', () => soupScene('soup', randomSoup(1500, 7), { position: [0, 0, -30], forward: [0, 0, 1], up: [0, 1, 0], vfovDegrees: 50 })],
  ['moving instances over a static soup', movingTestScene],
];

describe('GPU grid traversal equals the CPU oracle', () => {
  it.each(SCENES)('%s', async (_, make) => {
    const { device } = await testGpu();
    const prepared = prepareScene(make(), undefined, { accel: 'grid' });
    expect(prepared.packed.features.staticAccel).toBe('grid');
    const rays = makeRays(prepared, 32, { lo: prepared.grid!.lo, hi: prepared.grid!.hi, random: 768, perInstance: 128 });
    const gpu = await traceOnGpu(device, prepared, rays);
    expectHitsMatchOracle(prepared, rays, gpu, prepared.grid);
  });
});

describe('rendering through the grid', () => {
  it('a tile scene renders the same image through the grid as through the BVH (same seed)', async () => {
    const scene = tileMapScene({ n: 12, seed: 4, moving: true });
    const options = { width: 12, height: 12, spp: 2, maxBounces: 2, seed: 3 };
    const bvh = await renderScene(scene, options);
    const grid = await renderScene(scene, options, async (r) => {
      r.updateSettings({ accel: 'grid' });
      await r.accelSettled();
      expect(r.scene?.grid).toBeDefined();
    });
    let worst = 0, sum = 0;
    for (let i = 0; i < bvh.radiance.length; i++) {
      worst = Math.max(worst, Math.abs(bvh.radiance[i]! - grid.radiance[i]!));
      sum += bvh.radiance[i]!;
    }
    console.log(`grid vs bvh render: worst difference ${worst}, mean radiance ${sum / bvh.radiance.length}`);
    expect(sum / bvh.radiance.length).toBeGreaterThan(0.05);
    expect(worst).toBeLessThan(1e-3);
  });
});

describe('the heat map through the grid', () => {
  it('counts the cells and primitive tests the grid oracle counts for each pixel-centre ray', async () => {
    const renderer = await Renderer.create(await testGpu());
    try {
      const prepared = await expectHeatMatchesOracle(renderer, 'grid', 48, 36, (p, ray) => traceGrid(p.grid!, p.triangles.positions, ray, p.triangles.kinds), 5);
      expect(prepared.grid).toBeDefined();
    } finally {
      renderer.destroy();
    }
  });
});
