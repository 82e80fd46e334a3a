import { describe, expect, it } from 'vitest';
import { INV_DIR_EPSILON, intersectAabb, intersectTriangle, prepareRay, safeInverse, T_MISS, type Barycentrics } from './ray.ts';

const unitBox = new Float32Array([0, 0, 0, 1, 1, 1]);
const triangle = new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0]); // in z = 0, counter-clockwise seen from +z

describe('safeInverse', () => {
  it('inverts ordinary components and clamps near-zero ones to ±1/epsilon, treating -0 as positive', () => {
    expect(safeInverse(2)).toBe(0.5);
    expect(safeInverse(-4)).toBe(-0.25);
    expect(safeInverse(0)).toBe(1 / INV_DIR_EPSILON);
    expect(safeInverse(-0)).toBe(1 / INV_DIR_EPSILON);
    expect(safeInverse(1e-20)).toBe(1 / INV_DIR_EPSILON);
    expect(safeInverse(-1e-20)).toBe(-1 / INV_DIR_EPSILON);
    expect(Number.isFinite(safeInverse(0))).toBe(true);
  });
});

describe('intersectAabb', () => {
  it('returns the entry distance, negative from inside, and T_MISS behind, beside or beyond tBest', () => {
    const hit = (o: [number, number, number], d: [number, number, number], tBest = T_MISS) => intersectAabb(unitBox, 0, prepareRay({ origin: o, direction: d }), tBest);
    expect(hit([-1, 0.5, 0.5], [1, 0, 0])).toBe(1);
    expect(hit([-1, 0.5, 0.5], [2, 0, 0])).toBe(0.5);
    expect(hit([0.5, 0.5, 0.5], [1, 0, 0])).toBe(-0.5);
    expect(hit([2, 0.5, 0.5], [1, 0, 0])).toBe(T_MISS);
    expect(hit([-1, 2, 0.5], [1, 0, 0])).toBe(T_MISS);
    expect(hit([-1, 0.5, 0.5], [1, 0, 0], 1)).toBe(T_MISS);
    expect(hit([-1, 0.5, 0.5], [1, 0, 0], 1.0001)).toBe(1);
    // A zero direction component acts as +1e-12, so an axis-parallel ray lying in a box face
    // enters through the min face but leaves the max face's slab at t = 0 (the GPU does the same).
    expect(hit([-1, 0, 0.5], [1, 0, 0])).toBe(1);
    expect(hit([-1, 0, 0.5], [1, -0, 0])).toBe(1);
    expect(hit([-1, 1, 0.5], [1, 0, 0])).toBe(T_MISS);
  });

  it('handles flat boxes (zero thickness) like the GPU', () => {
    const flat = new Float32Array([0, 0, 0, 1, 1, 0]);
    expect(intersectAabb(flat, 0, prepareRay({ origin: [0.5, 0.5, 2], direction: [0, 0, -1] }), T_MISS)).toBe(2);
    expect(intersectAabb(flat, 0, prepareRay({ origin: [0.5, 0.5, 2], direction: [1, 0, 0] }), T_MISS)).toBe(T_MISS);
  });
});

describe('intersectTriangle', () => {
  const bary: Barycentrics = { u: -1, v: -1 };
  const cast = (o: [number, number, number], d: [number, number, number], tMin = 0, tBest = T_MISS) => intersectTriangle(triangle, 0, prepareRay({ origin: o, direction: d }), tMin, tBest, bary);

  it('hits from either side and reports the barycentrics of v1 and v2', () => {
    expect(cast([0.25, 0.5, 2], [0, 0, -1])).toBe(2);
    expect(bary.u).toBeCloseTo(0.25, 15);
    expect(bary.v).toBeCloseTo(0.5, 15);
    expect(cast([0.25, 0.5, -3], [0, 0, 2])).toBe(1.5);
  });

  it('misses outside the triangle, parallel to it, behind tMin and at or beyond tBest', () => {
    expect(cast([0.75, 0.75, 2], [0, 0, -1])).toBe(T_MISS);
    expect(cast([-0.1, 0.5, 2], [0, 0, -1])).toBe(T_MISS);
    expect(cast([0.25, 0.25, 1], [1, 0, 0])).toBe(T_MISS);
    expect(cast([0.25, 0.25, 2], [0, 0, 1])).toBe(T_MISS);
    expect(cast([0.25, 0.25, 2], [0, 0, -1], 2)).toBe(T_MISS);
    expect(cast([0.25, 0.25, 2], [0, 0, -1], 1.9, 2)).toBe(T_MISS);
    expect(cast([0.25, 0.25, 2], [0, 0, -1], 1.9, 2.1)).toBe(2);
  });

  it('includes the edges and vertices (u, v >= 0, u + v <= 1)', () => {
    expect(cast([0, 0, 1], [0, 0, -1])).toBe(1);
    expect(cast([1, 0, 1], [0, 0, -1])).toBe(1);
    expect(cast([0.5, 0.5, 1], [0, 0, -1])).toBe(1);
  });

  it('never hits a zero-area triangle', () => {
    const point = new Float32Array(9).fill(1);
    expect(intersectTriangle(point, 0, prepareRay({ origin: [1, 1, 3], direction: [0, 0, -1] }), 0, T_MISS, bary)).toBe(T_MISS);
  });
});
