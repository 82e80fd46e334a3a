/**
 * Sliding doors: panels that slide sideways into the wall beside them, wait, and slide back
 * (Wolfenstein 3D's doors, WL_ACT1.C: OpenDoor, DoorOpening, DoorOpen, CloseDoor, DoorClosing): the
 * animator that plays Scene.dynamics.slidingDoors (the data: scene/dynamics-types.ts; its checks:
 * scene/validate.ts), and the walk grid's use rule, which push walls share. Each door is an instance
 * (created with `moves: true`) carried from its closed pose along `slide`, and a walk-map sector
 * that lets the walker through only while the door is fully open (the game clears the door's tile
 * only then). Pure.
 *
 * The game's rules, in seconds instead of 70 Hz tics:
 * - opening or closing takes `travelSeconds` (the game: 0xffff / (1024 per tic) = 64 tics, 0.91 s);
 * - an open door waits `waitSeconds` (the game: OPENTICS = 300 tics, 4.3 s), then closes, unless
 *   the player's body overlaps the door's tile (CloseDoor returns; it tries again every step);
 * - a closing door that the player's body comes into reopens (DoorClosing);
 * - the use key (OperateDoor) opens a closed or closing door and closes an open or opening one.
 * What the game has that is not here: keys (locked doors open like the others: no inventory is kept)
 * and actors in the doorway.
 *
 * Triggers (SlidingDoorSet.trigger):
 * - 'use': the use key only, Wolfenstein's rule (Cmd_Use): the player's direction of view rounded to
 *   the nearest of east, north, west and south picks the tile next to the player's; a door there
 *   answers;
 * A walking player (Viewpoint.walking: the viewer's walk mode) always gets 'use', as in the game.
 * - 'proximity': the use key opens doors (it never closes one: whoever uses a door stands in front
 *   of it, which keeps it open), and a door also opens by itself while the viewer stands in front of it
 *   (within `proximity` of its panel, measured across the panel, and within the doorway's width
 *   along it): deterministic, so a camera path or a still render at a given time sees the same
 *   doors open. An open door stays open while the viewer stands there (the game's OpenDoor on an
 *   open door restarts its wait: here its wait starts when the viewer leaves).
 */
import type { Mat4 } from '../math/mat4.ts';
import type { SlidingDoor, SlidingDoorSet, WalkGrid } from '../scene/dynamics-types.ts';
import { touches } from './movers.ts';
import type { Animator, AnimatorFactory, UpdateBuilder, Viewpoint } from './animator.ts';

/** What a door is doing (the game's dr_closed, dr_opening, dr_open, dr_closing). */
export type DoorAction = 'closed' | 'opening' | 'open' | 'closing';

interface DoorState {
  action: DoorAction;
  /** 0 closed … 1 fully open. */
  position: number;
  /** Seconds spent open. */
  waited: number;
}

/** The cell [i, j] of `grid` containing (x, z). */
export function cellOf(grid: WalkGrid, x: number, z: number): [number, number] {
  return [Math.floor((x - grid.originX) / grid.size), Math.floor((z - grid.originZ) / grid.size)];
}

/**
 * Wolfenstein's use key (Cmd_Use): the cell next to the viewer's in the direction of view rounded
 * to the nearest of east (+x), north (−z), west (−x) and south (+z), with that direction as a unit
 * step [di, dj]; undefined when the viewer looks straight up or down.
 */
export function usedCell(grid: WalkGrid, view: Viewpoint): { cell: [number, number]; step: [number, number] } | undefined {
  const [fx, , fz] = view.forward;
  if (!(Math.hypot(fx, fz) > 1e-9)) return undefined;
  // The game's angle: counter-clockwise from east, north being −z here.
  let angle = Math.atan2(-fz, fx);
  if (angle < 0) angle += 2 * Math.PI;
  const eighth = Math.PI / 4;
  const step: [number, number] = angle < eighth || angle > 7 * eighth ? [1, 0] : angle < 3 * eighth ? [0, -1] : angle < 5 * eighth ? [-1, 0] : [0, 1];
  const [i, j] = cellOf(grid, view.position[0], view.position[2]);
  return { cell: [i + step[0], j + step[1]], step };
}

/** The square of a cell as an outline (x0, z0, x1, z1 per side), for movers.ts `touches`. */
export function cellOutline(grid: WalkGrid, [i, j]: readonly [number, number]): Float32Array {
  const x0 = grid.originX + i * grid.size, z0 = grid.originZ + j * grid.size;
  const x1 = x0 + grid.size, z1 = z0 + grid.size;
  return new Float32Array([x0, z0, x1, z0, x1, z0, x1, z1, x1, z1, x0, z1, x0, z1, x0, z0]);
}

/** The panel's transform at `position` (0 closed … 1 open): the closed pose moved by position · slide. */
export function doorPose(door: SlidingDoor, position: number): Mat4 {
  const m = [...door.closedPose];
  m[12] = m[12]! + door.slide[0] * position;
  m[13] = m[13]! + door.slide[1] * position;
  m[14] = m[14]! + door.slide[2] * position;
  return m;
}

/** Plays Scene.dynamics.slidingDoors; exported for tests that drive it without a World. */
export class SlidingDoorAnimator implements Animator {
  private readonly states: DoorState[];
  private readonly outlines: Float32Array[];
  /** Whether the walk map was last told the door is passable. */
  private readonly shownOpen: boolean[];
  private readonly byCell = new Map<string, number>();
  /** Where the viewer was at the last step or use: whose body a closing door must not close on. */
  private view?: Viewpoint;

