import { describe, expect, it } from 'vitest';
import { PRIMITIVE_KIND, type TriangleList } from '../scene/triangles.ts';
import { DIFFUSE_OFFSET, diffuseRaysFromHits, type HitWords, type RayWords } from './benchmark-rays.ts';

// Ray: origin xyz, t_min, direction xyz, t_max (8 words); hit: t, triangle, u, v (4 words).
const RAY: RayWords = { stride: 8, origin: 0, direction: 4, tMin: 3, tMax: 7 };
const HIT: HitWords = { stride: 4, t: 0, triangle: 1 };
const NO_TRIANGLE = 0xffffffff;

/** One big triangle in the plane z = 0 (normal +z), and a sphere of radius 1 at (10, 0, 0). */
const triangles = {
  count: 2,
  positions: new Float32Array([-100, -100, 0, 100, -100, 0, 0, 100, 0, 10, 0, 0, 1, 0, 0, 0, 0, 0]),
  kinds: new Uint8Array([PRIMITIVE_KIND.triangle, PRIMITIVE_KIND.sphere]),
} as unknown as TriangleList;

function rays(list: { origin: number[]; direction: number[]; t: number; prim: number }[]) {
  const r = new Float32Array(list.length * RAY.stride), h = new ArrayBuffer(list.length * HIT.stride * 4);
  const hf = new Float32Array(h), hu = new Uint32Array(h);
  list.forEach((x, i) => {
    r.set(x.origin, i * RAY.stride + RAY.origin);
    r.set(x.direction, i * RAY.stride + RAY.direction);
    hf[i * HIT.stride + HIT.t] = x.t;
    hu[i * HIT.stride + HIT.triangle] = x.prim;
  });
  return { r, h };
}

describe('tinybvh diffuse rays', () => {
  it('makes one ray per hit, in order, from the hit point pushed along the normal facing the incoming ray', () => {
    const { r, h } = rays([
      { origin: [1, 2, 5], direction: [0, 0, -1], t: 5, prim: 0 }, // from above: normal +z
      { origin: [0, 0, 0], direction: [1, 0, 0], t: 1, prim: NO_TRIANGLE }, // a miss: no ray
      { origin: [3, 4, -2], direction: [0, 0, 1], t: 2, prim: 0 }, // from below: normal −z
      { origin: [10, 0, 5], direction: [0, 0, -1], t: 4, prim: 1 }, // the sphere's top: normal +z
    ]);
    const out = diffuseRaysFromHits(r, h, 4, triangles, 50, RAY, HIT);
    expect(out.count).toBe(3);
    const origin = (j: number) => Array.from(out.rays.subarray(j * RAY.stride, j * RAY.stride + 3));
    const direction = (j: number) => Array.from(out.rays.subarray(j * RAY.stride + 4, j * RAY.stride + 7));
    const eps = DIFFUSE_OFFSET * 50;
    expect(origin(0)[2]).toBeCloseTo(eps, 7);
    expect(origin(0).slice(0, 2)).toEqual([1, 2]);
    expect(origin(1)[2]).toBeCloseTo(-eps, 7);
    expect(origin(2)[2]).toBeCloseTo(1 + eps, 6);
    expect(direction(0)[2]).toBeGreaterThan(0);
    expect(direction(1)[2]).toBeLessThan(0);
    expect(direction(2)[2]).toBeGreaterThan(0);
    for (let j = 0; j < 3; j++) expect(Math.hypot(...direction(j))).toBeCloseTo(1, 6);
  });

  it('draws directions with the cosine distribution about the normal (E[cos] = 2/3, E[cos²] = 1/2), the same every run', () => {
    const n = 20000;
    const { r, h } = rays(Array.from({ length: n }, () => ({ origin: [0, 0, 1], direction: [0, 0, -1], t: 1, prim: 0 })));
    const out = diffuseRaysFromHits(r, h, n, triangles, 1, RAY, HIT);
    let c1 = 0, c2 = 0, sx = 0;
    for (let j = 0; j < n; j++) {
      const c = out.rays[j * RAY.stride + 6]!;
      c1 += c;
      c2 += c * c;
      sx += out.rays[j * RAY.stride + 4]!;
    }
    expect(c1 / n).toBeCloseTo(2 / 3, 2);
    expect(c2 / n).toBeCloseTo(1 / 2, 2);
    expect(Math.abs(sx / n)).toBeLessThan(0.02);
    expect(diffuseRaysFromHits(r, h, n, triangles, 1, RAY, HIT).rays).toEqual(out.rays);
  });
});
