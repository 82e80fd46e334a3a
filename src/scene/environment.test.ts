/**
 * Lantern's lat-long convention pinned at the points docs/environment.md names, and the rotations it
 * gives for carrying a map to and from Mitsuba 3 and Blender, checked against those renderers' own
 * mappings as their sources write them (transcribed below; tests/gpu/environment.test.ts ties the
 * shader's environment_uv and rotation to these CPU functions).
 */
import { describe, expect, it } from 'vitest';
import type { Vec3 } from '../math/vec3.ts';
import { directionFromLatLong, latLongFromDirection } from './environment.ts';

const DEG = Math.PI / 180;

/** Lantern's map rotation (environment.wgsl, world_from_map): R_y(ρ), +z toward +x for ρ > 0. */
const rotateY = (d: Vec3, deg: number): Vec3 => {
  const [c, s] = [Math.cos(deg * DEG), Math.sin(deg * DEG)];
  return [d[0] * c + d[2] * s, d[1], -d[0] * s + d[2] * c];
};

/** The texel (u, v from the top row) a map turned by `rotationDeg` shows in world direction d. */
const lanternTexel = (d: Vec3, rotationDeg: number) => latLongFromDirection(rotateY(d, -rotationDeg));

/**
 * Mitsuba 3, src/emitters/envmap.cpp: eval looks up direction_to_uv(to_world⁻¹ · d) with
 * direction_to_uv(d) = (atan2(d.x, −d.z) / 2π, safe_acos(d.y) / π), u taken modulo 1; to_world =
 * rotate([0, 1, 0], α) is drjit's right-handed rotation (+z toward +x for α > 0).
 */
const mitsubaTexel = (d: Vec3, alphaDeg: number): [number, number] => {
  const local = rotateY(d, -alphaDeg);
  const u = Math.atan2(local[0], -local[2]) / (2 * Math.PI);
  return [u - Math.floor(u), Math.acos(local[1]) / Math.PI];
};

/**
 * Blender (Cycles kernel/camera/projection.h): direction_to_equirectangular(d) = (0.5 − atan2(d.y, d.x)
 * / 2π, 1 − acos(d.z) / π), v from the bottom row, +Z up; the world's Mapping node (Point) turns the
 * vector first: d → R_z(β) d. A Lantern scene exported from Blender as glTF (+Y up) has
 * (x, y, z)_Lantern = (x, z, −y)_Blender, so Blender's direction is (x, −z, y).
 */
const blenderTexel = (d: Vec3, betaDeg: number): [number, number] => {
  const b: Vec3 = [d[0], -d[2], d[1]];
  const [c, s] = [Math.cos(betaDeg * DEG), Math.sin(betaDeg * DEG)];
  const r: Vec3 = [b[0] * c - b[1] * s, b[0] * s + b[1] * c, b[2]];
  const u = 0.5 - Math.atan2(r[1], r[0]) / (2 * Math.PI);
  const vFromBottom = 1 - Math.acos(r[2]) / Math.PI;
  // Blender's images are stored bottom row first: the same file's v from its top row.
  return [u - Math.floor(u), 1 - vFromBottom];
};

/** Directions spread over the sphere, off the seam and the poles. */
function directions(n: number): Vec3[] {
  return Array.from({ length: n }, (_, i) => directionFromLatLong(((i * 0.618034) % 1) * 0.98 + 0.01, 0.05 + (0.9 * (i + 0.5)) / n));
}

/** Equal texels, u compared across the seam. */
function expectSameTexel(a: [number, number], b: [number, number]): void {
  const du = Math.abs(a[0] - b[0]);
  expect(Math.min(du, 1 - du)).toBeLessThan(1e-9);
  expect(a[1]).toBeCloseTo(b[1], 9);
}

describe("Lantern's lat-long convention", () => {
  it('u = 0 looks toward +z, 0.25 toward −x, 0.5 toward −z (the image centre), 0.75 toward +x; v = 0 is +y, v = 1 is −y', () => {
    const cases: [number, number, Vec3][] = [
      [0, 0.5, [0, 0, 1]],
      [0.25, 0.5, [-1, 0, 0]],
      [0.5, 0.5, [0, 0, -1]],
      [0.75, 0.5, [1, 0, 0]],
    ];
    for (const [u, v, d] of cases) {
      directionFromLatLong(u, v).forEach((x, k) => expect(x).toBeCloseTo(d[k]!, 12));
      const [uu, vv] = latLongFromDirection(d);
      expect(uu).toBeCloseTo(u, 12);
      expect(vv).toBeCloseTo(v, 12);
    }
    expect(latLongFromDirection([0, 1, 0])[1]).toBe(0);
    expect(latLongFromDirection([0, -1, 0])[1]).toBe(1);
    expect(directionFromLatLong(0.3, 0)[1]).toBeCloseTo(1, 12);
  });

  it('a rotation of 90° shows at +x what the map has toward +z (u = 0)', () => {
    expectSameTexel(lanternTexel([1, 0, 0], 90), [0, 0.5]);
  });
});

describe('carrying a map between Lantern, Mitsuba 3 and Blender (docs/environment.md)', () => {
  it('Mitsuba 3 envmap with to_world = rotate(+y, α) is Lantern --env-rotation α + 180', () => {
    for (const alpha of [0, 30, 90, -135]) for (const d of directions(200)) expectSameTexel(lanternTexel(d, alpha + 180), mitsubaTexel(d, alpha));
    // And not with the rotation the docs once implied (none): the two differ by half a turn.
    expect(Math.abs(lanternTexel([0, 0, -1], 0)[0] - mitsubaTexel([0, 0, -1], 0)[0])).toBeCloseTo(0.5, 12);
  });

  it("Blender's world texture with Mapping rotation Z = β, seen in its glTF export, is Lantern --env-rotation 270 − β", () => {
    for (const beta of [0, 45, 90, -60]) for (const d of directions(200)) expectSameTexel(lanternTexel(d, 270 - beta), blenderTexel(d, beta));
  });
});
