import { describe, expect, it } from 'vitest';
import { cross, dot, sub, type Vec3 } from '../../math/vec3.ts';
import { flattenTriangles } from '../../scene/triangles.ts';
import { validateScene } from '../../scene/validate.ts';
import { builtinScene, builtinSceneNames } from './index.ts';
import { furnaceRadiance } from './furnace.ts';
import { CORNELL_LIGHT_EMISSION } from './cornell.ts';
import { LanternError } from '../../errors.ts';

function triangles(name: string) {
  const scene = builtinScene(name);
  const list = flattenTriangles(scene);
  const tri = (t: number): [Vec3, Vec3, Vec3] => {
    const p = list.positions;
    const v = (c: number): Vec3 => [p[t * 9 + c * 3]!, p[t * 9 + c * 3 + 1]!, p[t * 9 + c * 3 + 2]!];
    return [v(0), v(1), v(2)];
  };
  const normal = (t: number): Vec3 => {
    const [a, b, c] = tri(t);
    return cross(sub(b, a), sub(c, a));
  };
  return { scene, list, tri, normal };
}

describe('built-in scenes', () => {
  it.each(builtinSceneNames())('%s passes validation', (name) => {
    expect(() => validateScene(builtinScene(name))).not.toThrow();
  });

  it('rejects an unknown name with the list of known ones', () => {
    const error = (() => {
      try {
        builtinScene('cornel');
      } catch (e) {
        return e;
      }
    })();
    expect(error).toBeInstanceOf(LanternError);
    expect((error as LanternError).userMessage).toMatch(/unknown scene 'cornel'.*cornell/);
  });

  it('furnace: every face emits toward the inside of the cube', () => {
    const { list, tri, normal } = triangles('furnace');
    expect(list.count).toBe(12);
    for (let t = 0; t < list.count; t++) {
      const [a, b, c] = tri(t);
      const centroid: Vec3 = [(a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3, (a[2] + b[2] + c[2]) / 3];
      expect(dot(normal(t), sub([0, 0, 0], centroid))).toBeGreaterThan(0);
    }
  });

  it('furnace: the bounce-limited analytic answer is the partial geometric series', () => {
    expect(furnaceRadiance(0)).toBeCloseTo(1, 12);
    expect(furnaceRadiance(2)).toBeCloseTo(1 + 0.8 + 0.64, 12);
    expect(furnaceRadiance(Infinity)).toBeCloseTo(5, 12);
  });

  it('cornell: 32 triangles, one downward-facing light of the published size and height', () => {
    const { scene, list, tri, normal } = triangles('cornell');
    expect(list.count).toBe(32);
    const lightMaterial = scene.materials.findIndex((m) => m.emission.some((e) => e > 0));
    expect(scene.materials[lightMaterial]!.emission).toEqual(CORNELL_LIGHT_EMISSION);
    const lights = [...list.materialIds.keys()].filter((t) => list.materialIds[t] === lightMaterial);
    expect(lights).toHaveLength(2);
    let area = 0;
    for (const t of lights) {
      const n = normal(t);
      expect(n[1]).toBeLessThan(0);
      expect(Math.abs(n[0]) + Math.abs(n[2])).toBe(0);
      area += Math.hypot(...n) / 2;
      for (const v of tri(t)) expect(v[1]).toBeCloseTo(548.7, 4);
    }
    expect(area).toBeCloseTo(130 * 105, 6);
  });

  it('cornell: the red wall is at x ≈ 550 and the green wall at x = 0', () => {
    const { scene, list, tri } = triangles('cornell');
    const wallX = (name: string) => {
      const m = scene.materials.findIndex((mat) => mat.name === name);
      const xs = [...list.materialIds.keys()].filter((t) => list.materialIds[t] === m).flatMap((t) => tri(t).map((v) => v[0]));
      return [Math.min(...xs), Math.max(...xs)];
    };
    expect(wallX('green')).toEqual([0, 0]);
    const [lo, hi] = wallX('red');
    expect(lo).toBeGreaterThanOrEqual(549.5); // 549.6 as float32
    expect(hi).toBeLessThanOrEqual(556.0);
  });
});
