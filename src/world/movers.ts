/**
 * Movers: sectors whose floor or ceiling moves (Doom's doors and lifts), and the animator that plays
 * them (their data, MoverSet, is in scene/dynamics-types.ts). Each mover is one mesh with two morph
 * targets, the displacement per unit of its floor height and per unit of its ceiling height, so the
 * heights become morph weights (height − rest height); its walk-map sector gets the same heights. Triggers start them: use lines
 * (the use key, in front of the player) and walk-over lines. The behaviours follow vanilla Doom's
 * door and platform thinkers (p_doors.c T_VerticalDoor, EV_VerticalDoor; p_plats.c T_PlatRaise),
 * in seconds instead of tics; the World steps them at its ticks (world/world.ts). Pure.
 */
import { moverKindOf, type MoverSet, type MoverTrigger } from '../scene/dynamics-types.ts';
import { NO_SECTOR, type WalkMap } from '../scene/walk-map.ts';
import type { AnimatorFactory, Animator, UpdateBuilder, Viewpoint } from './animator.ts';

type Phase = 'up' | 'down' | 'waiting';

/** A mover in motion (Doom: the sector's thinker). */
interface Motion {
  readonly trigger: MoverTrigger;
  phase: Phase;
  /** Seconds left to wait. */
  waitLeft: number;
  /** Where the moving plane goes when it goes up. */
  top: number;
  /** When it started (it moves only from then on). */
  readonly since: number;
}

/** The state of all movers; exported for tests that drive it without a World. */
export class MoverAnimator implements Animator {
  readonly floors: number[];
  readonly ceilings: number[];
  private readonly motions = new Map<number, Motion>();
  private readonly spent = new Set<number>();
  private readonly dirty = new Set<number>();
  private view?: Viewpoint;
  /** Mover index by walk-map sector. */
  private readonly moverOfSector: Map<number, number>;

  /** With a walk map, walls and shut openings between the player and a use line stop the use key. */
  constructor(readonly set: MoverSet, private readonly walkMap?: WalkMap) {
    this.floors = set.movers.map((m) => m.restFloor);
    this.ceilings = set.movers.map((m) => m.restCeiling);
    this.moverOfSector = new Map(set.movers.map((m, i) => [m.sector, i]));
  }

  /** Whether mover `i` is moving or waiting. */
  active(i: number): boolean {
    return this.motions.has(i);
  }

  /** Something is moving or waiting (a stepped mover always either moves or counts down its wait). */
  moving(): boolean {
    return this.motions.size > 0;
  }

  step(t: number, dt: number, view: Viewpoint, out: UpdateBuilder, first: boolean): void {
    this.view = view;
    for (const [i, motion] of [...this.motions]) this.advance(i, motion, Math.min(dt, t - motion.since));
    const changed = first ? this.set.movers.map((_, i) => i) : [...this.dirty];
    this.dirty.clear();
    for (const i of changed) {
      const m = this.set.movers[i]!;
      out.morphWeights.set(m.mesh, new Float32Array([this.floors[i]! - m.restFloor, this.ceilings[i]! - m.restCeiling]));
      out.walkHeights.set(m.sector, [this.floors[i]!, this.ceilings[i]!]);
    }
  }

  /**
   * Doom's use (P_UseLines): a segment of `useRange` from the player's centre along the view
   * direction projected on the floor; the nearest trigger line it crosses answers, and only from its
   * front side (from behind, nothing happens).
   */
  use(view: Viewpoint, t: number): boolean {
    this.view = view;
    const [px, , pz] = view.position;
    const [fx, , fz] = view.forward;
    const n = Math.hypot(fx, fz);
    if (!(n > 0)) return false;
    const ex = (fx / n) * this.set.useRange, ez = (fz / n) * this.set.useRange;
    let nearest = -1, best = Infinity;
    this.set.triggers.forEach((trigger, k) => {
      if (trigger.activation !== 'use' || this.spent.has(k)) return;
      const s = crossing(px, pz, px + ex, pz + ez, trigger.line);
      if (s !== undefined && s < best) [nearest, best] = [k, s];
    });
    if (nearest < 0 || this.blockedBefore(px, pz, px + ex, pz + ez, best)) return false;
    const trigger = this.set.triggers[nearest]!;
    const [x0, z0, x1, z1] = trigger.line;
    if (!((x1 - x0) * (pz - z0) - (z1 - z0) * (px - x0) > 0)) return false;
    return this.fire(nearest, t);
  }

