/**
 * Push walls: wall blocks that slide away from the player who uses them (Wolfenstein 3D's secret
 * doors, WL_ACT1.C PushWall and MovePWalls): the animator that plays Scene.dynamics.pushWalls (the
 * data: scene/dynamics-types.ts; its checks: scene/validate.ts). Each is an instance (created with
 * `moves: true`) of a cube's four wall faces and a walk-map sector per cell it may stand in: shut
 * ([floor, floor]) while the block is in it or on its way into it, open ([floor, ceiling]) once it
 * has left. Pure.
 *
 * The game's rules, in seconds instead of 70 Hz tics:
 * - the use key, from the cell next to the block, facing it (the direction of view rounded to east,
 *   north, west or south: sliding-doors.ts usedCell), pushes it that way; a block moves once;
 * - it moves a cell per 128 tics (1.83 s), at most two cells, and stops early at a cell that is not
 *   free (a wall, a door, a blocking object, another block): the game checks the next cell as the
 *   block enters the one before it. The loader lists the cells that are free in each direction when
 *   the level starts (`paths`); the animator also keeps blocks out of each other's cells.
 * - the cell the block leaves becomes free as the block has left it wholly; the cell it enters is
 *   shut from the moment it starts toward it.
 */
import type { Mat4 } from '../math/mat4.ts';
import { PUSH_DIRECTIONS, type PushWallCell, type PushWallSet } from '../scene/dynamics-types.ts';
import { usedCell } from './sliding-doors.ts';
import type { Animator, AnimatorFactory, UpdateBuilder, Viewpoint } from './animator.ts';

interface Push {
  readonly direction: number;
  /** Seconds since the push. */
  elapsed: number;
  /** Cells it enters (each reserved when the block sets off toward it). */
  readonly entered: PushWallCell[];
  done: boolean;
}

/** Plays Scene.dynamics.pushWalls; exported for tests that drive it without a World. */
export class PushWallAnimator implements Animator {
  private readonly pushes = new Map<number, Push>();
  /** Walk-map sectors shut by a block (where one stands or is going), by the block's index. */
  private readonly shut = new Map<number, number>();
  private readonly byCell = new Map<string, number>();
  private readonly dirtyWalls = new Set<number>();
  private readonly dirtySectors = new Set<number>();

  constructor(readonly set: PushWallSet) {
    set.walls.forEach((w, i) => {
      this.byCell.set(`${w.cell[0]},${w.cell[1]}`, i);
      this.shut.set(w.sector, i);
    });
  }

  /** How far block `i` has moved, in cells, and which way (undefined before it is pushed). */
  offset(i: number): { readonly cells: number; readonly direction: number } | undefined {
    const p = this.pushes.get(i);
    return p && { cells: this.cells(p), direction: p.direction };
  }

  private cells(p: Push): number {
    return Math.min(p.elapsed / this.set.secondsPerCell, p.entered.length);
  }

  /** Whether walk-map sector `sector` is shut by a block now. */
  isShut(sector: number): boolean {
    return this.shut.has(sector);
  }

  /** A block is on its way. */
  moving(): boolean {
    for (const p of this.pushes.values()) if (!p.done) return true;
    return false;
  }

  step(_t: number, dt: number, _view: Viewpoint, out: UpdateBuilder, first: boolean): void {
    for (const [i, p] of this.pushes) {
      if (p.done) continue;
      p.elapsed += dt;
      const wall = this.set.walls[i]!;
      const path = wall.paths[p.direction]!;
      // MovePWalls: each time the block fills the cell it entered, the cell behind frees and, while
      // it has moved fewer than `reach` cells, it sets off into the next if that is free.
      while (!p.done && p.elapsed >= p.entered.length * this.set.secondsPerCell) {
        const behind = p.entered.length === 1 ? wall.sector : p.entered[p.entered.length - 2]!.sector;
        this.free(behind);
        const next = path[p.entered.length];
        if (p.entered.length >= this.set.reach || !next || this.shut.has(next.sector)) p.done = true;
        else this.reserve(next.sector, i, p);
      }
      this.dirtyWalls.add(i);
    }
    if (first) {
      this.set.walls.forEach((w, i) => {
        this.dirtyWalls.add(i);
        this.dirtySectors.add(w.sector);
        for (const path of w.paths) for (const c of path) this.dirtySectors.add(c.sector);
      });
    }
    for (const i of this.dirtyWalls) out.pose(this.set.walls[i]!.instance, { worldFromObject: this.pose(i) });
    for (const s of this.dirtySectors) {
      const w = this.set.walls.find((wall) => wall.sector === s || wall.paths.some((path) => path.some((c) => c.sector === s)))!;
      out.walkHeights.set(s, [w.floor, this.shut.has(s) ? w.floor : w.ceiling]);
    }
    this.dirtyWalls.clear();
    this.dirtySectors.clear();
  }

  /** The use key: the block in the cell faced, not yet pushed, sets off away from the viewer if it can. */
  use(view: Viewpoint): boolean {
    const used = usedCell(this.set.grid, view);
    if (!used) return false;
    const i = this.byCell.get(`${used.cell[0]},${used.cell[1]}`);
    if (i === undefined || this.pushes.has(i)) return false;
    const direction = PUSH_DIRECTIONS.findIndex(([di, dj]) => di === used.step[0] && dj === used.step[1]);
    const first = this.set.walls[i]!.paths[direction]![0];
    // PushWall: "no way" when the first cell is not free.
    if (!first || this.shut.has(first.sector)) return false;
    const push: Push = { direction, elapsed: 0, entered: [], done: false };
    this.reserve(first.sector, i, push);
    this.pushes.set(i, push);
    return true;
  }

  /** Block `i`'s transform now: its rest pose moved by the cells it has travelled. */
  pose(i: number): Mat4 {
    const w = this.set.walls[i]!;
    const p = this.pushes.get(i);
    if (!p) return w.restPose;
    const d = this.cells(p) * this.set.grid.size;
    const [di, dj] = PUSH_DIRECTIONS[p.direction]!;
    const m = [...w.restPose];
    m[12] = m[12]! + di * d;
    m[14] = m[14]! + dj * d;
    return m;
  }

  private reserve(sector: number, wall: number, push: Push): void {
    const cell = this.set.walls[wall]!.paths[push.direction]!.find((c) => c.sector === sector)!;
    push.entered.push(cell);
    this.shut.set(sector, wall);
    this.dirtySectors.add(sector);
  }

  private free(sector: number): void {
    this.shut.delete(sector);
    this.dirtySectors.add(sector);
  }
}

export const pushWallAnimator: AnimatorFactory = (scene) => {
  const set = scene.dynamics?.pushWalls;
  return set && set.walls.length > 0 ? new PushWallAnimator(set) : undefined;
};
