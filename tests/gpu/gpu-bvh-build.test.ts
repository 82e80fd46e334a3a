/**
 * The GPU BVH builder (gpu/build, shaders/build): its trees hold the layout's invariants, trace like
 * the CPU build's, cost about what the CPU build costs by the SAH, and its radix sort sorts. Small
 * meshes only: SwiftShader runs about a million simple operations a millisecond.
 */
import { beforeAll, describe, expect, it } from 'vitest';
import { buildBvh } from '../../src/bvh/build.ts';
import { intersectTriangle, prepareRay, T_MISS } from '../../src/bvh/ray.ts';
import { degenerateSoup, makeRandom, pointCloud, quadGrid, randomSoup, testRays, uvSphere } from '../../src/bvh/test-scenes.ts';
import { traceClosest } from '../../src/bvh/traverse.ts';
import type { Bvh } from '../../src/bvh/types.ts';
import { checkBvh } from '../../src/bvh/validate.ts';
import { GpuBvhBuilder, readBackBvh } from '../../src/gpu/build/gpu-bvh-builder.ts';
import { createBufferWithData } from '../../src/gpu/readback.ts';
import { LanternError } from '../../src/errors.ts';
import { testGpu } from './gpu-context.ts';

let device: GPUDevice;
let builder: GpuBvhBuilder;

beforeAll(async () => {
  device = (await testGpu()).device;
  builder = await GpuBvhBuilder.create(device);
});

async function gpuBuild(positions: Float32Array | GPUBuffer, count: number, using = builder): Promise<Bvh> {
  const built = await using.build(positions, count);
  try {
    return await readBackBvh(device, built);
  } finally {
    built.nodes.destroy();
    built.triIndices.destroy();
  }
}

async function expectLanternError(promise: Promise<unknown>, pattern: RegExp): Promise<void> {
  await expect(promise).rejects.toBeInstanceOf(LanternError);
  await expect(promise).rejects.toThrow(pattern);
}


describe('GPU radix sort', () => {
  it('sorts random keys with many duplicates stably, and full 32-bit keys', async () => {
    const rnd = makeRandom(11);
    // 2,500 keys: more than two sort blocks, the last one partial.
    const duplicates = Uint32Array.from({ length: 2500 }, () => Math.floor(rnd() * 40) * 0x01010101);
    const wide = Uint32Array.from({ length: 1500 }, () => Math.floor(rnd() * 2 ** 32));
    for (const keys of [duplicates, wide]) {
      const sorted = await builder.sortPairs(keys);
      const expected = Array.from(keys.keys()).sort((a, b) => keys[a]! - keys[b]! || a - b);
      expect(Array.from(sorted.values)).toEqual(expected);
      expect(Array.from(sorted.keys)).toEqual(expected.map((i) => keys[i]!));
    }
  });
});

