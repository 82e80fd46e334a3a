import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../expect-lantern-error.ts';
import { determinant3, IDENTITY, transformPoint, type Mat4 } from '../math/mat4.ts';
import { cross, dot, sub, type Vec3 } from '../math/vec3.ts';
import { billboardPose, billboardQuad, facingYaw, rotationIndex } from './billboards.ts';
import type { Scene } from './types.ts';
import { validateScene } from './validate.ts';
import { billboardImage as image, twoBillboardScene } from '../../tests/fixtures/billboard-scene.ts';

const DEG = Math.PI / 180;
/** A viewer `d` units from `at` in the direction of map angle `deg` (0 east, 90 north = −z). */
const around = (at: Vec3, deg: number, d = 100): Vec3 => [at[0] + d * Math.cos(deg * DEG), at[1], at[2] - d * Math.sin(deg * DEG)];

describe('rotationIndex (R_ProjectSprite)', () => {
  const thing: Vec3 = [10, 0, -20];

  it.each([0, 1, 2, 3, 4, 5, 6, 7])('a thing facing east seen from %i × 45° counter-clockwise shows that rotation index', (k) => {
    expect(rotationIndex(0, around(thing, 45 * k), thing)).toBe(k);
  });

  it('turns with the thing: facing north, seen from the north is rotation 1, from the west rotation 3, from the south rotation 5', () => {
    expect(rotationIndex(90 * DEG, around(thing, 90), thing)).toBe(0);
    expect(rotationIndex(90 * DEG, around(thing, 180), thing)).toBe(2);
    expect(rotationIndex(90 * DEG, around(thing, 270), thing)).toBe(4);
    expect(rotationIndex(90 * DEG, around(thing, 0), thing)).toBe(6);
  });

  it('centres each 45° sector on its rotation: the boundaries lie at ±22.5°', () => {
    expect(rotationIndex(0, around(thing, 22.4), thing)).toBe(0);
    expect(rotationIndex(0, around(thing, 22.6), thing)).toBe(1);
    expect(rotationIndex(0, around(thing, -22.4), thing)).toBe(0);
    expect(rotationIndex(0, around(thing, -22.6), thing)).toBe(7);
    expect(rotationIndex(0, around(thing, 157.4), thing)).toBe(3);
    expect(rotationIndex(0, around(thing, 157.6), thing)).toBe(4);
  });

  it("agrees with Doom's binary-angle arithmetic, (ang − angle + ANG45/2·9) >> 29, over many positions and facings", () => {
    const ANG45 = 0x20000000;
    const bam = (radians: number) => Math.round((radians / (2 * Math.PI)) * 2 ** 32) >>> 0;
    let seed = 7;
    const next = () => ((seed = (seed * 1103515245 + 12345) >>> 0) / 2 ** 32);
    for (let i = 0; i < 2000; i++) {
      const facingDeg = 45 * Math.floor(next() * 8); // map things face multiples of 45°
      const viewer: Vec3 = [thing[0] + (next() - 0.5) * 2000, 41, thing[2] + (next() - 0.5) * 2000];
      // R_PointToAngle(thing.x, thing.y): from the viewer to the thing, in map coordinates (y = −z).
      const ang = Math.atan2(-(thing[2] - viewer[2]), thing[0] - viewer[0]);
      const doom = ((bam(ang) - bam(facingDeg * DEG) + (ANG45 / 2) * 9) >>> 0) >>> 29;
      expect(rotationIndex(facingDeg * DEG, viewer, thing)).toBe(doom);
    }
  });
});

/** The quad's two triangles in world space, with the winding a mirroring transform gets (scene/triangles.ts swaps v1 and v2). */
function worldTriangles(m: Mat4): [Vec3, Vec3, Vec3][] {
  const q = billboardQuad(0);
  const p = (i: number): Vec3 => transformPoint(m, [q.positions[3 * i]!, q.positions[3 * i + 1]!, q.positions[3 * i + 2]!]);
  const mirror = determinant3(m) < 0;
  const out: [Vec3, Vec3, Vec3][] = [];
  for (let t = 0; t < q.indices.length; t += 3) {
    const [a, b, c] = [q.indices[t]!, q.indices[t + 1]!, q.indices[t + 2]!];
    out.push(mirror ? [p(a), p(c), p(b)] : [p(a), p(b), p(c)]);
  }
  return out;
}


