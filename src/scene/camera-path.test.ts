import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../expect-lantern-error.ts';
import { cross, length, type Vec3 } from '../math/vec3.ts';
import { cameraAt, frameTime, parseCameraPath, uprightFor } from './camera-path.ts';
import type { Camera } from './types.ts';

const base: Camera = { position: [0, 0, 0], forward: [0, 0, 1], up: [0, 1, 0], vfovDegrees: 40, exposureStops: 1 };
const path = parseCameraPath({
  keyframes: [
    { time: 0, position: [0, 0, 0], target: [0, 0, 10], fov: 30 },
    { time: 2, position: [4, 0, 0], target: [4, 0, 10] },
    { time: 3, position: [4, 2, 0], target: [4, 2, 10], fov: 60 },
  ],
});

describe('camera paths', () => {
  it('interpolates position, target and field of view linearly between keyframes', () => {
    const c = cameraAt(path, 1, base);
    expect(c.position).toEqual([2, 0, 0]);
    expect(c.forward).toEqual([0, 0, 10]);
    expect(c.vfovDegrees).toBeCloseTo(35); // 30 → the base camera's 40
    const d = cameraAt(path, 2.5, base);
    expect(d.position).toEqual([4, 1, 0]);
    expect(d.vfovDegrees).toBeCloseTo(50);
    expect(d.up).toEqual([0, 1, 0]);
    expect(d.exposureStops).toBe(1);
  });

  it('holds the end keyframes outside the path and spaces frames evenly', () => {
    expect(cameraAt(path, -5, base).position).toEqual([0, 0, 0]);
    expect(cameraAt(path, 99, base).position).toEqual([4, 2, 0]);
    expect([0, 1, 2, 3].map((i) => frameTime(path, i, 4))).toEqual([0, 1, 2, 3]);
    expect(frameTime(path, 0, 1)).toBe(0);
    expect(cameraAt(parseCameraPath({ keyframes: [{ time: 1, position: [1, 1, 1], target: [0, 0, 0] }] }), 7, base).position).toEqual([1, 1, 1]);
  });

  it('refuses malformed paths with a message naming the keyframe', () => {
    expectLanternError(() => parseCameraPath({}), /non-empty "keyframes"/);
    expectLanternError(() => parseCameraPath({ keyframes: [{ time: 0, position: [0, 0], target: [0, 0, 1] }] }), /keyframe 0: "position"/);
    expectLanternError(() => parseCameraPath({ keyframes: [{ time: 1, position: [0, 0, 0], target: [0, 0, 1] }, { time: 1, position: [0, 0, 0], target: [0, 0, 1] }] }), /keyframe 1: times must increase/);
    expectLanternError(() => parseCameraPath({ keyframes: [{ time: 0, position: [0, 0, 0], target: [0, 0, 0] }] }), /same point/);
    expectLanternError(() => parseCameraPath({ keyframes: [{ time: 0, position: [0, 0, 0], target: [0, 0, 1], fov: 200 }] }), /fov/);
  });

  it('gives a keyframe looking straight up or down an up vector it does not look along', () => {
    const vertical = parseCameraPath({
      keyframes: [
        { time: 0, position: [0, 0, 0], target: [0, 10, 0] },
        { time: 1, position: [0, 0, 0], target: [10, 0, 0] },
        { time: 2, position: [0, 0, 0], target: [0, -10, 0] },
      ],
    });
    const sideways = (forward: Vec3, up: Vec3) => length(cross(forward, up)) / (length(forward) * length(up));
    for (const t of [0, 2]) {
      const c = cameraAt(vertical, t, base);
      expect(sideways(c.forward, c.up), `t = ${t}`).toBeCloseTo(1, 9);
    }
    // Where the base camera's up works, it is kept.
    expect(cameraAt(vertical, 1, base).up).toEqual([0, 1, 0]);
    expect(uprightFor([0, 0, 5], [1, 0, 0])).toEqual([1, 0, 0]);
    expect(uprightFor([1, 0, 0], [1, 0, 0])).toEqual([0, 1, 0]);
    expect(uprightFor([0, -3, 0])).toEqual([0, 0, -1]);
  });

  it('refuses coordinates too large to subtract, and a segment whose camera passes through its target', () => {
    expectLanternError(() => parseCameraPath({ keyframes: [{ time: 0, position: [1e308, 0, 0], target: [-1e308, 0, 0] }] }), /keyframe 0: "position" must be three numbers from -10000000/);
    expectLanternError(() => parseCameraPath({ keyframes: [{ time: 0, position: [0, 0, 0], target: [0, 0, 2e7] }] }), /keyframe 0: "target"/);
    // Position and target trade places: halfway, the camera stands on its target.
    expectLanternError(
      () => parseCameraPath({ keyframes: [{ time: 0, position: [0, 0, 0], target: [0, 0, 1] }, { time: 1, position: [0, 0, 1], target: [0, 0, 0] }] }),
      /between keyframes 0 and 1 the camera passes through its target/,
    );
    // So does turning round on the spot, where the target sweeps through the camera.
    expectLanternError(() => parseCameraPath({ keyframes: [{ time: 0, position: [0, 0, 0], target: [0, 0, 1] }, { time: 1, position: [0, 0, 0], target: [0, 0, -1] }] }), /passes through/);
    // A quarter turn never reaches the target.
    expect(() => parseCameraPath({ keyframes: [{ time: 0, position: [0, 0, 0], target: [0, 0, 1] }, { time: 1, position: [5, 0, 1], target: [6, 0, 1] }] })).not.toThrow();
  });
});
