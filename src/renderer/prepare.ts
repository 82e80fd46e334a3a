/**
 * Everything between a loaded Scene and GPU upload that runs on the CPU: validation, flattening,
 * BVH build and packing. Pure (no GPU, no DOM), so it can run in a worker; the Renderer uploads the
 * result.
 */
import { buildBvh } from '../bvh/build.ts';
import type { Bvh } from '../bvh/types.ts';
import { packScene, type PackedScene } from '../gpu/pack/scene-pack.ts';
import { flattenTriangles, type TriangleList } from '../scene/triangles.ts';
import type { Scene } from '../scene/types.ts';
import { validateScene } from '../scene/validate.ts';

export interface PreparedScene {
  readonly scene: Scene;
  readonly triangles: TriangleList;
  readonly bvh: Bvh;
  readonly packed: PackedScene;
  /** Milliseconds spent in each CPU stage. */
  readonly timings: { readonly flattenMs: number; readonly bvhMs: number; readonly packMs: number };
}

export function prepareScene(scene: Scene): PreparedScene {
  validateScene(scene);
  const t0 = performance.now();
  const triangles = flattenTriangles(scene);
  const t1 = performance.now();
  const bvh = buildBvh(triangles.positions);
  const t2 = performance.now();
  const packed = packScene(scene, triangles, bvh);
  const t3 = performance.now();
  return { scene, triangles, bvh, packed, timings: { flattenMs: t1 - t0, bvhMs: t2 - t1, packMs: t3 - t2 } };
}
