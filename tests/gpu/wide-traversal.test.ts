/**
 * The wide traversals on the GPU (scene/bvh4.wgsl and scene/cwbvh.wgsl inside scene/bvh.wgsl's
 * trace_closest and trace_any, STATIC_ACCEL = ACCEL_BVH4 / ACCEL_CWBVH) against their CPU oracles
 * (bvh/levels.ts traceScene with the wide tree, bvh/wide.ts), with and without moving instances; the
 * heat map's counts against the oracle's; and a scene rendered through each layout and through the
 * binary BVH with the same seed gives the same image. The GPU computes in f32 and the oracle in f64:
 * distances agree to a relative tolerance, and a different primitive is accepted only where it is a
 * genuine tie (the oracle hits it at the same distance) or the ray grazes an edge.
 */
import { describe, expect, it } from 'vitest';
import { tileMapScene } from '../../src/bvh/grid-test-scenes.ts';
import { movingTestScene } from '../../src/bvh/test-scenes.ts';
import { traceWide, WIDE_LAYOUTS } from '../../src/bvh/wide.ts';
import { prepareScene } from '../../src/renderer/prepare.ts';
import { Renderer } from '../../src/renderer/renderer.ts';
import type { Scene } from '../../src/scene/types.ts';
import { expectHeatMatchesOracle, expectHitsMatchOracle, makeRays, traceOnGpu } from './accel-rays.ts';
import { testGpu } from './gpu-context.ts';
import { renderScene } from './scene-render.ts';



// One scene each (compiling the kernels is what takes the time): a static world of 460 triangles under moving instances.
const SCENES: [string, () => Scene][] = [['moving instances over a static soup (the top level after the wide tree)', movingTestScene]];

const CASES = WIDE_LAYOUTS.flatMap((layout) => SCENES.map(([name, make]) => [layout, name, make] as const));

describe('GPU wide traversal equals the CPU oracle', () => {
  it.each(CASES)('%s: %s', async (layout, _, make) => {
    const { device } = await testGpu();
    const prepared = prepareScene(make(), undefined, { accel: layout });
    expect(prepared.wide?.layout).toBe(layout);
    expect(prepared.packed.features.staticAccel).toBe(layout);
    const rays = makeRays(prepared, 24, { lo: prepared.bvh.bounds.subarray(0, 3), hi: prepared.bvh.bounds.subarray(3, 6), random: 384, perInstance: 96 });
    const gpu = await traceOnGpu(device, prepared, rays);
    expectHitsMatchOracle(prepared, rays, gpu, prepared.wide, `${layout}: `);
  });
});

describe('rendering through the wide trees', () => {
  // The quantised layout only: each render compiles the path tracer once more (BVH4's hits are held to the oracle above).
  it('a tile scene with moving instances renders the same image through the cwbvh as through the binary BVH (same seed)', async () => {
    const scene = tileMapScene({ n: 12, seed: 4, moving: true });
    const options = { width: 10, height: 10, spp: 2, maxBounces: 2, seed: 3 };
    const bvh = await renderScene(scene, options);
    let sum = 0;
    for (const v of bvh.radiance) sum += v;
    expect(sum / bvh.radiance.length).toBeGreaterThan(0.05);
    for (const layout of ['cwbvh'] as const) {
      const wide = await renderScene(scene, options, async (r) => {
        r.updateSettings({ accel: layout });
        await r.accelSettled();
        expect(r.scene?.wide?.layout).toBe(layout);
      });
      let worst = 0;
      for (let i = 0; i < bvh.radiance.length; i++) worst = Math.max(worst, Math.abs(bvh.radiance[i]! - wide.radiance[i]!));
      console.log(`${layout} vs bvh render: worst difference ${worst}, mean radiance ${sum / bvh.radiance.length}`);
      expect(worst).toBeLessThan(1e-3);
    }
  });
});

describe('the heat map through the wide trees', () => {
  it.each(WIDE_LAYOUTS)('%s: counts the nodes and primitive tests the oracle counts for each pixel-centre ray', async (layout) => {
    const renderer = await Renderer.create(await testGpu());
    try {
      const prepared = await expectHeatMatchesOracle(renderer, layout, 32, 24, (p, ray) => traceWide(p.wide!, p.triangles.positions, ray, p.triangles.kinds), 3);
      expect(prepared.wide?.layout).toBe(layout);
    } finally {
      renderer.destroy();
    }
  });
});
