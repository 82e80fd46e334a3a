/**
 * What an animator is to the World (world/world.ts): one kind of motion of Scene.dynamics, made from
 * the scene's data, stepped to a time seen from a viewpoint, writing what changed into an
 * UpdateBuilder. Apart from world.ts so that the animators of world/ and the World that composes them
 * import it, not each other. Pure.
 */
import type { Vec3 } from '../math/vec3.ts';
import type { InstancePose, SceneUpdate } from '../scene/dynamics.ts';
import type { MaterialEdit } from '../scene/material-edit.ts';
import type { Scene } from '../scene/types.ts';

/** Where the scene is seen from: billboards turn toward it; the use key acts in front of it. */
export interface Viewpoint {
  readonly position: Vec3;
  /** Need not be unit length. */
  readonly forward: Vec3;
  /**
   * A player walks (the viewer's walk mode): what a demo does by itself waits for the player's use
   * key (Wolfenstein's doors). Absent: a camera flies or follows a path (renders, fly mode).
   */
  readonly walking?: boolean;
}

/** The mutable SceneUpdate animators write into during one step (later writes win). */
export class UpdateBuilder {
  readonly instances = new Map<number, InstancePose>();
  readonly morphWeights = new Map<number, Float32Array>();
  readonly materials = new Map<number, MaterialEdit>();
  readonly walkHeights = new Map<number, readonly [number, number]>();

  /** Merges a pose into what this step already says about the instance. */
  pose(instanceId: number, pose: InstancePose): void {
    this.instances.set(instanceId, { ...this.instances.get(instanceId), ...pose });
  }

  /** Merges an edit into what this step already says about the material. */
  material(index: number, edit: MaterialEdit): void {
    this.materials.set(index, { ...this.materials.get(index), ...edit });
  }

  build(): SceneUpdate {
    return { instances: this.instances, morphWeights: this.morphWeights, materials: this.materials, walkHeights: this.walkHeights };
  }
}

/** One kind of motion, made from one field of Scene.dynamics. */
export interface Animator {
  /**
   * Brings the animator to time `t` (seconds since the world started; `dt` since the previous step,
   * 0 on the first), seen from `view`, writing into `out` only what changed since its previous step
   * (everything on the first step, `first` true).
   */
  step(t: number, dt: number, view: Viewpoint, out: UpdateBuilder, first: boolean): void;
  /**
   * Present on animators whose state integrates over time and meets the walker on the way (doors,
   * lifts, push walls): whether a step seen from `view` would change anything. While it says so the
   * World steps it at every tick; otherwise its ticks are skipped, which changes nothing (a world at
   * rest costs no ticks, however long the frame or far the --time). Animators without it are pure
   * functions of the time and the view, stepped once at the last tick of each advance.
   */
  moving?(view: Viewpoint): boolean;
  /** The player pressed the use key at `view`; true when something answered (a door started to open). */
  use?(view: Viewpoint, t: number): boolean;
  /** The walker moved from (x0, z0) to (x1, z1) in the walk plane (walk-over triggers). */
  walked?(x0: number, z0: number, x1: number, z1: number, t: number): void;
}

/** Makes the animator of one kind of motion for `scene`, or undefined when the scene has none of it. */
export type AnimatorFactory = (scene: Scene) => Animator | undefined;
