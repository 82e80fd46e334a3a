import { describe, expect, it } from 'vitest';
import { LanternError } from '../errors.ts';
import { buildBvh, DEFAULT_BVH_BUILD_OPTIONS } from './build.ts';
import { bvhStats } from './stats.ts';
import { degenerateSoup, makeRandom, pointCloud, quadGrid, randomSoup, uvSphere } from './test-scenes.ts';
import { checkBvh } from './validate.ts';

const scenes: Record<string, () => Float32Array> = {
  'random soup (5k)': () => randomSoup(5000, 1),
  'quad grid (flat boxes)': () => quadGrid(40),
  'uv sphere': () => uvSphere(32, 64),
  'degenerate soup': degenerateSoup,
  'single point cloud': () => pointCloud(50),
  'huge coordinates': () => randomSoup(2000, 7, 1e37),
  'tiny coordinates': () => randomSoup(2000, 8, 1e-30),
  'one triangle': () => new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0]),
  'two triangles': () => new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0, 5, 5, 5, 6, 5, 5, 5, 6, 5]),
};

describe('buildBvh', () => {
  for (const [name, make] of Object.entries(scenes)) {
    it(`keeps every invariant: ${name}`, () => {
      const positions = make();
      const bvh = buildBvh(positions);
      checkBvh(bvh, positions, DEFAULT_BVH_BUILD_OPTIONS.maxDepth);
      const recomputed = bvhStats(bvh);
      expect(bvh.stats.triangleCount).toBe(positions.length / 9);
      expect(bvh.stats.nodeCount).toBe(bvh.nodeCount - 1);
      expect(recomputed.nodeCount).toBe(bvh.stats.nodeCount);
      expect(recomputed.leafCount).toBe(bvh.stats.leafCount);
      expect(recomputed.maxDepth).toBe(bvh.stats.maxDepth);
      expect(recomputed.meanLeafDepth).toBeCloseTo(bvh.stats.meanLeafDepth, 9);
      expect(recomputed.sahCost / bvh.stats.sahCost).toBeCloseTo(1, 9);
      expect(Number.isFinite(bvh.stats.sahCost)).toBe(true);
      expect(bvh.stats.buildMs).toBeGreaterThanOrEqual(0);
    });
  }

  it('makes a single triangle a root leaf', () => {
    const bvh = buildBvh(scenes['one triangle']!());
    expect(bvh.nodeCount).toBe(2);
    expect(bvh.triCount[0]).toBe(1);
    expect(bvh.leftFirst[0]).toBe(0);
    expect(Array.from(bvh.bounds.subarray(0, 6))).toEqual([0, 0, 0, 1, 1, 0]);
    expect(bvh.stats.sahCost).toBe(1);
  });

  it('splits two distant triangles into two leaves at slots 2 and 3', () => {
    const bvh = buildBvh(scenes['two triangles']!());
    expect(bvh.nodeCount).toBe(4);
    expect(bvh.triCount[0]).toBe(0);
    expect(bvh.leftFirst[0]).toBe(2);
    expect([bvh.triCount[2], bvh.triCount[3]]).toEqual([1, 1]);
  });

  it('keeps identical triangles in one leaf unless maxLeafSize forces middle splits', () => {
    const copies = new Float32Array(Array.from({ length: 20 }, () => [0, 0, 0, 1, 0, 0, 0, 1, 0]).flat());
    const asLeaf = buildBvh(copies, { maxLeafSize: 32 });
    expect(asLeaf.triCount[0]).toBe(20);
    const split = buildBvh(copies, { maxLeafSize: 4 });
    checkBvh(split, copies);
    expect(Math.max(...bvhStats(split).leafSizeHistogram.map((n, size) => (n > 0 ? size : 0)))).toBeLessThanOrEqual(4);
  });

  it('never exceeds maxLeafSize when splits exist, and stops at maxDepth', () => {
    const positions = randomSoup(3000, 3);
    const bvh = buildBvh(positions, { maxLeafSize: 2, traversalCost: 100 });
    checkBvh(bvh, positions);
    expect(bvhStats(bvh).leafSizeHistogram.length).toBeLessThanOrEqual(3);
    const shallow = buildBvh(positions, { maxDepth: 3 });
    checkBvh(shallow, positions, 3);
    expect(shallow.stats.maxDepth).toBe(3);
  });

  it('respects bins and cost options', () => {
    const positions = uvSphere(16, 32);
    for (const bins of [2, 4, 64]) checkBvh(buildBvh(positions, { bins }), positions);
    // Expensive triangle tests make deeper trees with smaller leaves.
    const cheapTris = buildBvh(positions, { intersectionCost: 0.05 });
    const dearTris = buildBvh(positions, { intersectionCost: 20 });
    expect(dearTris.stats.leafCount).toBeGreaterThan(cheapTris.stats.leafCount);
  });

  it('gives a much better SAH cost than one leaf on a spread-out scene', () => {
    const positions = randomSoup(5000, 11);
    const { sahCost } = buildBvh(positions).stats;
    expect(sahCost).toBeLessThan(5000 / 20);
  });

  it('falls back to centroid bounds when every centroid lands in one bin of the node box', () => {
    // 40 big overlapping triangles whose centroids differ by < 0.02 inside a 100-wide box. Their
    // centroids sit at the box centre, which an odd bin count puts in the middle of a bin.
    const rnd = makeRandom(12);
    const tris: number[] = [];
    for (let k = 0; k < 40; k++) {
      const [a, b, c] = [rnd() * 0.01, rnd() * 0.01, rnd() * 0.01];
      tris.push(a, b, c, 100 + a, 100 + b, c, a, 100 + b, 100 + c);
    }
    const positions = new Float32Array(tris);
    const bvh = buildBvh(positions, { maxLeafSize: 4, bins: 15 });
    checkBvh(bvh, positions);
    expect(bvhStats(bvh).leafSizeHistogram.length).toBeLessThanOrEqual(5);
  });

  it('rejects zero triangles, malformed arrays, non-finite coordinates and bad options', () => {
    expect(() => buildBvh(new Float32Array(0))).toThrow(new LanternError('cannot build a BVH over zero triangles'));
    expect(() => buildBvh(new Float32Array(10))).toThrow(LanternError);
    const withNaN = randomSoup(10, 1);
    withNaN[40] = NaN;
    expect(() => buildBvh(withNaN)).toThrow(/triangle 4 has a non-finite/);
    const withInf = randomSoup(10, 1);
    withInf[0] = Infinity;
    expect(() => buildBvh(withInf)).toThrow(LanternError);
    for (const bad of [{ bins: 1 }, { bins: 2.5 }, { maxLeafSize: 0 }, { maxDepth: -1 }, { intersectionCost: 0 }, { traversalCost: NaN }]) {
      expect(() => buildBvh(randomSoup(10, 1), bad)).toThrow(LanternError);
    }
  });

  it('is deterministic', () => {
    const positions = randomSoup(2000, 5);
    const a = buildBvh(positions), b = buildBvh(positions);
    expect(a.bounds).toEqual(b.bounds);
    expect(a.triIndices).toEqual(b.triIndices);
    expect(a.leftFirst).toEqual(b.leftFirst);
  });
});
