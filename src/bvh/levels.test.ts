import { describe, expect, it } from 'vitest';
import { makeRandom, movingTestScene } from './test-scenes.ts';
import { intersectAll } from './traverse.ts';
import { buildTlas } from './tlas.ts';
import { flattenTriangles } from '../scene/triangles.ts';
import { buildLevels, buildStaticBvh, traceScene } from './levels.ts';

describe('the top-level tree', () => {
  it('holds every instance with a box in exactly one leaf, under boxes that contain it', () => {
    const rnd = makeRandom(5);
    const n = 1000;
    const boxes = new Float32Array(n * 6);
    for (let i = 0; i < n; i++) {
      const x = rnd() * 100, y = rnd() * 10, z = rnd() * 100, s = rnd() * 2;
      boxes.set(i === 7 ? [1, 1, 1, 0, 0, 0] : [x, y, z, x + s, y + s, z + s], i * 6);
    }
    const t = buildTlas(boxes);
    const seen = new Map<number, number>();
    const walk = (node: number, parent: number) => {
      for (let c = 0; c < 3; c++) {
        expect(t.bounds[node * 6 + c]).toBeGreaterThanOrEqual(t.bounds[parent * 6 + c]!);
        expect(t.bounds[node * 6 + 3 + c]).toBeLessThanOrEqual(t.bounds[parent * 6 + 3 + c]!);
      }
      if (t.triCount[node]! > 0) {
        expect(t.triCount[node]).toBe(1);
        const i = t.leftFirst[node]!;
        seen.set(i, (seen.get(i) ?? 0) + 1);
        for (let c = 0; c < 6; c++) expect(t.bounds[node * 6 + c]).toBe(boxes[i * 6 + c]);
        return;
      }
      walk(t.leftFirst[node]!, node);
      walk(t.leftFirst[node]! + 1, node);
    };
    walk(0, 0);
    expect(seen.size).toBe(n - 1);
    expect([...seen.values()].every((c) => c === 1)).toBe(true);
    expect(seen.has(7)).toBe(false);
    expect(t.nodeCount).toBe(2 * (n - 1));
  });

  it('is an empty root without instances, and a leaf with one', () => {
    expect(buildTlas(new Float32Array()).triCount[0]).toBe(0);
    const one = buildTlas(new Float32Array([0, 0, 0, 1, 1, 1]));
    expect([one.triCount[0], one.leftFirst[0], one.nodeCount]).toEqual([1, 0, 2]);
  });
});

describe('two-level traversal (CPU oracle)', () => {
  it('finds the same closest hit as brute force over the flattened world, ray for ray', () => {
    const scene = movingTestScene();
    const triangles = flattenTriangles(scene);
    const staticBvh = buildStaticBvh(scene, triangles);
    const levels = buildLevels(scene, staticBvh)!;
    expect(levels.dynamic).toEqual([1, 2, 3]);
    expect(levels.blas.size).toBe(2);
    const rnd = makeRandom(9);
    let hits = 0;
    const byInstance = new Set<number>();
    for (let i = 0; i < 3000; i++) {
      const origin = [rnd() * 30 - 15, rnd() * 30 - 15, rnd() * 30 - 15] as const;
      const target = [rnd() * 12 - 6, rnd() * 8 - 4, rnd() * 12 - 6];
      const ray = { origin: [...origin] as [number, number, number], direction: [target[0]! - origin[0], target[1]! - origin[1], target[2]! - origin[2]] as [number, number, number] };
      const expected = intersectAll(triangles.positions, ray, triangles.kinds);
      const got = traceScene(scene, triangles, staticBvh, levels, ray);
      if (!expected) {
        expect(got).toBeNull();
        continue;
      }
      hits++;
      expect(got).not.toBeNull();
      expect(got!.t).toBeCloseTo(expected.t, 4);
      if (Math.abs(got!.t - expected.t) < 1e-7 * expected.t || got!.triangle === expected.triangle) {
        expect(got!.triangle).toBe(expected.triangle);
        if (triangles.kinds[expected.triangle] === 0) {
          expect(got!.u).toBeCloseTo(expected.u, 3);
          expect(got!.v).toBeCloseTo(expected.v, 3);
        }
      }
      byInstance.add(got!.instance);
    }
    expect(hits).toBeGreaterThan(500);
    expect([...byInstance].sort()).toEqual([0, 1, 2, 3]);
  });

  it('without moving instances is the single BVH over everything', () => {
    const scene = { ...movingTestScene(), instances: movingTestScene().instances.map((i) => ({ ...i, moves: false })) };
    const triangles = flattenTriangles(scene);
    const bvh = buildStaticBvh(scene, triangles);
    expect(buildLevels(scene, bvh)).toBeUndefined();
    expect(bvh.triIndices.length).toBe(triangles.count);
  });
});

describe('a scene where everything moves', () => {
  it('has an empty static world, and traces through the top level alone', () => {
    const moving = movingTestScene();
    const scene = { ...moving, instances: moving.instances.map((i) => ({ ...i, moves: true })) };
    const triangles = flattenTriangles(scene);
    const staticBvh = buildStaticBvh(scene, triangles);
    expect(staticBvh.triIndices.length).toBe(0);
    const levels = buildLevels(scene, staticBvh)!;
    expect(levels.dynamic.length).toBe(scene.instances.length);
    const rnd = makeRandom(4);
    for (let i = 0; i < 500; i++) {
      const origin: [number, number, number] = [rnd() * 30 - 15, rnd() * 30 - 15, 20];
      const ray = { origin, direction: [rnd() * 2 - 1 - origin[0] / 20, rnd() * 2 - 1 - origin[1] / 20, -1] as [number, number, number] };
      const expected = intersectAll(triangles.positions, ray, triangles.kinds);
      const got = traceScene(scene, triangles, staticBvh, levels, ray);
      expect(got?.t ?? null).toBe(expected ? got!.t : null);
      if (expected) expect(got!.t).toBeCloseTo(expected.t, 4);
    }
  });
});
