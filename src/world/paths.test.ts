/** world/paths.ts: the animator writes each carried instance's pose at t, and nothing while time stands still. */
import { describe, expect, it } from 'vitest';
import { IDENTITY } from '../math/mat4.ts';
import type { Vec3 } from '../math/vec3.ts';
import type { InstancePath } from '../scene/dynamics-types.ts';
import { CompiledPath } from '../scene/paths.ts';
import { floorSquare } from '../scene/shapes.ts';
import { diffuse, type Scene } from '../scene/types.ts';
import { pathAnimator } from './paths.ts';
import { sceneUpdateAt, World } from './world.ts';

const SQUARE: Vec3[] = [[0, 0, 0], [10, 0, 0], [10, 0, 10], [0, 0, 10]];

function sceneWith(paths: InstancePath[]): Scene {
  return {
    name: 'carried',
    meshes: [floorSquare('thing', 1, 0, 0)],
    instances: [{ id: 7, mesh: 0, worldFromObject: IDENTITY, moves: true }],
    materials: [diffuse('grey', [0.5, 0.5, 0.5])],
    camera: { position: [0, 5, 20], forward: [0, 0, -1], up: [0, 1, 0], vfovDegrees: 60 },
    dynamics: { paths },
  };
}

const VIEW = { position: [0, 0, 0] as Vec3, forward: [0, 0, -1] as Vec3 };

describe('the path animator', () => {
  it('the World writes the pose at t (the same whatever the steps), and nothing when time stands still', () => {
    const path: InstancePath = { instance: 7, points: SQUARE, speed: 2, bob: { amplitude: 0.1, perLap: 2 } };
    const scene = sceneWith([path]);
    const expected = new CompiledPath(path).poseAt(3.3);
    const direct = sceneUpdateAt(scene, 3.3, VIEW).instances.get(7)!.worldFromObject!;
    for (let k = 0; k < 16; k++) expect(direct[k]!).toBeCloseTo(expected[k]!, 9);
    const world = World.of(scene)!;
    expect(world.advance(0, VIEW)?.instances.get(7)).toBeDefined();
    expect(world.advance(0, VIEW)).toBeUndefined();
    for (let i = 0; i < 33; i++) world.advance(0.1, VIEW);
    const stepped = world.advance(0, VIEW);
    expect(stepped).toBeUndefined();
    expect(world.seconds).toBeCloseTo(3.3, 9);
  });

  it('is made only for a scene with paths', () => {
    expect(pathAnimator(sceneWith([]))).toBeUndefined();
  });
});
