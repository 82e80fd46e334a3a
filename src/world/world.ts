/**
 * Plays a scene's dynamics (Scene.dynamics, scene/dynamics-types.ts): a clock, the viewer's
 * position, the player's actions in, SceneUpdates (scene/dynamics.ts) out. The viewer advances it
 * every frame it plays, by the frame's real time; `lantern render --time t` brings it to t once,
 * frame mode frame by frame. Each kind of motion is an Animator made by one module of world/ from the
 * scene's data; the World only keeps time and merges what they change. Pure: no DOM, no GPU.
 *
 * Time runs in whole ticks of 1/TICKS_PER_SECOND s, whatever the frames: an advance by dt moves the
 * clock by dt and the world to the tick nearest the clock. Animators whose state integrates over
 * time (doors, lifts, push walls: Animator.moving) step once a tick while something of theirs
 * moves; the others are functions of the time and the view and step once, at the advance's last
 * tick. So the world after one 3 s frame is the world after ninety 1/30 s frames, exactly, and
 * `render --time t` shows what the viewer shows at t.
 */
import { emptySceneUpdate, isEmptyUpdate, type SceneUpdate } from '../scene/dynamics.ts';
import type { Scene } from '../scene/types.ts';
import { UpdateBuilder, type Animator, type AnimatorFactory, type Viewpoint } from './animator.ts';
import { billboardAnimator } from './billboards.ts';
import { materialAnimator } from './material-animation.ts';
import { moverAnimator } from './movers.ts';
import { pathAnimator } from './paths.ts';
import { pushWallAnimator } from './push-walls.ts';
import { slidingDoorAnimator } from './sliding-doors.ts';

/** Every kind of motion (scene/dynamics-types.ts lists them), in the order their updates are merged. */
const ANIMATORS: readonly AnimatorFactory[] = [materialAnimator, moverAnimator, pathAnimator, billboardAnimator, slidingDoorAnimator, pushWallAnimator];

/**
 * The world's ticks per second: a multiple of Doom's 35 and Wolfenstein's 70 tics a second and of the
 * common frame rates (24, 30, 60, 120), so their frames and tics fall on whole ticks; fine enough
 * (1.2 ms) that a phantom stepped at the nearest tick moves smoothly at any display rate.
 */
export const TICKS_PER_SECOND = 840;
const TICK = 1 / TICKS_PER_SECOND;

export class World {
  /** Seconds given by advance and advanceTo (the world shows the tick nearest it). */
  private clock = 0;
  /** Ticks stepped. */
  private ticks = 0;
  private stepped = false;
  /** The animators with Animator.moving, stepped tick by tick, and the others, stepped once an advance. */
  private readonly everyTick: readonly Animator[];
  private readonly once: readonly Animator[];

  private constructor(private readonly animators: readonly Animator[]) {
    this.everyTick = animators.filter((a) => a.moving);
    this.once = animators.filter((a) => !a.moving);
  }

  /** The world of `scene`, or undefined when nothing in it moves. */
  static of(scene: Scene, factories: readonly AnimatorFactory[] = ANIMATORS): World | undefined {
    if (!scene.dynamics) return undefined;
    const animators = factories.map((make) => make(scene)).filter((a): a is Animator => a !== undefined);
    return animators.length > 0 ? new World(animators) : undefined;
  }

  /** Seconds since the world started (the sum of the advances). */
  get seconds(): number {
    return this.clock;
  }

  /** The time the animators are at: the last tick stepped. */
  private get now(): number {
    // A quotient of whole numbers: tick 2520 is 3 s exactly (2520 · (1/840) is not).
    return this.ticks / TICKS_PER_SECOND;
  }

  /** Advances the clock by `dt` seconds (0: only the view changed); undefined when nothing changed. */
  advance(dt: number, view: Viewpoint): SceneUpdate | undefined {
    if (!(dt >= 0) || !Number.isFinite(dt)) throw new RangeError(`World.advance: dt must be a finite number ≥ 0, got ${dt}`);
    this.clock += dt;
    const update = this.stepTo(Math.round(this.clock * TICKS_PER_SECOND), view);
    return isEmptyUpdate(update) ? undefined : update;
  }

  /** Advances the clock to `t` (≥ seconds), returning everything that changed as one update (empty when nothing did). */
  advanceTo(t: number, view: Viewpoint): SceneUpdate {
    if (!(t >= this.clock) || !Number.isFinite(t)) throw new RangeError(`World.advanceTo: ${t} is not a finite time at or after ${this.clock}`);
    this.clock = t;
    return this.stepTo(Math.round(t * TICKS_PER_SECOND), view);
  }

  /** Steps the animators to tick `target` (the integrating ones tick by tick while they move, the others once). */
  private stepTo(target: number, view: Viewpoint): SceneUpdate {
    const out = new UpdateBuilder();
    const from = this.ticks;
    if (!this.stepped) {
      this.stepped = true;
      for (const a of this.animators) a.step(this.now, 0, view, out, true);
    }
    let busy = this.everyTick.filter((a) => a.moving!(view));
    for (let k = from + 1; k <= target && busy.length > 0; k++) {
      for (const a of busy) a.step(k / TICKS_PER_SECOND, TICK, view, out, false);
      busy = busy.filter((a) => a.moving!(view));
    }
    this.ticks = Math.max(from, target);
    for (const a of this.once) a.step(this.now, (this.ticks - from) / TICKS_PER_SECOND, view, out, false);
    return out.build();
  }

  /** The player pressed use; true when something answered. */
  use(view: Viewpoint): boolean {
    let answered = false;
    for (const a of this.animators) if (a.use?.(view, this.now)) answered = true;
    return answered;
  }

  /** The walker moved (walk-over triggers). */
  walked(x0: number, z0: number, x1: number, z1: number): void {
    for (const a of this.animators) a.walked?.(x0, z0, x1, z1, this.now);
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
