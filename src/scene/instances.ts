/** Instances for scenes whose meshes are already in world space (built-in boxes, Doom maps, PLY): each mesh placed once, untransformed. */
import { IDENTITY } from '../math/mat4.ts';
import type { Instance, Mesh } from './types.ts';

export function placeEachOnce(meshes: readonly Mesh[], firstId = 0): Instance[] {
  return meshes.map((mesh, i) => ({ id: firstId + i, name: mesh.name, mesh: i, worldFromObject: IDENTITY }));
}
