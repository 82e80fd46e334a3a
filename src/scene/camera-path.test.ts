import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../expect-lantern-error.ts';
import { cameraAt, frameTime, parseCameraPath } from './camera-path.ts';
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
});
