import { describe, expect, it } from 'vitest';
import { duration, frameRate, significant, withUnit } from './number-format.ts';

describe('number formatting', () => {
  it('keeps three significant figures at any magnitude, never rounding a small value to zero', () => {
    expect(significant(0.05)).toBe('0.05');
    expect(significant(0.051234)).toBe('0.0512');
    expect(significant(0.000123456)).toBe('0.000123');
    expect(significant(20.06)).toBe('20.1');
    expect(significant(1.5)).toBe('1.5');
    expect(significant(1234)).toBe('1234');
    expect(significant(-0.5)).toBe('-0.5');
    expect(significant(0)).toBe('0');
    // A carry into a new digit: 9.996 at three figures is 10, not "10.00".
    expect(significant(9.996)).toBe('10');
    expect(significant(0.09996)).toBe('0.1');
  });

  it('every positive value reads back within half a unit of its last shown figure', () => {
    // A round trip over 12 decades: the text parses to the value within the rounding of 3 figures.
    for (let e = -6; e <= 6; e += 0.37) {
      const v = 10 ** e;
      const back = Number(significant(v));
      expect(back).toBeGreaterThan(0);
      expect(Math.abs(back - v) / v).toBeLessThanOrEqual(0.005 + 1e-12);
    }
  });

  it('writes rates with SI prefixes: 20 k rays/s, not 0.0 M', () => {
    expect(withUnit(20_000, 'rays/s')).toBe('20 k rays/s');
    expect(withUnit(1_234_567, 'rays/s')).toBe('1.23 M rays/s');
    expect(withUnit(3.2e9, 'rays/s')).toBe('3.2 G rays/s');
    expect(withUnit(999, 'rays/s')).toBe('999 rays/s');
    expect(withUnit(0.5, 'rays/s')).toBe('0.5 rays/s');
    // The boundary: what would round to "1000 k" is written "1 M".
    expect(withUnit(999_960, 'rays/s')).toBe('1 M rays/s');
    expect(withUnit(999_400, 'rays/s')).toBe('999 k rays/s');
  });

  it('writes durations in the unit that fits them', () => {
    expect(duration(0.42)).toBe('0.42 ms');
    expect(duration(16.666)).toBe('16.7 ms');
    expect(duration(850)).toBe('850 ms');
    expect(duration(20_100)).toBe('20.1 s');
    expect(duration(150_000)).toBe('2.5 min');
    expect(duration(2 * 3600_000)).toBe('2 h');
  });

  it('writes slow frame rates with the time a frame takes', () => {
    expect(frameRate(60)).toBe('60 fps');
    expect(frameRate(12.48)).toBe('12.5 fps');
    expect(frameRate(0.05)).toBe('0.05 fps (20 s a frame)');
    expect(frameRate(1 / 20.1)).toBe('0.05 fps (20.1 s a frame)');
    expect(frameRate(0)).toBe('– fps');
    for (const fps of [0.007, 0.05, 0.3, 0.99]) expect(frameRate(fps)).not.toMatch(/^0(\.0+)? fps/);
  });
});
