import { describe, expect, it } from 'vitest';
import type { Mover, MoverSet, MoverTrigger } from '../scene/dynamics-types.ts';
import type { WalkMap } from '../scene/walk-map.ts';
import { UpdateBuilder, type Viewpoint } from './animator.ts';
import { MoverAnimator } from './movers.ts';

/**
 * A door sector x 128..144, z −128..0 (the walk plane), closed (floor = ceiling = 0), opening to 124;
 * and a lift x 300..364, z −128..0, floor 64 lowering to 0, ceiling 200.
 */
const square = (x0: number, z0: number, x1: number, z1: number) => new Float32Array([x0, z0, x0, z1, x0, z1, x1, z1, x1, z1, x1, z0, x1, z0, x0, z0]);
const DOOR: Mover = { mesh: 5, sector: 2, kinds: ['door'], restFloor: 0, restCeiling: 0, doorTop: 124, liftBottom: 0, outline: square(128, -128, 144, 0) };
const LIFT: Mover = { mesh: 6, sector: 3, kinds: ['lift'], restFloor: 64, restCeiling: 200, doorTop: 196, liftBottom: 0, outline: square(300, -128, 364, 0) };
const TIC = 1 / 35;

/** A use line on the door's west face (x = 128): its front side is x < 128 (cross > 0). */
const doorUse = (over: Partial<MoverTrigger> = {}): MoverTrigger => ({
  line: [128, -128, 128, 0], activation: 'use', repeatable: true, movers: [0], action: 'open-wait-close', speed: 2 * 35, wait: 150 / 35, reverses: true, ...over,
});

function animator(triggers: MoverTrigger[]): MoverAnimator {
  const set: MoverSet = { movers: [DOOR, LIFT], triggers, useRange: 64, body: { radius: 16, height: 56 } };
  return new MoverAnimator(set);
}

/** Standing at (x, z) looking along (fx, fz). */
const at = (x: number, z: number, fx = 1, fz = 0): Viewpoint => ({ position: [x, 41, z], forward: [fx, 0, fz] });
const FAR = at(-1000, -1000);

/** Steps in tics until `seconds`, from `from`; returns the last update. */
function run(a: MoverAnimator, from: number, seconds: number, view = FAR): UpdateBuilder {
  let out = new UpdateBuilder();
  const steps = Math.round((seconds - from) / TIC);
  for (let i = 1; i <= steps; i++) {
    out = new UpdateBuilder();
    a.step(from + i * TIC, TIC, view, out, false);
  }
  return out;
}

