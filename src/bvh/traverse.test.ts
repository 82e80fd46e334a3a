import { describe, expect, it } from 'vitest';
import { buildBvh } from './build.ts';
import { intersectTriangle, prepareRay, T_MISS, type Ray } from './ray.ts';
import { degenerateSoup, makeRandom, quadGrid, randomSoup, testRays, uvSphere } from './test-scenes.ts';
import { intersectAll, traceClosest, traverseAny, traverseClosest } from './traverse.ts';

const scenes: Record<string, () => Float32Array> = {
  'random soup': () => randomSoup(5000, 2),
  'quad grid': () => quadGrid(30),
  'uv sphere': () => uvSphere(24, 48, 3),
  'degenerate soup': degenerateSoup,
  'huge coordinates': () => randomSoup(1500, 9, 1e37),
};


describe('traverseClosest against brute force', () => {
  for (const [name, make] of Object.entries(scenes)) {
    it(`agrees on hits, t and triangle: ${name}`, () => {
      const positions = make();
      const bvh = buildBvh(positions);
      const rays = testRays(positions, 3000, 42);
      let hits = 0, ties = 0;
      for (const ray of rays) {
        const oracle = intersectAll(positions, ray);
        const trace = traceClosest(bvh, positions, ray);
        const got = trace.hit;
        expect(got === null, `hit/miss for ray ${JSON.stringify(ray)}`).toBe(oracle === null);
        expect(trace.nodesVisited).toBeGreaterThanOrEqual(1);
        if (!got || !oracle) continue;
        hits++;
        expect(Math.abs(got.t - oracle.t)).toBeLessThanOrEqual(1e-9 * Math.abs(oracle.t));
        expect(bvh.triIndices[got.leafIndex]).toBe(got.triangle);
        expect(got.trianglesTested).toBeGreaterThanOrEqual(1);
        if (got.triangle !== oracle.triangle) {
          // A tie: a shared edge or vertex, or coincident copies. The BVH's triangle must really be
          // hit at its t, which (checked above) equals the oracle's up to rounding. Rounding can also
          // make the BVH skip the oracle's triangle: its box entry distance, rounded up, is not below
          // the other triangle's t, rounded down, when the hit lies on the box's face.
          const t = intersectTriangle(positions, got.triangle, prepareRay(ray), ray.tMin ?? 0, T_MISS, { u: 0, v: 0 });
          expect(t).toBe(got.t);
          ties++;
        } else {
          expect(got.t).toBe(oracle.t);
          expect([got.u, got.v]).toEqual([oracle.u, oracle.v]);
        }
      }
      expect(hits).toBeGreaterThan(rays.length / 4);
      // Ties are rare, except among the degenerate soup's 300 coincident copies.
      if (name !== 'degenerate soup') expect(ties).toBeLessThan(hits / 100);
    });
  }

  it('counts one visited node and no triangle tests for a ray that misses the root box', () => {
    const positions = quadGrid(4);
    const bvh = buildBvh(positions);
    const trace = traceClosest(bvh, positions, { origin: [-5, -5, 1], direction: [-1, 0, 0] });
    expect(trace).toEqual({ hit: null, nodesVisited: 1, trianglesTested: 0 });
  });

  it('reports work counts for rays that enter the root box but hit nothing', () => {
    const positions = uvSphere(8, 16);
    const bvh = buildBvh(positions);
    const trace = traceClosest(bvh, positions, { origin: [0, 0, 0], direction: [1, 0, 0], tMax: 0.5 });
    expect(trace.hit).toBeNull();
    expect(trace.nodesVisited).toBeGreaterThan(1);
  });

  it('finds the first of a stack of parallel quads and tests fewer triangles than exist', () => {
    const layers: number[] = [];
    for (let z = 0; z < 100; z++) layers.push(0, 0, z, 1, 0, z, 0, 1, z);
    const positions = new Float32Array(layers);
    const bvh = buildBvh(positions);
    const hit = traverseClosest(bvh, positions, { origin: [0.2, 0.2, 200], direction: [0, 0, -1] });
    expect(hit?.triangle).toBe(99);
    expect(hit?.t).toBe(101);
    expect(hit!.trianglesTested).toBeLessThan(20);
  });
});

describe('traverseAny', () => {
  for (const [name, make] of Object.entries(scenes)) {
    it(`reports a hit exactly when a closest hit exists in (tMin, tMax): ${name}`, () => {
      const positions = make();
      const bvh = buildBvh(positions);
      const rnd = makeRandom(7);
      for (const base of testRays(positions, 1500, 99)) {
        const closest = traverseClosest(bvh, positions, base);
        // Shorten some rays to just before / after the closest hit, as shadow rays do.
        const ray: Ray = closest && rnd() < 0.5 ? { ...base, tMax: closest.t * (rnd() < 0.5 ? 0.999 : 1.001) } : base;
        const expected = traverseClosest(bvh, positions, ray) !== null;
        const any = traverseAny(bvh, positions, ray);
        expect(any.hit).toBe(expected);
        expect(any.nodesVisited).toBeGreaterThanOrEqual(1);
      }
    });
  }
});