  constructor(readonly set: SlidingDoorSet) {
    this.states = set.doors.map(() => ({ action: 'closed', position: 0, waited: 0 }));
    this.outlines = set.doors.map((d) => cellOutline(set.grid, d.cell));
    this.shownOpen = set.doors.map(() => false);
    set.doors.forEach((d, i) => this.byCell.set(`${d.cell[0]},${d.cell[1]}`, i));
  }

  /** What door `i` is doing and how far open it is (0–1). */
  state(i: number): { readonly action: DoorAction; readonly position: number } {
    const s = this.states[i]!;
    return { action: s.action, position: s.position };
  }

  /** Whether the walker may pass door `i` (fully open, as the game clears the tile only then). */
  passable(i: number): boolean {
    return this.states[i]!.action === 'open';
  }

  /**
   * Whether a step seen from `view` would change a door: one slides, or waits to close, or stands
   * closed with the viewer in front of it by proximity. An open door held open (the viewer in front,
   * or a body in the doorway once its wait is over) is at rest until the view changes.
   */
  moving(view: Viewpoint): boolean {
    const proximity = this.trigger(view) === 'proximity';
    return this.set.doors.some((door, i) => {
      const s = this.states[i]!;
      const near = proximity && this.inFront(door, view);
      if (s.action === 'closed') return near;
      if (s.action === 'open') return near ? s.waited !== 0 : !(s.waited >= this.set.waitSeconds && this.blocked(i, view));
      return true;
    });
  }

  step(_t: number, dt: number, view: Viewpoint, out: UpdateBuilder, first: boolean): void {
    this.view = view;
    const { doors, travelSeconds, waitSeconds } = this.set;
    doors.forEach((door, i) => {
      const s = this.states[i]!;
      const before = s.position;
      // By proximity the viewer in front opens the door and holds it open: its wait starts once they leave.
      const near = this.trigger(view) === 'proximity' && this.inFront(door, view);
      if (near) this.open(i);
      let left = dt;
      // A few state changes per step at most (opening → open → closing …); the bound ends the loop.
      for (let guard = 0; guard < 4 && left > 0; guard++) {
        if (s.action === 'opening') {
          const need = (1 - s.position) * travelSeconds;
          if (need > left) {
            s.position += left / travelSeconds;
            left = 0;
          } else {
            left -= need;
            s.position = 1;
            s.action = 'open';
            s.waited = 0;
          }
        } else if (s.action === 'open') {
          if (near) break;
          const need = waitSeconds - s.waited;
          if (need > left) {
            s.waited += left;
            left = 0;
          } else {
            s.waited = waitSeconds;
            // CloseDoor: not on a body in the doorway; it tries again at every step, from the end of its wait.
            if (this.blocked(i)) break;
            left -= need;
            s.action = 'closing';
          }
        } else if (s.action === 'closing') {
          if (this.blocked(i)) {
            s.action = 'opening';
            continue;
          }
          const need = s.position * travelSeconds;
          if (need > left) {
            s.position -= left / travelSeconds;
            left = 0;
          } else {
            left -= need;
            s.position = 0;
            s.action = 'closed';
          }
        } else break;
      }
      const open = s.action === 'open';
      if (first || s.position !== before) out.pose(door.instance, { worldFromObject: doorPose(door, s.position) });
      if (first || open !== this.shownOpen[i]) out.walkHeights.set(door.sector, [door.floor, open ? door.ceiling : door.floor]);
      this.shownOpen[i] = open;
    });
  }

  /** Wolfenstein's use key (Cmd_Use, OperateDoor): the door in the cell faced opens, or closes. */
  use(view: Viewpoint): boolean {
    this.view = view;
    const used = usedCell(this.set.grid, view);
    const i = used && this.byCell.get(`${used.cell[0]},${used.cell[1]}`);
    if (i === undefined) return false;
    const s = this.states[i]!;
    if (s.action === 'closed' || s.action === 'closing') this.open(i);
    // By proximity the user stands in front of the door, which keeps it open: the key only opens.
    else if (this.trigger(view) === 'use' && !this.blocked(i)) s.action = 'closing';
    return true;
  }

  /** The trigger in force: a walking player always uses doors (Wolfenstein's rule), whatever the demo default. */
  private trigger(view: Viewpoint): 'use' | 'proximity' {
    return view.walking ? 'use' : this.set.trigger;
  }

  /** OpenDoor: a closed or closing door starts opening; an open one waits again from the start. */
  private open(i: number): void {
    const s = this.states[i]!;
    if (s.action === 'open') s.waited = 0;
    else s.action = 'opening';
  }

  /** Whether the viewer stands in front of door `i`: within `proximity` across its panel and the doorway's width along it. */
  private inFront(door: SlidingDoor, view: Viewpoint): boolean {
    const { grid } = this.set;
    const cx = grid.originX + (door.cell[0] + 0.5) * grid.size, cz = grid.originZ + (door.cell[1] + 0.5) * grid.size;
    const dx = view.position[0] - cx, dz = view.position[2] - cz;
    const [ax, az] = door.across;
    const across = Math.abs(dx * ax + dz * az);
    const along = Math.abs(-dx * az + dz * ax);
    return across <= this.set.proximity && along < grid.size / 2;
  }

  /** Whether the player's body (the viewpoint, the last step's by default) overlaps door `i`'s cell. */
  private blocked(i: number, v: Viewpoint | undefined = this.view): boolean {
    return v !== undefined && touches(this.outlines[i]!, v.position[0], v.position[2], this.set.bodyRadius);
  }
}

export const slidingDoorAnimator: AnimatorFactory = (scene) => {
  const set = scene.dynamics?.slidingDoors;
  return set && set.doors.length > 0 ? new SlidingDoorAnimator(set) : undefined;
};
