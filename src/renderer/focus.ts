/**
 * Where a lens focuses when nobody says: the depth (along the camera's forward axis) of the first
 * surface the chief ray through the image centre meets, found on the CPU with the BVH oracle
 * (bvh/traverse.ts) over the prepared scene's world-space primitives (triangles, spheres, capsules). One ray: cheap on any scene.
 * Pure (no GPU), so the CLI and the page share it.
 */
import { traverseClosest } from '../bvh/traverse.ts';
import { normalize } from '../math/vec3.ts';
import type { Camera } from '../scene/types.ts';
import type { PreparedScene } from './prepare.ts';

/** Depth along forward of the surface at the image centre, or undefined when the centre ray leaves the scene. */
export function centreFocusDistance(prepared: PreparedScene, camera: Camera): number | undefined {
  const direction = normalize(camera.forward);
  const { positions, kinds } = prepared.triangles;
  const hit = traverseClosest(prepared.bvh, positions, { origin: camera.position, direction }, kinds);
  // The centre ray runs along the unit forward axis, so its distance is the depth.
  return hit?.t;
}
