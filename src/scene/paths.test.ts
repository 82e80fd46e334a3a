import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../expect-lantern-error.ts';
import { IDENTITY, transformDirection, transformPoint, type Mat4 } from '../math/mat4.ts';
import { length, sub, type Vec3 } from '../math/vec3.ts';
import type { InstancePath } from './dynamics-types.ts';
import { CompiledPath, compilePaths } from './paths.ts';
import { floorSquare } from './shapes.ts';
import { diffuse, type Scene } from './types.ts';

const SQUARE: Vec3[] = [[0, 0, 0], [10, 0, 0], [10, 0, 10], [0, 0, 10]];

function sceneWith(paths: InstancePath[], moves = true): Scene {
  return {
    name: 'carried',
    meshes: [floorSquare('thing', 1, 0, 0)],
    instances: [{ id: 7, mesh: 0, worldFromObject: IDENTITY, moves }],
    materials: [diffuse('grey', [0.5, 0.5, 0.5])],
    camera: { position: [0, 5, 20], forward: [0, 0, -1], up: [0, 1, 0], vfovDegrees: 60 },
    dynamics: { paths },
  };
}

const origin = (m: Mat4): Vec3 => transformPoint(m, [0, 0, 0]);

describe('paths', () => {
  it('a polyline square is 40 long and is walked at the given speed, corner to corner', () => {
    const p = new CompiledPath({ instance: 7, points: SQUARE, curve: 'polyline', speed: 4, faceMotion: false });
    expect(p.length).toBeCloseTo(40, 9);
    expect(p.lapSeconds).toBeCloseTo(10, 9);
    // 2.5 s at 4 units/s: the second corner; 3.75 s: halfway down the second side.
    expect(origin(p.poseAt(2.5))).toEqual([expect.closeTo(10, 9), 0, expect.closeTo(0, 9)]);
    expect(origin(p.poseAt(3.75))).toEqual([expect.closeTo(10, 9), 0, expect.closeTo(5, 9)]);
    expect(origin(p.poseAt(-2.5))).toEqual([expect.closeTo(0, 9), 0, expect.closeTo(10, 9)]);
  });

  it('a Catmull–Rom loop passes through every point, at constant speed', () => {
    const p = new CompiledPath({ instance: 7, points: SQUARE, speed: 2 });
    // It passes through each point: the closest sample along the loop comes within a hair of it.
    for (const q of SQUARE) {
      let best = Infinity;
      for (let i = 0; i < 4000; i++) best = Math.min(best, length(sub(p.positionAt((i / 4000) * p.length), q)));
      expect(best).toBeLessThan(p.length / 4000);
    }
    // Equal times, equal arc: chords over 1/200 of a lap differ by little (the chord under-measures
    // the arc by at most its curvature's sagitta).
    const chords: number[] = [];
    for (let i = 0; i < 200; i++) chords.push(length(sub(origin(p.poseAt(((i + 1) * p.lapSeconds) / 200)), origin(p.poseAt((i * p.lapSeconds) / 200)))));
    const expected = p.length / 200;
    for (const c of chords) expect(Math.abs(c - expected) / expected).toBeLessThan(0.01);
  });

  it('the pose is continuous and a lap is its period, bob included', () => {
    const p = new CompiledPath({ instance: 7, points: SQUARE, speed: 3, offset: 2.5, bob: { amplitude: 0.3, perLap: 5 } });
    const dt = 1e-4;
    let worstStep = 0;
    for (let i = 0; i < 2000; i++) {
      const t = (i / 2000) * p.lapSeconds * 1.3;
      const a = p.poseAt(t), b = p.poseAt(t + dt);
      worstStep = Math.max(worstStep, ...a.map((v, k) => Math.abs(v - b[k]!)));
      const c = p.poseAt(t + p.lapSeconds);
      for (let k = 0; k < 16; k++) expect(c[k]!).toBeCloseTo(a[k]!, 6);
    }
    // Position moves by speed·dt plus the bob's share; the rotation turns by at most the curvature's.
    expect(worstStep).toBeLessThan(5 * 3 * dt);
    expect(worstStep).toBeGreaterThan(0);
  });

  it('turns object +z along the motion with object +y up, a rotation', () => {
    const p = new CompiledPath({ instance: 7, points: SQUARE, curve: 'polyline', speed: 1 });
    const m = p.poseAt(5); // halfway along the first side, moving +x
    const z = transformDirection(m, [0, 0, 1]), y = transformDirection(m, [0, 1, 0]), x = transformDirection(m, [1, 0, 0]);
    expect(z.map((v) => +v.toFixed(9))).toEqual([1, 0, 0]);
    expect(y.map((v) => +v.toFixed(9))).toEqual([0, 1, 0]);
    expect(x.map((v) => +v.toFixed(9))).toEqual([0, 0, -1]);
  });

  it('refuses bad paths with a message naming the problem', () => {
    expectLanternError(() => compilePaths(sceneWith([{ instance: 3, points: SQUARE, speed: 1 }])), /path 0 carries instance 3, which the scene does not have/);
    expectLanternError(() => compilePaths(sceneWith([{ instance: 7, points: SQUARE, speed: 1 }], false)), /moves: true/);
    expectLanternError(() => compilePaths(sceneWith([{ instance: 7, points: SQUARE.slice(0, 2), speed: 1 }])), /at least 3/);
    expectLanternError(() => compilePaths(sceneWith([{ instance: 7, points: [...SQUARE, [0, 0, 0]], speed: 1 }])), /points 4 and 0 are equal/);
    expectLanternError(() => compilePaths(sceneWith([{ instance: 7, points: SQUARE, speed: 0 }])), /speed/);
    expectLanternError(() => compilePaths(sceneWith([{ instance: 7, points: SQUARE, speed: 1, bob: { amplitude: 1, perLap: 2.5 } }])), /whole number/);
    expect(compilePaths(sceneWith([]))).toEqual([]);
  });
});
