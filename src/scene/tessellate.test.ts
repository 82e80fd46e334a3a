import { describe, expect, it } from 'vitest';
import { intersectCapsule, intersectSphere, prepareRay, T_MISS } from '../bvh/ray.ts';
import { tessellateAnalytic } from './tessellate.ts';
import type { Mesh } from './types.ts';

const mesh: Mesh = {
  name: 'shapes',
  positions: new Float32Array(0),
  indices: new Uint32Array(0),
  materialIds: new Uint32Array(0),
  spheres: { centers: new Float32Array([1, 2, 3]), radii: new Float32Array([0.5]), materialIds: new Uint32Array([4]) },
  capsules: { endpoints: new Float32Array([0, 0, 0, 1, 2, -1]), radii: new Float32Array([0.3]), materialIds: new Uint32Array([7]) },
};

describe('tessellateAnalytic', () => {
  const t = tessellateAnalytic(mesh, 32)!;
  const vertex = (i: number) => [t.positions[i * 3]!, t.positions[i * 3 + 1]!, t.positions[i * 3 + 2]!];

  it('puts every vertex on the surface with the analytic normal, and winds triangles outward', () => {
    const sdf = (p: number[]) => {
      const sphere = Math.hypot(p[0]! - 1, p[1]! - 2, p[2]! - 3) - 0.5;
      const h = Math.min(1, Math.max(0, (p[0]! * 1 + p[1]! * 2 + p[2]! * -1) / 6));
      const capsule = Math.hypot(p[0]! - h, p[1]! - 2 * h, p[2]! + h) - 0.3;
      return Math.min(Math.abs(sphere), Math.abs(capsule));
    };
    for (let i = 0; i < t.positions.length / 3; i++) expect(sdf(vertex(i))).toBeLessThan(1e-6);
    let outward = 0;
    for (let k = 0; k < t.indices.length / 3; k++) {
      const [a, b, c] = [0, 1, 2].map((j) => vertex(t.indices[k * 3 + j]!));
      const e1 = a!.map((x, j) => b![j]! - x), e2 = a!.map((x, j) => c![j]! - x);
      const n = [e1[1]! * e2[2]! - e1[2]! * e2[1]!, e1[2]! * e2[0]! - e1[0]! * e2[2]!, e1[0]! * e2[1]! - e1[1]! * e2[0]!];
      const vn = t.indices[k * 3]! * 3;
      if (n[0]! * t.normals![vn]! + n[1]! * t.normals![vn + 1]! + n[2]! * t.normals![vn + 2]! > 0) outward++;
    }
    expect(outward).toBe(t.indices.length / 3);
    expect(new Set(t.materialIds)).toEqual(new Set([4, 7]));
  });

  it('gives vertices the uv the ray tests report there', () => {
    const positions = new Float32Array([1, 2, 3, 0.5, 0, 0, 0, 0, 0, 0, 0, 0, 1, 2, -1, 0.3, 0, 0]);
    const out = { u: 0, v: 0 };
    let checked = 0;
    for (let i = 0; i < t.positions.length / 3; i++) {
      const u = t.uvs![i * 2]!, v = t.uvs![i * 2 + 1]!;
      // Seams (u = 0 or 1) and poles have more than one right answer.
      if (u < 0.01 || u > 0.99 || v < 0.01 || v > 0.99) continue;
      const p = vertex(i), n = [0, 1, 2].map((k) => t.normals![i * 3 + k]!);
      const origin = p.map((x, k) => x + 2 * n[k]!) as [number, number, number];
      const ray = prepareRay({ origin, direction: [-n[0]!, -n[1]!, -n[2]!] });
      const sphere = i < t.positions.length / 3 && Math.hypot(p[0]! - 1, p[1]! - 2, p[2]! - 3) < 0.5 + 1e-5;
      const hit = sphere ? intersectSphere(positions, 0, ray, 0, T_MISS, out) : intersectCapsule(positions, 1, ray, 0, T_MISS, out);
      expect(hit).toBeCloseTo(2, 4);
      expect(out.u).toBeCloseTo(u, 5);
      expect(out.v).toBeCloseTo(v, 5);
      checked++;
    }
    expect(checked).toBeGreaterThan(400);
  });

  it('returns nothing for a mesh without spheres or capsules', () => {
    expect(tessellateAnalytic({ ...mesh, spheres: undefined, capsules: undefined })).toBeUndefined();
  });
});
