import { describe, expect, it } from 'vitest';
import { intersectAll, traverseClosest } from '../bvh/traverse.ts';
import { checkBvh } from '../bvh/validate.ts';
import { fromTrs, translation } from '../math/mat4.ts';
import { uvSphere } from '../scene/shapes.ts';
import { diffuse, type Scene } from '../scene/types.ts';
import { GEOMETRY_BUFFERS, moveInstances, prepareScene, updateGeometry } from './prepare.ts';
import { traceScene } from '../bvh/levels.ts';

/** Two unit spheres (one mesh, two instances) and an emissive one, in a row along x. */
function spheres(): Scene {
  return {
    name: 'spheres',
    meshes: [uvSphere('sphere', 1, 24, 12)],
    instances: [
      { id: 10, mesh: 0, worldFromObject: translation([-3, 0, 0]) },
      { id: 11, mesh: 0, worldFromObject: translation([0, 0, 0]) },
      { id: 12, mesh: 0, worldFromObject: translation([3, 0, 0]), material: 1 },
    ],
    materials: [diffuse('grey', [0.5, 0.5, 0.5]), diffuse('lamp', [0, 0, 0], [4, 4, 4])],
    camera: { position: [0, 0, 10], forward: [0, 0, -1], up: [0, 1, 0], vfovDegrees: 40 },
  };
}

describe('moveInstances', () => {
  it('refits the BVH so that it stays exact and finds the moved instance where it now is', () => {
    const prepared = prepareScene(spheres());
    const moved = moveInstances(prepared, new Map([[11, fromTrs([0, 5, 0], [0, 0, 0, 1], [2, 2, 2])]]));
    // Every box is again the exact union of its triangles (checkBvh's invariant).
    checkBvh(moved.bvh, moved.triangles.positions);
    // A ray down the y axis from above now meets the moved sphere's top (y = 5 + 2), not the old one.
    const ray = { origin: [0, 20, 0] as const, direction: [0, -1, 0] as const };
    const hit = traverseClosest(moved.bvh, moved.triangles.positions, ray);
    const brute = intersectAll(moved.triangles.positions, ray);
    expect(hit?.t).toBeCloseTo(brute!.t, 6);
    expect(hit!.t).toBeGreaterThan(12.9);
    expect(hit!.t).toBeLessThan(13.1);
    // Where the sphere was, a horizontal ray now passes through to the others (or nothing).
    const through = traverseClosest(moved.bvh, moved.triangles.positions, { origin: [0, 0, 10], direction: [0, 0, -1] });
    expect(through).toBeNull();
    // Only the geometry buffers change, and they keep their sizes (written in place on the GPU).
    for (const name of GEOMETRY_BUFFERS) expect(moved.packed[name].byteLength).toBe(prepared.packed[name].byteLength);
    expect(moved.packed.materials).toBe(prepared.packed.materials);
    expect(moved.scene.instances.find((i) => i.id === 11)!.worldFromObject[13]).toBe(5);
  });

  it('keeps light selection consistent when an emitter is scaled', () => {
    const prepared = prepareScene(spheres());
    const moved = moveInstances(prepared, new Map([[12, fromTrs([3, 0, 0], [0, 0, 0, 1], [2, 2, 2])]]));
    // The emitter's area grew fourfold, and so did the power the light table normalises by.
    expect(moved.packed.totalLightPower / prepared.packed.totalLightPower).toBeCloseTo(4, 3);
  });

  it('moves a moving instance in the top level only: the static world and its records stay, the instance is found where it now is', () => {
    const scene = spheres();
    const movingScene = { ...scene, instances: scene.instances.map((i) => (i.id === 11 ? { ...i, moves: true } : i)) };
    const prepared = prepareScene(movingScene);
    expect(prepared.levels?.dynamic).toEqual([1]);
    const { prepared: moved, writes, attributes } = updateGeometry(prepared, new Map([[11, { worldFromObject: fromTrs([0, 5, 0], [0, 0, 0, 1], [2, 2, 2]) }]]), new Map());
    expect(attributes).toBe(false);
    expect(writes.map((w) => w.name).sort()).toEqual(['bvh_nodes', 'instances']);
    const nodeWrite = writes.find((w) => w.name === 'bvh_nodes')!;
    expect(nodeWrite.offset).toBe(prepared.packed.layout.tlasBase * 32);
    expect(moved.bvh).toBe(prepared.bvh);
    const ray = { origin: [0, 20, 0] as [number, number, number], direction: [0, -1, 0] as [number, number, number] };
    const hit = traceScene(moved.scene, moved.triangles, moved.bvh, moved.levels, ray);
    expect(hit!.t).toBeGreaterThan(12.9);
    expect(hit!.t).toBeLessThan(13.1);
    expect(hit!.instance).toBe(1);
    expect(hit!.t).toBeCloseTo(intersectAll(moved.triangles.positions, ray)!.t, 5);
  });

  it('refuses an unknown instance id', () => {
    expect(() => moveInstances(prepareScene(spheres()), new Map([[99, translation([0, 0, 0])]]))).toThrow(/no instance with id 99/);
  });
});
