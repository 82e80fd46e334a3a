/**
 * What one step of a moving world changes, as data: the records world/world.ts writes as it plays a
 * scene's dynamics (scene/dynamics-types.ts, Scene.dynamics) and the renderer applies. Pure.
 */
import type { Mat4 } from '../math/mat4.ts';
import type { MaterialEdit } from './material-edit.ts';

/** An instance's new state: a transform, a material override (Instance.material), or both. */
export interface InstancePose {
  readonly worldFromObject?: Mat4;
  readonly material?: number;
}

/**
 * One step of a moving world: everything that changed since the previous step. The renderer applies
 * it (Renderer.applySceneUpdate): instances move in the top-level BVH, morphed meshes are refitted,
 * materials are repacked; the viewer applies `walkHeights` to the walk map.
 */
export interface SceneUpdate {
  /** By Instance.id. */
  readonly instances: ReadonlyMap<number, InstancePose>;
  /** By mesh index: one weight per Mesh.morphTargets entry (positions = base + Σ weight · delta). */
  readonly morphWeights: ReadonlyMap<number, Float32Array>;
  /** By material index. */
  readonly materials: ReadonlyMap<number, MaterialEdit>;
  /** By walk-map sector: [floor, ceiling] heights. */
  readonly walkHeights: ReadonlyMap<number, readonly [number, number]>;
}

export function emptySceneUpdate(): SceneUpdate {
  return { instances: new Map(), morphWeights: new Map(), materials: new Map(), walkHeights: new Map() };
}

export function isEmptyUpdate(u: SceneUpdate): boolean {
  return u.instances.size + u.morphWeights.size + u.materials.size + u.walkHeights.size === 0;
}
