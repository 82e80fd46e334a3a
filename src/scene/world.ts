/**
 * Plays a scene's dynamics (scene/dynamics.ts): a clock, the viewer's position, the player's actions
 * in, SceneUpdates out. The viewer advances it every frame it plays; `lantern render --time t`
 * evaluates it once at t. Each kind of motion is an Animator made by one module from the scene's
 * data; the World only keeps time and merges what they change. Pure: no DOM, no GPU.
 */
import type { Vec3 } from '../math/vec3.ts';
import { billboardAnimator } from './billboards.ts';
import { materialAnimator } from './material-animation.ts';
import { emptySceneUpdate, isEmptyUpdate, type InstancePose, type SceneUpdate } from './dynamics.ts';
import type { MaterialEdit } from './material-edit.ts';
import { moverAnimator } from './movers.ts';
import { pathAnimator } from './paths.ts';
import { pushWallAnimator } from './push-walls.ts';
import { slidingDoorAnimator } from './sliding-doors.ts';
import type { Scene } from './types.ts';

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
  /** The player pressed the use key at `view`; true when something answered (a door started to open). */
  use?(view: Viewpoint, t: number): boolean;
  /** The walker moved from (x0, z0) to (x1, z1) in the walk plane (walk-over triggers). */
  walked?(x0: number, z0: number, x1: number, z1: number, t: number): void;
}

/** Makes the animator of one kind of motion for `scene`, or undefined when the scene has none of it. */
export type AnimatorFactory = (scene: Scene) => Animator | undefined;

/** Every kind of motion (scene/dynamics.ts lists them), in the order their updates are merged. */
const ANIMATORS: readonly AnimatorFactory[] = [materialAnimator, moverAnimator, pathAnimator, billboardAnimator, slidingDoorAnimator, pushWallAnimator];

export class World {
  private time = 0;
  private stepped = false;

  private constructor(private readonly animators: readonly Animator[]) {}

  /** The world of `scene`, or undefined when nothing in it moves. */
  static of(scene: Scene, factories: readonly AnimatorFactory[] = ANIMATORS): World | undefined {
    if (!scene.dynamics) return undefined;
    const animators = factories.map((make) => make(scene)).filter((a): a is Animator => a !== undefined);
    return animators.length > 0 ? new World(animators) : undefined;
  }

  /** Seconds since the world started. */
  get seconds(): number {
    return this.time;
  }

  /** Advances the clock by `dt` seconds (0: only the view changed); undefined when nothing changed. */
  advance(dt: number, view: Viewpoint): SceneUpdate | undefined {
    if (!(dt >= 0) || !Number.isFinite(dt)) throw new RangeError(`World.advance: dt must be a finite number ≥ 0, got ${dt}`);
    const first = !this.stepped;
    this.time += dt;
    this.stepped = true;
    const out = new UpdateBuilder();
    for (const a of this.animators) a.step(this.time, first ? 0 : dt, view, out, first);
    const update = out.build();
    return isEmptyUpdate(update) ? undefined : update;
  }

  /**
   * Advances the clock to `t` (≥ seconds) in steps of at most `maxStep` seconds (movers integrate
   * their motion), returning everything that changed as one update (empty when nothing did).
   */
  advanceTo(t: number, view: Viewpoint, maxStep = 1 / 35): SceneUpdate {
    if (!(t >= this.time) || !Number.isFinite(t)) throw new RangeError(`World.advanceTo: ${t} is not a finite time at or after ${this.time}`);
    const updates: (SceneUpdate | undefined)[] = [];
    if (!this.stepped) updates.push(this.advance(0, view));
    const steps = Math.min(100_000, Math.ceil((t - this.time) / maxStep));
    const from = this.time;
    for (let i = 1; i <= steps; i++) updates.push(this.advance(from + ((t - from) * i) / steps - this.time, view));
    return mergeUpdates(updates);
  }

  /** The player pressed use; true when something answered. */
  use(view: Viewpoint): boolean {
    let answered = false;
    for (const a of this.animators) if (a.use?.(view, this.time)) answered = true;
    return answered;
  }

  /** The walker moved (walk-over triggers). */
  walked(x0: number, z0: number, x1: number, z1: number): void {
    for (const a of this.animators) a.walked?.(x0, z0, x1, z1, this.time);
  }
}

/** Merges updates in order (later ones win where they say the same thing). */
export function mergeUpdates(updates: readonly (SceneUpdate | undefined)[]): SceneUpdate {
  const merged = new UpdateBuilder();
  for (const u of updates) {
    if (!u) continue;
    for (const [k, v] of u.instances) merged.pose(k, v);
    for (const [k, v] of u.morphWeights) merged.morphWeights.set(k, v);
    for (const [k, v] of u.materials) merged.material(k, v);
    for (const [k, v] of u.walkHeights) merged.walkHeights.set(k, v);
  }
  return merged.build();
}

/**
 * The state of `scene` at `t` seconds seen from `view`, as one update from the scene as loaded (what
 * `lantern render --time` shows).
 */
export function sceneUpdateAt(scene: Scene, t: number, view: Viewpoint): SceneUpdate {
  return World.of(scene)?.advanceTo(t, view) ?? emptySceneUpdate();
}
