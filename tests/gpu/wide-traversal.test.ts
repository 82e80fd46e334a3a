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
import { traceScene } from '../../src/bvh/levels.ts';
import { intersectPrimitive, prepareRay } from '../../src/bvh/ray.ts';
import { tileMapScene } from '../../src/bvh/grid-test-scenes.ts';
import { movingTestScene } from '../../src/bvh/test-scenes.ts';
import { traceWide, WIDE_LAYOUTS } from '../../src/bvh/wide.ts';
import { prepareScene } from '../../src/renderer/prepare.ts';
import { Renderer } from '../../src/renderer/renderer.ts';
import type { Scene } from '../../src/scene/types.ts';
import { expectHeatMatchesOracle, makeRays, traceOnGpu } from './accel-rays.ts';
import { testGpu } from './gpu-context.ts';
import { renderScene } from './scene-render.ts';

const NO_TRIANGLE = 0xffffffff;
const EDGE = 1e-3;


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
    const { positions, kinds } = prepared.triangles;
    let exact = 0, ties = 0, grazing = 0, hits = 0;
    const failures: string[] = [];
    rays.forEach((ray, i) => {
      const cpu = traceScene(prepared.scene, prepared.triangles, prepared.bvh, prepared.levels, ray, prepared.wide);
      const g = gpu[i]!;
      const onEdge = (u: number, v: number, prim: number) => kinds[prim] !== 0 || Math.min(u, v, 1 - u - v) < EDGE;
      // Any hit is whether the closest hit exists.
      if (g.any !== (g.tri !== NO_TRIANGLE) && !(cpu && onEdge(cpu.u, cpu.v, cpu.triangle))) failures.push(`ray ${i}: any ${g.any}, closest ${g.tri === NO_TRIANGLE ? 'miss' : g.tri}`);
      if (cpu) hits++;
      if (!cpu || g.tri === NO_TRIANGLE) {
        if (!cpu && g.tri === NO_TRIANGLE) exact++;
        else if (cpu && onEdge(cpu.u, cpu.v, cpu.triangle)) grazing++;
        else if (!cpu && onEdge(g.u, g.v, g.tri)) grazing++;
        else failures.push(`ray ${i}: cpu ${cpu ? `hit ${cpu.triangle} at ${cpu.t}` : 'miss'}, gpu ${g.tri === NO_TRIANGLE ? 'miss' : `hit ${g.tri} at ${g.t}`}`);
        return;
      }
      const relative = Math.abs(g.t - cpu.t) / Math.max(cpu.t, 1e-3);
      if (g.tri === cpu.triangle && relative < 1e-4) {
        exact++;
        return;
      }
      const tAlt = intersectPrimitive(positions, kinds, g.tri, prepareRay(ray), 0, 3e38, { u: 0, v: 0 });
      if (Math.abs(tAlt - cpu.t) / Math.max(cpu.t, 1e-3) < 1e-4 || (onEdge(cpu.u, cpu.v, cpu.triangle) && relative < 1e-3)) ties++;
      else failures.push(`ray ${i}: cpu ${cpu.triangle} at ${cpu.t}, gpu ${g.tri} at ${g.t} (oracle has it at ${tAlt})`);
    });
    console.log(`${layout}: ${rays.length} rays: ${hits} hits, ${exact} exact, ${ties} ties, ${grazing} grazing`);
    expect(failures.slice(0, 10)).toEqual([]);
    expect(hits).toBeGreaterThan(rays.length / 6);
    expect(ties + grazing).toBeLessThan(0.01 * rays.length);
    if (prepared.levels) {
      const moving = new Set(prepared.levels.dynamic);
      expect(gpu.filter((g) => g.tri !== NO_TRIANGLE && moving.has(prepared.triangles.instanceIds[g.tri]!)).length).toBeGreaterThan(30);
    }
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