describe('MoverAnimator', () => {
  it('writes every mover on the first step: rest heights, weights 0', () => {
    const a = animator([doorUse()]);
    const out = new UpdateBuilder();
    a.step(0, 0, FAR, out, true);
    expect([...out.morphWeights]).toEqual([[5, new Float32Array([0, 0])], [6, new Float32Array([0, 0])]]);
    expect([...out.walkHeights]).toEqual([[2, [0, 0]], [3, [64, 200]]]);
  });

  it('opens a door at 2 units per tic, waits 150 tics, closes at 2 units per tic', () => {
    const a = animator([doorUse()]);
    expect(a.use(at(100, -64), 0)).toBe(true);
    run(a, 0, 35 * TIC);
    expect(a.ceilings[0]).toBeCloseTo(70, 6); // 35 tics × 2
    const opened = 62 * TIC; // 124 / 2 tics
    let out = run(a, 35 * TIC, opened);
    expect(a.ceilings[0]).toBeCloseTo(124, 6);
    expect(out.morphWeights.get(5)).toEqual(new Float32Array([0, 124]));
    expect(out.walkHeights.get(2)).toEqual([0, 124]);
    // Open for 150 tics: still at the top one tic before the end, nothing written while it waits.
    out = run(a, opened, opened + 149 * TIC);
    expect(a.ceilings[0]).toBeCloseTo(124, 6);
    expect(out.morphWeights.size).toBe(0);
    run(a, opened + 149 * TIC, opened + 160 * TIC);
    expect(a.ceilings[0]).toBeCloseTo(124 - 2 * 10, 4);
    run(a, opened + 160 * TIC, opened + 213 * TIC); // 212 tics, and one for rounding
    expect(a.ceilings[0]).toBeCloseTo(0, 4);
    expect(a.active(0)).toBe(false);
  });

  it('opens a blazing door (117) at 8 units per tic', () => {
    const a = animator([doorUse({ speed: 8 * 35 })]);
    a.use(at(100, -64), 0);
    run(a, 0, 10 * TIC);
    expect(a.ceilings[0]).toBeCloseTo(80, 6);
  });

  it('lowers a lift at 4 units per tic, waits 105 tics, raises it back', () => {
    const walk: MoverTrigger = { line: [290, -128, 290, 0], activation: 'walk', repeatable: true, movers: [1], action: 'lower-wait-raise', speed: 4 * 35, wait: 3, reverses: false };
    const a = animator([walk]);
    a.walked(280, -64, 295, -64, 0);
    run(a, 0, 10 * TIC);
    expect(a.floors[1]).toBeCloseTo(64 - 40, 6);
    run(a, 10 * TIC, 16 * TIC); // at the bottom after 16 tics
    expect(a.floors[1]).toBeCloseTo(0, 6);
    run(a, 16 * TIC, (16 + 104) * TIC);
    expect(a.floors[1]).toBeCloseTo(0, 6);
    const out = run(a, (16 + 104) * TIC, (16 + 105 + 5) * TIC);
    expect(a.floors[1]).toBeCloseTo(20, 4);
    expect(out.morphWeights.get(6)![0]).toBeCloseTo(20 - 64, 4);
    expect(out.walkHeights.get(3)![1]).toBe(200);
    run(a, (16 + 105 + 5) * TIC, 200 * TIC);
    expect(a.floors[1]).toBeCloseTo(64, 4);
    expect(a.active(1)).toBe(false);
  });

  it('moves only from the moment it was triggered within a step', () => {
    const a = animator([doorUse()]);
    a.use(at(100, -64), 0.5);
    a.step(1, 1, FAR, new UpdateBuilder(), false);
    expect(a.ceilings[0]).toBeCloseTo(35, 6);
  });

  describe('use', () => {
    it('reaches 64 units from the centre along the view projected on the floor', () => {
      expect(animator([doorUse()]).use(at(65, -64), 0)).toBe(true); // the line is 63 units ahead
      expect(animator([doorUse()]).use(at(63, -64), 0)).toBe(false); // 65 units
      expect(animator([doorUse()]).use(at(100, -64, -1, 0), 0)).toBe(false); // looking away
      // Looking steeply up still uses what is ahead on the floor plan.
      const up = animator([doorUse()]);
      expect(up.use({ position: [100, 41, -64], forward: [0.2, 0.98, 0] }, 0)).toBe(true);
      expect(up.active(0)).toBe(true);
    });

    it('works from the front side only', () => {
      const a = animator([doorUse()]);
      expect(a.use(at(150, -64, -1, 0), 0)).toBe(false);
      expect(a.active(0)).toBe(false);
    });

    it('picks the nearest line crossed; a nearest line seen from behind blocks the ones beyond', () => {
      const liftSwitch = (x: number, flip = false): MoverTrigger => ({
        line: flip ? [x, 0, x, -128] : [x, -128, x, 0], activation: 'use', repeatable: true, movers: [1], action: 'lower-wait-raise', speed: 140, wait: 3, reverses: false,
      });
      const nearer = animator([doorUse(), liftSwitch(120)]);
      expect(nearer.use(at(100, -64), 0)).toBe(true);
      expect([nearer.active(0), nearer.active(1)]).toEqual([false, true]);
      const farther = animator([liftSwitch(150), doorUse()]);
      expect(farther.use(at(100, -64), 0)).toBe(true);
      expect([farther.active(0), farther.active(1)]).toEqual([true, false]);
      const behind = animator([doorUse(), liftSwitch(120, true)]);
      expect(behind.use(at(100, -64), 0)).toBe(false);
      expect([behind.active(0), behind.active(1)]).toEqual([false, false]);
    });

    it('is stopped by a wall or a shut door between the player and the line, not by an open one', () => {
      // A walk map with one line across the way at x = 110, between sectors 0 and 1 (or a wall).
      const across = (back: number, floors = [0, 0], ceilings = [128, 128]): WalkMap => ({
        lines: new Float32Array([110, -128, 110, 0]), lineSectors: new Int32Array([0, back]), lineBlocks: new Uint8Array([0]),
        floors: new Float32Array([...floors, 0, 0]), ceilings: new Float32Array([...ceilings, 0, 0]), eyeHeight: 41, stepHeight: 24, bodyHeight: 56, radius: 16,
      });
      const use = (map: WalkMap) => new MoverAnimator({ movers: [DOOR, LIFT], triggers: [doorUse()], useRange: 64, body: { radius: 16, height: 56 } }, map).use(at(100, -64), 0);
      expect(use(across(1))).toBe(true); // an opening
      expect(use(across(-1))).toBe(false); // a wall
      expect(use(across(1, [0, 64], [128, 64]))).toBe(false); // shut: no room between floor and ceiling
      // The door's own face is a shut opening too (sector 2, the closed door), but it is what the key uses.
      const withDoorFace: WalkMap = { ...across(1), lines: new Float32Array([110, -128, 110, 0, 128, -128, 128, 0]), lineSectors: new Int32Array([0, 1, 0, 2]), lineBlocks: new Uint8Array([0, 0]) };
      expect(use(withDoorFace)).toBe(true);
    });

    it('sends a manual door back: a waiting door closes, a closing door reopens', () => {
      const a = animator([doorUse()]);
      a.use(at(100, -64), 0);
      run(a, 0, 100 * TIC); // open (62 tics) and waiting
      expect(a.use(at(100, -64), 100 * TIC)).toBe(true);
      run(a, 100 * TIC, 110 * TIC);
      expect(a.ceilings[0]).toBeCloseTo(124 - 20, 4);
      expect(a.use(at(100, -64), 110 * TIC)).toBe(true);
      run(a, 110 * TIC, 115 * TIC);
      expect(a.ceilings[0]).toBeCloseTo(124 - 10, 4);
    });

    it('uses a once-only door line (31) once', () => {
      const a = animator([doorUse({ repeatable: false, action: 'open', reverses: false })]);
      expect(a.use(at(100, -64), 0)).toBe(true);
      run(a, 0, 100 * TIC);
      expect(a.ceilings[0]).toBeCloseTo(124, 6);
      expect(a.active(0)).toBe(false); // open and staying
      expect(a.use(at(100, -64), 100 * TIC)).toBe(false);
    });
  });

  describe('walk-over lines', () => {
    const walkLine = (repeatable: boolean): MoverTrigger => ({
      line: [64, -128, 64, 0], activation: 'walk', repeatable, movers: [0], action: 'open-wait-close', speed: 70, wait: 150 / 35, reverses: false,
    });

    it('fire when the centre crosses them, either way, and not when it stops short', () => {
      const a = animator([walkLine(true)]);
      a.walked(40, -64, 60, -64, 0);
      expect(a.active(0)).toBe(false);
      a.walked(80, -64, 60, -64, 0); // westward
      expect(a.active(0)).toBe(true);
    });

    it('once-only lines fire once; repeatable ones again after the door closed', () => {
      for (const repeatable of [false, true]) {
        const a = animator([walkLine(repeatable)]);
        a.walked(50, -64, 70, -64, 0);
        expect(a.active(0)).toBe(true);
        run(a, 0, 300 * TIC);
        expect(a.active(0)).toBe(false);
        expect(a.ceilings[0]).toBeCloseTo(0, 4);
        a.walked(70, -64, 50, -64, 300 * TIC);
        expect(a.active(0)).toBe(repeatable);
      }
    });
  });

  it('reopens a closing door over the player, who it would squeeze below 56 units', () => {
    const a = animator([doorUse()]);
    a.use(at(100, -64), 0);
    run(a, 0, 212 * TIC); // open, waited, closing since tic 212
    const inDoorway = at(136, -64);
    let lowest = Infinity;
    for (let tic = 212; tic < 400; tic++) {
      a.step((tic + 1) * TIC, TIC, inDoorway, new UpdateBuilder(), false);
      lowest = Math.min(lowest, a.ceilings[0]!);
    }
    expect(lowest).toBeGreaterThanOrEqual(56);
    expect(lowest).toBeLessThan(60);
    // Standing just outside (more than the radius from its edge) the door closes.
    run(a, 400 * TIC, 700 * TIC, at(100, -64));
    expect(a.ceilings[0]).toBeCloseTo(0, 4);
  });
});
