import { describe, expect, it } from 'vitest';
import { NO_INPUT } from './camera-controller.ts';
import { KeyTimeline } from './key-timeline.ts';

const total = (spans: { seconds: number }[]) => spans.reduce((s, x) => s + x.seconds, 0);

describe('KeyTimeline', () => {
  it('a press that begins and ends between two frames still counts, for exactly its held time', () => {
    const k = new KeyTimeline(0);
    k.press('KeyW', 1000);
    k.release('KeyW', 4000);
    const spans = k.take(10_000);
    expect(total(spans)).toBeCloseTo(10, 9);
    const held = spans.filter((s) => s.input.forward === 1);
    expect(held).toHaveLength(1);
    expect(held[0]!.seconds).toBeCloseTo(3, 9);
    // Nothing is held now: the next take is idle time only.
    expect(k.take(12_000)).toEqual([{ input: NO_INPUT, seconds: 2 }]);
  });

  it('a key held across frames counts up to each take, auto-repeat changes nothing, and Shift runs', () => {
    const k = new KeyTimeline(0);
    k.press('ArrowRight', 0);
    k.press('ArrowRight', 500);
    expect(k.take(1000)).toEqual([{ input: { forward: 0, right: 0, up: 0, turn: 1, run: false }, seconds: 1 }]);
    k.press('ShiftLeft', 1500);
    const spans = k.take(2000);
    expect(spans.map((s) => [s.input.run, s.seconds])).toEqual([
      [false, 0.5],
      [true, 0.5],
    ]);
  });

  it('opposite keys cancel, losing focus lets everything go, and restart forgets held time', () => {
    const k = new KeyTimeline(0);
    k.press('KeyW', 0);
    k.press('KeyS', 0);
    expect(k.take(1000)).toEqual([{ input: NO_INPUT, seconds: 1 }]);
    k.releaseAll(1500);
    expect(k.active).toBe(false);
    k.press('KeyD', 2000);
    k.restart(5000);
    expect(k.take(6000)).toEqual([{ input: { forward: 0, right: 1, up: 0, turn: 0, run: false }, seconds: 1 }]);
    // Keys that do not move are not tracked.
    k.press('KeyQ', 6000);
    expect(k.move).toEqual({ forward: 0, right: 1, up: 0, turn: 0, run: false });
  });
});
