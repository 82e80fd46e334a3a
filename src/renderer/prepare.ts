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

/** The CPU stages of preparation, in order, for progress reports. */
export const PREPARE_STAGES = ['flattening triangles', 'building the BVH', 'packing for the GPU'] as const;

/** Prepares `scene`; `onStage` hears of each stage as it begins (a worker reports progress with it). */
export function prepareScene(scene: Scene, onStage?: (stage: (typeof PREPARE_STAGES)[number]) => void): PreparedScene {
  validateScene(scene);
  const t0 = performance.now();
  onStage?.(PREPARE_STAGES[0]);
  const triangles = flattenTriangles(scene);
  const t1 = performance.now();
  onStage?.(PREPARE_STAGES[1]);
  const bvh = buildBvh(triangles.positions);
  const t2 = performance.now();
  onStage?.(PREPARE_STAGES[2]);
  const packed = packScene(scene, triangles, bvh);
  const t3 = performance.now();
  return { scene, triangles, bvh, packed, timings: { flattenMs: t1 - t0, bvhMs: t2 - t1, packMs: t3 - t2 } };
}
