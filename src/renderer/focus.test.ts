import { describe, expect, it } from 'vitest';
import { placeEachOnce } from '../scene/instances.ts';
import type { Camera, Mesh, Scene } from '../scene/types.ts';
import { centreFocusDistance } from './focus.ts';
import { prepareScene } from './prepare.ts';

const camera: Camera = { position: [0, 0, 0], forward: [0, 0, 1], up: [0, 1, 0], vfovDegrees: 40 };

/** A sphere of radius 2 at z = 10 in front of a wall at z = 30 (two triangles). */
function sphereScene(): Scene {
  const mesh: Mesh = {
    name: 'sphere and wall',
    positions: new Float32Array([-50, -50, 30, -50, 50, 30, 50, 50, 30, 50, -50, 30]),
    indices: new Uint32Array([0, 1, 2, 0, 2, 3]),
    materialIds: new Uint32Array([0, 0]),
    spheres: { centers: new Float32Array([0, 0, 10]), radii: new Float32Array([2]), materialIds: new Uint32Array([0]) },
  };
  const meshes = [mesh];
  return { name: 'sphere', meshes, instances: placeEachOnce(meshes), materials: [{ kind: 'diffuse', name: 'grey', albedo: [0.5, 0.5, 0.5], emission: [0, 0, 0] }], camera };
}

describe('the focus distance at the image centre', () => {
  it('is the depth of the first primitive the centre ray meets, analytic spheres included', () => {
    const prepared = prepareScene(sphereScene());
    expect(centreFocusDistance(prepared, camera)).toBeCloseTo(8, 5);
    // Beside the sphere the wall is next; behind the camera nothing.
    expect(centreFocusDistance(prepared, { ...camera, position: [5, 0, 0] })).toBeCloseTo(30, 5);
    expect(centreFocusDistance(prepared, { ...camera, forward: [0, 0, -1] })).toBeUndefined();
  });
});