  /**
   * Whether a wall or a shut opening (no room between the higher floor and the lower ceiling: a
   * closed door) crosses the segment before the fraction `before` (PTR_UseTraverse's "noway").
   */
  private blockedBefore(ax: number, az: number, bx: number, bz: number, before: number): boolean {
    const map = this.walkMap;
    if (!map) return false;
    const L = map.lines;
    const height = (sector: number, floor: boolean) => {
      const i = this.moverOfSector.get(sector);
      if (i !== undefined) return floor ? this.floors[i]! : this.ceilings[i]!;
      return floor ? map.floors[sector]! : map.ceilings[sector]!;
    };
    for (let i = 0; i < L.length; i += 4) {
      const s = crossing(ax, az, bx, bz, [L[i]!, L[i + 1]!, L[i + 2]!, L[i + 3]!]);
      // The use line itself (a door's face is a shut opening too) lies at `before`, not before it.
      if (s === undefined || s >= before - 1e-9) continue;
      const a = map.lineSectors[i / 2]!, b = map.lineSectors[i / 2 + 1]!;
      if (a === NO_SECTOR || b === NO_SECTOR) return true;
      if (Math.min(height(a, false), height(b, false)) - Math.max(height(a, true), height(b, true)) <= 0) return true;
    }
    return false;
  }

  /** The player's centre moved from (x0, z0) to (x1, z1): walk-over lines it crossed fire. */
  walked(x0: number, z0: number, x1: number, z1: number, t: number): void {
    this.set.triggers.forEach((trigger, k) => {
      if (trigger.activation === 'walk' && !this.spent.has(k) && crossing(x0, z0, x1, z1, trigger.line) !== undefined) this.fire(k, t);
    });
  }

  /** Starts (or, for manual doors, reverses) the trigger's movers; true when any answered. */
  private fire(k: number, t: number): boolean {
    const trigger = this.set.triggers[k]!;
    let answered = false;
    for (const i of trigger.movers) {
      const m = this.set.movers[i];
      if (!m) continue;
      const motion = this.motions.get(i);
      if (motion) {
        // EV_VerticalDoor on a door with a thinker: a closing door goes back up, any other closes.
        if (!trigger.reverses || moverKindOf(motion.trigger.action) !== 'door') continue;
        motion.phase = motion.phase === 'down' ? 'up' : 'down';
        answered = true;
        continue;
      }
      const action = trigger.action;
      const door = moverKindOf(action) === 'door';
      const phase: Phase = action === 'close' || action === 'close-wait-open' || action === 'lower-wait-raise' ? 'down' : 'up';
      // A close-wait-open door reopens to where its ceiling was; other doors open to the top.
      const top = action === 'close-wait-open' ? this.ceilings[i]! : door ? m.doorTop : this.floors[i]!;
      this.motions.set(i, { trigger, phase, waitLeft: 0, top, since: t });
      answered = true;
    }
    // Doom clears a once-only walk line whatever happened, a once-only use line when it worked.
    if (!trigger.repeatable && (answered || trigger.activation === 'walk')) this.spent.add(k);
    return answered;
  }

