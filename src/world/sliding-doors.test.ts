import { describe, expect, it } from 'vitest';
import { IDENTITY } from '../math/mat4.ts';
import type { SlidingDoor, SlidingDoorSet, WalkGrid } from '../scene/dynamics-types.ts';
import { UpdateBuilder, type Viewpoint } from './animator.ts';
import { doorPose, SlidingDoorAnimator, usedCell } from './sliding-doors.ts';

const GRID: WalkGrid = { originX: 0, originZ: 0, size: 10 };
/** A door in cell (2, 0), passed east–west, sliding 10 units south; sector 4. */
const DOOR: SlidingDoor = { instance: 7, closedPose: IDENTITY, slide: [0, 0, 10], cell: [2, 0], across: [1, 0], sector: 4, floor: 0, ceiling: 10 };
const set = (trigger: 'use' | 'proximity'): SlidingDoorSet => ({ doors: [DOOR], grid: GRID, trigger, proximity: 15, travelSeconds: 1, waitSeconds: 4, bodyRadius: 3 });
const at = (x: number, z: number, fx = 1, fz = 0): Viewpoint => ({ position: [x, 5, z], forward: [fx, 0, fz] });

function step(a: SlidingDoorAnimator, dt: number, view: Viewpoint, first = false): UpdateBuilder {
  const out = new UpdateBuilder();
  a.step(0, dt, view, out, first);
  return out;
}

describe('usedCell (Cmd_Use)', () => {
  it('rounds the view to the nearest of east, north, west, south and names the next cell', () => {
    expect(usedCell(GRID, at(15, 5, 1, 0.9))).toEqual({ cell: [2, 0], step: [1, 0] });
    expect(usedCell(GRID, at(15, 5, 0.9, -1))).toEqual({ cell: [1, -1], step: [0, -1] });
    expect(usedCell(GRID, at(15, 5, -1, 0.2))).toEqual({ cell: [0, 0], step: [-1, 0] });
    expect(usedCell(GRID, at(15, 5, 0.2, 1))).toEqual({ cell: [1, 1], step: [0, 1] });
    expect(usedCell(GRID, { position: [15, 5, 5], forward: [0, 1, 0] })).toBeUndefined();
  });
});

describe('SlidingDoorAnimator', () => {
  it('writes the closed pose and a shut sector first, then nothing while nothing happens', () => {
    const a = new SlidingDoorAnimator(set('use'));
    const first = step(a, 0, at(5, 5), true);
    expect(first.instances.get(7)!.worldFromObject).toEqual(IDENTITY);
    expect(first.walkHeights.get(4)).toEqual([0, 0]);
    const later = step(a, 1, at(5, 5));
    expect(later.instances.size + later.walkHeights.size).toBe(0);
  });

  it('slides linearly over the travel time and opens the sector only when fully open', () => {
    const a = new SlidingDoorAnimator(set('use'));
    step(a, 0, at(15, 5), true);
    expect(a.use(at(15, 5))).toBe(true);
    let out = step(a, 0.25, at(15, 5));
    expect(out.instances.get(7)!.worldFromObject![14]).toBeCloseTo(2.5, 9);
    expect(out.walkHeights.size).toBe(0);
    out = step(a, 0.75, at(15, 5));
    expect(out.instances.get(7)!.worldFromObject).toEqual(doorPose(DOOR, 1));
    expect(out.walkHeights.get(4)).toEqual([0, 10]);
    expect(a.state(0)).toEqual({ action: 'open', position: 1 });
  });

  it('closes by the use key at once (shutting the sector), but not on a body in the doorway', () => {
    const a = new SlidingDoorAnimator(set('use'));
    step(a, 0, at(15, 5), true);
    a.use(at(15, 5));
    step(a, 1.5, at(15, 5));
    // East of it, the body's edge over the door's cell (x = 30 + 2 < 30 + radius 3), facing it: the key answers, the door stays.
    expect(a.use(at(32, 5, -1, 0))).toBe(true);
    expect(a.state(0).action).toBe('open');
    a.use(at(15, 5));
    const out = step(a, 0.5, at(15, 5));
    expect(out.walkHeights.get(4)).toEqual([0, 0]);
    expect(a.state(0)).toEqual({ action: 'closing', position: 0.5 });
  });

  it('by proximity, the use key opens a door but never closes one', () => {
    const a = new SlidingDoorAnimator(set('proximity'));
    step(a, 0, at(-20, 5), true);
    expect(a.use(at(15, 5))).toBe(true);
    step(a, 0.5, at(15, 5));
    expect(a.use(at(15, 5))).toBe(true);
    expect(a.state(0)).toEqual({ action: 'opening', position: 0.5 });
  });

  it('opens by proximity only in front of the door, within the doorway width', () => {
    const a = new SlidingDoorAnimator(set('proximity'));
    step(a, 0, at(-20, 5), true);
    step(a, 0.1, at(9, 16)); // beside, not in front
    expect(a.state(0).action).toBe('closed');
    step(a, 0.1, at(11, 5)); // 14 units west of the panel at x = 25
    expect(a.state(0).action).toBe('opening');
    const b = new SlidingDoorAnimator(set('use'));
    step(b, 0, at(11, 5), true);
    step(b, 0.1, at(11, 5));
    expect(b.state(0).action).toBe('closed');
  });

  it('waits for a walking player\'s use key even where the demo opens doors by proximity, and the key then closes them too', () => {
    const a = new SlidingDoorAnimator(set('proximity'));
    const walker = (x: number, z: number): Viewpoint => ({ ...at(x, z), walking: true });
    step(a, 0, walker(-20, 5), true);
    step(a, 0.5, walker(11, 5)); // in front, where a flying camera opens it
    expect(a.state(0).action).toBe('closed');
    expect(a.use(walker(15, 5))).toBe(true);
    step(a, 2, walker(15, 5));
    expect(a.state(0).action).toBe('open');
    expect(a.use(walker(15, 5))).toBe(true);
    expect(a.state(0).action).toBe('closing');
  });
});
