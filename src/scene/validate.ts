/**
 * Checks the invariants of a Scene after a loader built it, so every later stage (BVH, GPU packing)
 * can rely on them. Throws a LanternError naming the first broken invariant.
 */
import { LanternError } from '../errors.ts';
import { cross, isFiniteVec3, length, type Vec3 } from '../math/vec3.ts';
import type { Scene } from './types.ts';

export function validateScene(scene: Scene): void {
  const fail = (what: string): never => {
    throw new LanternError(`scene '${scene.name}' is invalid: ${what}`);
  };
  if (scene.materials.length === 0) fail('it has no materials');
  scene.materials.forEach((m, i) => {
    if (!isFiniteVec3(m.albedo) || m.albedo.some((c) => c < 0 || c > 1)) {
      fail(`material ${i} ('${m.name}') has albedo ${m.albedo.join(', ')} outside [0, 1]`);
    }
    if (!isFiniteVec3(m.emission) || m.emission.some((c) => c < 0)) {
      fail(`material ${i} ('${m.name}') has a negative or non-finite emission`);
    }
  });
  let triangles = 0;
  scene.meshes.forEach((mesh, mi) => {
    const where = `mesh ${mi} ('${mesh.name}')`;
    const vertexCount = mesh.positions.length / 3;
    if (!Number.isInteger(vertexCount)) fail(`${where} has a position array whose length is not a multiple of 3`);
    if (mesh.indices.length % 3 !== 0) fail(`${where} has an index array whose length is not a multiple of 3`);
    const triCount = mesh.indices.length / 3;
    if (mesh.materialIds.length !== triCount) {
      fail(`${where} has ${mesh.materialIds.length} material ids for ${triCount} triangles`);
    }
    if (mesh.normals && mesh.normals.length !== mesh.positions.length) fail(`${where} has ${mesh.normals.length / 3} normals for ${vertexCount} vertices`);
    if (mesh.uvs && mesh.uvs.length !== vertexCount * 2) fail(`${where} has ${mesh.uvs.length / 2} uvs for ${vertexCount} vertices`);
    for (let i = 0; i < mesh.positions.length; i++) {
      if (!Number.isFinite(mesh.positions[i]!)) fail(`${where} has a non-finite position at vertex ${Math.floor(i / 3)}`);
    }
    for (let i = 0; i < mesh.indices.length; i++) {
      if (mesh.indices[i]! >= vertexCount) fail(`${where} triangle ${Math.floor(i / 3)} refers to vertex ${mesh.indices[i]} of ${vertexCount}`);
    }
    for (let t = 0; t < triCount; t++) {
      if (mesh.materialIds[t]! >= scene.materials.length) fail(`${where} triangle ${t} uses material ${mesh.materialIds[t]} of ${scene.materials.length}`);
    }
    triangles += triCount;
  });
  if (triangles === 0) fail('it has no triangles');
  const c = scene.camera;
  if (!isFiniteVec3(c.position)) fail('the camera position is not finite');
  if (!(length(c.forward) > 0) || !isFiniteVec3(c.forward)) fail('the camera forward vector is zero or not finite');
  const side: Vec3 = cross(c.forward, c.up);
  if (!(length(side) > 1e-9 * length(c.forward) * length(c.up))) fail('the camera up vector is zero or parallel to forward');
  if (!(c.vfovDegrees > 0 && c.vfovDegrees < 180)) fail(`the camera field of view ${c.vfovDegrees}° is outside (0, 180)`);
  if (c.exposureStops !== undefined && !(Math.abs(c.exposureStops) <= 64)) fail(`the camera exposure ${c.exposureStops} stops is outside ±64`);
}
