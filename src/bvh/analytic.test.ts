/**
 * The sphere and capsule tests of bvh/ray.ts against an independent oracle: the shapes' signed
 * distance functions, marched along the ray. A reported hit must lie on the surface, and no point of
 * the ray before it may be inside (for rays from outside); a miss must never come close.
 */
import { describe, expect, it } from 'vitest';
import { seededRandom } from '../math/seeded-random.ts';
import { intersectCapsule, intersectSphere, prepareRay, T_MISS, type Barycentrics } from './ray.ts';
import { computeTriangleBoxes, f32Down, f32Up } from './triangle-boxes.ts';
import { PRIMITIVE_KIND } from '../scene/triangles.ts';

type V = [number, number, number];
const sub = (a: V, b: V): V => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const dot = (a: V, b: V) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const at = (o: V, d: V, t: number): V => [o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]];

const sphereSdf = (c: V, r: number) => (p: V) => Math.hypot(...sub(p, c)) - r;
const capsuleSdf = (a: V, b: V, r: number) => (p: V) => {
  const ab = sub(b, a), ap = sub(p, a);
  const len2 = dot(ab, ab);
  const h = len2 > 0 ? Math.min(1, Math.max(0, dot(ap, ab) / len2)) : 0;
  return Math.hypot(...sub(ap, [ab[0] * h, ab[1] * h, ab[2] * h])) - r;
};

/** The first t in (0, tEnd) where the SDF is <= 0 (to `step`), or Infinity. */
function march(sdf: (p: V) => number, o: V, d: V, tEnd: number): number {
  const len = Math.hypot(...d);
  let t = 0;
  for (let i = 0; i < 100000 && t < tEnd; i++) {
    const s = sdf(at(o, d, t));
    if (s <= 1e-9) return t;
    t += Math.max(s, 1e-7) / len;
  }
  return Infinity;
}

describe('intersectSphere and intersectCapsule', () => {
  const rnd = seededRandom(11);
  const out: Barycentrics = { u: 0, v: 0 };
  it('agree with sphere tracing of the signed distance, from outside and inside', () => {
    for (let i = 0; i < 2000; i++) {
      const capsule = i % 2 === 1;
      const c: V = [rnd() * 4 - 2, rnd() * 4 - 2, rnd() * 4 - 2];
      const b: V = i % 10 === 1 ? c : [c[0] + rnd() * 3 - 1.5, c[1] + rnd() * 3 - 1.5, c[2] + rnd() * 3 - 1.5];
      const r = 0.1 + rnd() * 1.5;
      const positions = capsule ? new Float32Array([...c, ...b, r, 0, 0]) : new Float32Array([...c, r, 0, 0, 0, 0, 0]);
      // Use the float32 values the test itself sees.
      const cf = [positions[0]!, positions[1]!, positions[2]!] as V, bf = [positions[3]!, positions[4]!, positions[5]!] as V, rf = positions[capsule ? 6 : 3]!;
      const sdf = capsule ? capsuleSdf(cf, bf, rf) : sphereSdf(cf, rf);
      const o: V = [rnd() * 10 - 5, rnd() * 10 - 5, rnd() * 10 - 5];
      const target: V = [cf[0] + rnd() * 2 - 1, cf[1] + rnd() * 2 - 1, cf[2] + rnd() * 2 - 1];
      const d = sub(target, o);
      const ray = prepareRay({ origin: o, direction: d });
      const t = (capsule ? intersectCapsule : intersectSphere)(positions, 0, ray, 0, T_MISS, out);
      const inside = sdf(o) < 0;
      if (t === T_MISS) {
        // No hit: from outside the ray never enters; from inside that cannot happen.
        expect(inside).toBe(false);
        expect(march(sdf, o, d, 100)).toBe(Infinity);
        continue;
      }
      expect(Math.abs(sdf(at(o, d, t)))).toBeLessThan(1e-9 * (1 + Math.hypot(...o)) * 1e3);
      if (!inside) {
        const first = march(sdf, o, d, t * 1.001 + 1e-6);
        expect(Math.abs(first - t) * Math.hypot(...d)).toBeLessThan(1e-5);
      } else {
        // From inside, the exit: every earlier sample is inside.
        for (let k = 1; k < 50; k++) expect(sdf(at(o, d, (t * k) / 50))).toBeLessThan(1e-9);
      }
      expect(out.u).toBeGreaterThanOrEqual(0);
      expect(out.u).toBeLessThan(1);
      expect(out.v).toBeGreaterThanOrEqual(0);
      expect(out.v).toBeLessThanOrEqual(1);
    }
  });

  it('keeps its precision on a sphere of radius 1000 seen from 10 units away (Ray Tracing Gems ch. 7)', () => {
    const positions = new Float32Array([0, -1000, 0, 1000, 0, 0, 0, 0, 0]);
    for (let i = 0; i < 200; i++) {
      const o: V = [13, 2, 3];
      const d: V = [-13 + (rnd() - 0.5) * 8, -2 - rnd() * 1.5, -3 + (rnd() - 0.5) * 8];
      const t = intersectSphere(positions, 0, prepareRay({ origin: o, direction: d }), 0, T_MISS, out);
      expect(t).not.toBe(T_MISS);
      const p = at(o, d, t);
      // |p − c| − r, formed without cancellation: (|p−c|² − r²) / (|p−c| + r).
      const q = sub(p, [0, -1000, 0]);
      expect(Math.abs((dot(q, q) - 1e6) / (Math.hypot(...q) + 1000))).toBeLessThan(1e-9);
    }
  });

  it('reports sphere uv as scene/shapes.ts uvSphere lays it out', () => {
    const positions = new Float32Array([0, 0, 0, 1, 0, 0, 0, 0, 0]);
    const hitFrom = (o: V) => {
      intersectSphere(positions, 0, prepareRay({ origin: o, direction: [-o[0], -o[1], -o[2]] }), 0, T_MISS, out);
      return [out.u, out.v];
    };
    expect(hitFrom([0, 0, 5])).toEqual([0, 0.5]);
    expect(hitFrom([5, 0, 0])[0]).toBeCloseTo(0.25, 12);
    expect(hitFrom([0, 5, 0])[1]).toBeCloseTo(0, 12);
    expect(hitFrom([0, -5, 0])[1]).toBeCloseTo(1, 12);
  });
});

describe('primitive boxes', () => {
  it('contain spheres and capsules, rounded outward to float32', () => {
    const positions = new Float32Array([0.1, 0.2, 0.3, 0.7, 0, 0, 0, 0, 0, 1, 2, 3, -1, 5, 2, 0.3, 0, 0]);
    const boxes = computeTriangleBoxes(positions, new Uint8Array([PRIMITIVE_KIND.sphere, PRIMITIVE_KIND.capsule]));
    const c = [positions[0]!, positions[1]!, positions[2]!], r = positions[3]!;
    for (let a = 0; a < 3; a++) {
      expect(boxes[a]!).toBeLessThanOrEqual(c[a]! - r);
      expect(boxes[3 + a]!).toBeGreaterThanOrEqual(c[a]! + r);
    }
    expect(Array.from(boxes.slice(6))).toEqual([f32Down(-1 - positions[15]!), f32Down(2 - positions[15]!), f32Down(2 - positions[15]!), f32Up(1 + positions[15]!), f32Up(5 + positions[15]!), f32Up(3 + positions[15]!)]);
    expect(() => computeTriangleBoxes(new Float32Array([0, 0, 0, -1, 0, 0, 0, 0, 0]), new Uint8Array([PRIMITIVE_KIND.sphere]))).toThrow(/radius -1/);
  });
});