  /** Moves mover `i` by `dt` seconds of its motion, phase after phase. */
  private advance(i: number, motion: Motion, dt: number): void {
    const m = this.set.movers[i]!;
    const { action, speed, wait } = motion.trigger;
    const door = moverKindOf(action) === 'door';
    let left = dt;
    // A few phase changes per step at most; the bound guards against a zero-length loop.
    for (let guard = 0; guard < 8 && left > 0; guard++) {
      if (motion.phase === 'waiting') {
        const w = Math.min(left, motion.waitLeft);
        motion.waitLeft -= w;
        left -= w;
        if (motion.waitLeft > 0) return;
        motion.phase = action === 'lower-wait-raise' || action === 'close-wait-open' ? 'up' : 'down';
        continue;
      }
      const up = motion.phase === 'up';
      // Doors move the ceiling (down to the floor); lifts the floor (down to their bottom).
      const now = door ? this.ceilings[i]! : this.floors[i]!;
      const target = up ? motion.top : door ? this.floors[i]! : m.liftBottom;
      const distance = Math.abs(target - now);
      const move = Math.min(distance, speed * left);
      const next = now + Math.sign(target - now) * move;
      if (this.crushes(i, door, up, next)) {
        // T_VerticalDoor: a closing door that meets the player goes back up, except the "close"
        // kind, which waits; T_PlatRaise: a rising lift that would squeeze the player goes down.
        if (door && action === 'close') return;
        motion.phase = up ? 'down' : 'up';
        continue;
      }
      if (door) this.ceilings[i] = next;
      else this.floors[i] = next;
      if (move > 0) this.dirty.add(i);
      left -= speed > 0 ? move / speed : left;
      if (move < distance) return;
      // Arrived.
      const waits = (up && action === 'open-wait-close') || (!up && (action === 'close-wait-open' || action === 'lower-wait-raise'));
      if (waits) {
        motion.phase = 'waiting';
        motion.waitLeft = wait;
      } else {
        this.motions.delete(i);
        return;
      }
    }
  }

  /** Whether moving mover `i`'s plane to `next` would squeeze the player (the viewpoint) standing in it. */
  private crushes(i: number, door: boolean, up: boolean, next: number): boolean {
    // Doors crush going down, lifts going up.
    if (door === up || !this.view) return false;
    const m = this.set.movers[i]!;
    const room = door ? next - this.floors[i]! : this.ceilings[i]! - next;
    return room < this.set.body.height && touches(m.outline, this.view.position[0], this.view.position[2], this.set.body.radius);
  }
}

export const moverAnimator: AnimatorFactory = (scene) => {
  const set = scene.dynamics?.movers;
  return set && set.movers.length > 0 ? new MoverAnimator(set, scene.walkMap) : undefined;
};

/**
 * Where the segment (ax, az) → (bx, bz) crosses `line`, as a fraction of the segment (0..1), or
 * undefined when it does not (touching an end counts as crossing).
 */
export function crossing(ax: number, az: number, bx: number, bz: number, line: readonly [number, number, number, number]): number | undefined {
  const [x0, z0, x1, z1] = line;
  const dx = bx - ax, dz = bz - az, ex = x1 - x0, ez = z1 - z0;
  const denom = dx * ez - dz * ex;
  if (denom === 0) return undefined;
  const s = ((x0 - ax) * ez - (z0 - az) * ex) / denom;
  const u = ((x0 - ax) * dz - (z0 - az) * dx) / denom;
  return s >= 0 && s <= 1 && u >= 0 && u <= 1 ? s : undefined;
}

/** Whether a disc of radius `r` at (x, z) overlaps the area enclosed by `outline` (even-odd rule). */
export function touches(outline: Float32Array, x: number, z: number, r: number): boolean {
  let inside = false;
  for (let i = 0; i + 3 < outline.length; i += 4) {
    const x0 = outline[i]!, z0 = outline[i + 1]!, x1 = outline[i + 2]!, z1 = outline[i + 3]!;
    if (z0 > z !== z1 > z && x < x0 + ((z - z0) * (x1 - x0)) / (z1 - z0)) inside = !inside;
    const ex = x1 - x0, ez = z1 - z0;
    const len2 = ex * ex + ez * ez;
    const t = len2 > 0 ? Math.min(1, Math.max(0, ((x - x0) * ex + (z - z0) * ez) / len2)) : 0;
    if (Math.hypot(x - (x0 + t * ex), z - (z0 + t * ez)) < r) return true;
  }
  return inside;
}