describe('GPU BVH builder (PLOC)', () => {
  const meshes: Record<string, () => Float32Array> = {
    'one triangle': () => randomSoup(1, 5),
    'three triangles': () => randomSoup(3, 6),
    'uv sphere': () => uvSphere(8, 16),
    'flat quad grid': () => quadGrid(12),
    'degenerate soup (coincident copies, points, slivers)': degenerateSoup,
    'a point cloud with no extent': () => pointCloud(40),
  };
  for (const [name, make] of Object.entries(meshes)) {
    it(`builds a valid tree whose leaves hold a permutation of the triangles: ${name}`, async () => {
      const positions = make();
      const bvh = await gpuBuild(positions, positions.length / 9);
      checkBvh(bvh, positions);
      const leaves = Array.from(bvh.triCount).filter((c) => c > 0);
      expect(Math.max(...leaves)).toBeLessThanOrEqual(8);
    });
  }

  it('finds the same closest hits as the CPU-built tree (same t and triangle, ties aside)', async () => {
    const positions = randomSoup(1200, 21);
    const gpu = await gpuBuild(positions, 1200);
    const cpu = buildBvh(positions);
    let hits = 0, ties = 0;
    for (const ray of testRays(positions, 400, 5, { aimed: true, margin: 1 })) {
      const a = traceClosest(gpu, positions, ray).hit, b = traceClosest(cpu, positions, ray).hit;
      expect(a === null).toBe(b === null);
      if (!a || !b) continue;
      hits++;
      expect(gpu.triIndices[a.leafIndex]).toBe(a.triangle);
      if (a.triangle === b.triangle) {
        expect(a.t).toBe(b.t);
      } else {
        // A tie: the GPU tree's triangle must really be hit at the same distance.
        ties++;
        expect(intersectTriangle(positions, a.triangle, prepareRay(ray), 0, T_MISS, { u: 0, v: 0 })).toBe(a.t);
        expect(Math.abs(a.t - b.t)).toBeLessThanOrEqual(1e-6 * b.t);
      }
    }
    expect(hits).toBeGreaterThan(300);
    expect(ties).toBeLessThan(4);
  });

  it('comes within 10 % of the CPU binned SAH cost, and the collapse into leaves lowers the cost', async () => {
    const positions = randomSoup(3000, 3);
    const cpu = buildBvh(positions).stats.sahCost;
    const collapsed = await gpuBuild(positions, 3000);
    const single = await gpuBuild(positions, 3000, await GpuBvhBuilder.create(device, { maxLeafSize: 1 }));
    expect(Math.max(...single.triCount)).toBe(1);
    expect(collapsed.stats.sahCost).toBeLessThanOrEqual(1.1 * cpu);
    expect(collapsed.stats.sahCost).toBeLessThanOrEqual(single.stats.sahCost);
  });

  it('builds the same tree however many iterations each batch before a read-back holds', async () => {
    // 1,200 clusters take a few iterations of the multi-dispatch loop before ploc_tail's 256.
    const positions = randomSoup(1200, 8);
    const whole = await gpuBuild(positions, 1200);
    const built = await (await GpuBvhBuilder.create(device, { batchIterations: 1, timing: 'kernels' })).build(positions, 1200);
    const inBatches = await readBackBvh(device, built);
    built.nodes.destroy();
    built.triIndices.destroy();
    // Each batch is one timestamped pass (where timestamps exist): several, here.
    if (built.gpuMs !== undefined) {
      expect(built.passes.filter((p) => p.name.startsWith('cluster')).length).toBeGreaterThanOrEqual(3);
      // Timed by kernel: one dispatch of the tail per batch, and the same total either way.
      const kernels = new Map(built.kernels!.map((k) => [k.name, k]));
      expect(kernels.get('ploc_tail')?.dispatches).toBe(built.passes.filter((p) => p.name.startsWith('cluster')).length);
      expect(kernels.get('radix_scatter')?.dispatches).toBe(8);
      const sum = (xs: readonly { ms: number }[]) => xs.reduce((a, x) => a + x.ms, 0);
      expect(sum(built.kernels!)).toBeCloseTo(sum(built.passes), 6);
    }
    checkBvh(inBatches, positions);
    expect(built.iterations).toBeGreaterThan(6);
    expect(inBatches.stats.sahCost).toBe(whole.stats.sahCost);
    expect(Array.from(inBatches.triCount).sort()).toEqual(Array.from(whole.triCount).sort());
  });

  it('takes the positions from a GPU buffer as from an array, and refuses what it cannot build', async () => {
    const positions = uvSphere(6, 12);
    const n = positions.length / 9;
    const buffer = createBufferWithData(device, 'test positions', positions, GPUBufferUsage.STORAGE);
    try {
      const fromBuffer = await gpuBuild(buffer, n);
      checkBvh(fromBuffer, positions);
      expect(fromBuffer.stats.sahCost).toBe((await gpuBuild(positions, n)).stats.sahCost);
      await expectLanternError(builder.build(buffer, n + 1), /position buffer/);
    } finally {
      buffer.destroy();
    }
    const nan = positions.slice();
    nan[4] = NaN;
    await expectLanternError(builder.build(nan, n), /non-finite/);
    await expectLanternError(builder.build(positions, 0), /at least one triangle/);
    await expectLanternError(GpuBvhBuilder.create(device, { searchRadius: 0 }), /searchRadius/);
  });
});