describe('billboardPose', () => {
  const foot: Vec3 = [300, 24, -500];

  it.each([
    ['north', [0, 0, -1]],
    ['south-west, looking down', [-1, -0.7, 1]],
    ['east', [1, 0, 0]],
  ] as const)('faces a viewer looking %s, normal against the view, spanning the picture around its origin', (_, forward) => {
    const viewer: Vec3 = sub(foot, [forward[0] * 200, -17, forward[2] * 200]);
    for (const mirrored of [false, true]) {
      const m = billboardPose(foot, image({ mirrored }), facingYaw(forward as Vec3)!);
      for (const [a, b, c] of worldTriangles(m)) {
        const n = cross(sub(b, a), sub(c, a));
        expect(dot(n, sub(viewer, foot))).toBeGreaterThan(0);
        // Parallel to the view plane: the normal is horizontal and along −forward.
        expect(Math.abs(n[1])).toBeLessThan(1e-9);
        expect(dot(n, [forward[0], 0, forward[2]])).toBeLessThan(0);
      }
      // The picture's top edge is `top` above the anchor, its bottom `height` below that; its left
      // edge `left` to the viewer's left of it, whichever way the columns run.
      const corners = [0, 1].flatMap((x) => [0, 1].map((y) => transformPoint(m, [x, y, 0])));
      const ys = corners.map((p) => p[1]);
      expect(Math.max(...ys)).toBeCloseTo(foot[1] + 57, 9);
      expect(Math.min(...ys)).toBeCloseTo(foot[1] + 57 - 60, 9);
      const right: Vec3 = [-forward[2], 0, forward[0]];
      const len = Math.hypot(right[0], right[2]);
      const along = corners.map((p) => dot(sub(p, foot), right) / len);
      expect(Math.min(...along)).toBeCloseTo(-15, 9);
      expect(Math.max(...along)).toBeCloseTo(25, 9);
      // Texture column 0 (object x = 0) is the picture's left edge, or its right edge when mirrored.
      expect(dot(sub(transformPoint(m, [0, 0, 0]), foot), right) / len).toBeCloseTo(mirrored ? 25 : -15, 9);
      expect(determinant3(m) < 0).toBe(mirrored);
    }
  });

  it('stands a picture whose top offset equals its height with its bottom row on the floor', () => {
    const m = billboardPose(foot, image({ top: 60 }), 0);
    expect(transformPoint(m, [0, 0, 0])[1]).toBe(foot[1]);
    expect(transformPoint(m, [1, 1, 0])[1]).toBe(foot[1] + 60);
  });

  it('has no facing when the viewer looks straight down', () => {
    expect(facingYaw([0, -1, 0])).toBeUndefined();
  });
});

describe('billboardProblem (validateScene)', () => {
  const { billboards, scene } = twoBillboardScene();

  it('refuses an instance that does not move, a material out of range, a cycle frame of no duration', () => {
    const placed: Scene = { ...scene, instances: [10, 11].map((id) => ({ id, mesh: 0, worldFromObject: IDENTITY, moves: true })) };
    expect(() => validateScene(placed)).not.toThrow();
    expectLanternError(() => validateScene({ ...placed, instances: placed.instances.map((i) => ({ ...i, moves: false })) }), /billboard 0 poses instance 10, which is not a moving instance/);
    const bad = { ...placed, dynamics: { billboards: [{ ...billboards[1]!, frames: [{ duration: 0, images: [image({ material: 99 })] }] }] } };
    expectLanternError(() => validateScene(bad), /billboard 0 shows material 99 of 10/);
    const still = { ...placed, dynamics: { billboards: [{ ...billboards[1]!, frames: [{ duration: 0, images: [image()] }, { duration: 0, images: [image()] }] }] } };
    expectLanternError(() => validateScene(still), /billboard 0 has a frame of no or infinite duration/);
  });
});
