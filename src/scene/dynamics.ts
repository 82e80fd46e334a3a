/**
 * What moves in a scene, as data: the part of the model that says how instances, meshes, materials
 * and the walk map change with time, with the viewer's position and with the player's actions. A
 * loader describes it (Doom's things, animated textures, doors and lifts; the dungeon's phantom);
 * scene/world.ts plays it. Data only (no functions), so a scene built in a worker crosses to the page
 * by structured clone. Pure.
 *
 * Each kind of motion is one field, played by one module of scene/ (its "animator"):
 * - billboards (scene/billboards.ts): quads turned toward the viewer, their texture chosen by the
 *   angle between the thing's facing and the view (Doom's sprites);
 * - materialAnimations (scene/material-animation.ts): texture cycles, scrolling textures and
 *   emission patterns (Doom's animated flats and walls, scrolling walls, flickering sectors);
 * - movers (scene/movers.ts): doors and lifts, moving a sector's floor or ceiling by mesh morph
 *   weights, opened by the use key or by walking over a line;
 * - paths (scene/paths.ts): instances carried along a closed path (the dungeon's phantom);
 * - slidingDoors (scene/sliding-doors.ts): panels sliding sideways into the wall, opened by the use
 *   key or by standing in front of them (Wolfenstein's doors);
 * - pushWalls (scene/push-walls.ts): wall blocks pushed away by the use key (Wolfenstein's secrets).
 */
import type { Mat4 } from '../math/mat4.ts';
import type { Billboard } from './billboards.ts';
import type { MaterialAnimations } from './material-animation.ts';
import type { MaterialEdit } from './material-edit.ts';
import type { MoverSet } from './movers.ts';
import type { InstancePath } from './paths.ts';
import type { PushWallSet } from './push-walls.ts';
import type { SlidingDoorSet } from './sliding-doors.ts';

/**
 * The dynamic parts of a scene. Every field is optional; a scene without `dynamics` is frozen. Each
 * animator module owns its field's type and adds the field here:
 *   billboards (scene/billboards.ts), materialAnimations (scene/material-animation.ts),
 *   movers (scene/movers.ts), paths (scene/paths.ts).
 */
export interface SceneDynamics {
  /** Texture cycles, uv scrolls and emission patterns (scene/material-animation.ts). */
  readonly materialAnimations?: MaterialAnimations;
  /** Doors and lifts. */
  readonly movers?: MoverSet;
  /** Instances carried along closed paths (scene/paths.ts). */
  readonly paths?: readonly InstancePath[];
  /** Quads turned toward the viewer, showing the image for the angle they are seen from (Doom's things). */
  readonly billboards?: readonly Billboard[];
  /** Wolfenstein's doors (scene/sliding-doors.ts). */
  readonly slidingDoors?: SlidingDoorSet;
  /** Wolfenstein's push walls (scene/push-walls.ts). */
  readonly pushWalls?: PushWallSet;
}

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
