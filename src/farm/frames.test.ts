import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../expect-lantern-error.ts';
import { formatIntRange, parseFrames, parseIntRange, parseSampleRange } from './frames.ts';

describe('frame lists', () => {
  it('reads ranges, lists and steps as Open Job Description writes them, sorted and each once', () => {
    expect(parseIntRange('0-3', 'r')).toEqual([0, 1, 2, 3]);
    expect(parseIntRange('1-3,47,2', 'r')).toEqual([1, 2, 3, 47]);
    expect(parseIntRange('0-8:4', 'r')).toEqual([0, 4, 8]);
    expect(parseIntRange(' 5-5 ', 'r')).toEqual([5]);
  });
  it('keeps a plain count as the old --frames meaning: frames 0 to n - 1', () => {
    expect(parseFrames('3')).toEqual([0, 1, 2]);
    expect(parseFrames('2-4')).toEqual([2, 3, 4]);
  });
  it('refuses what is not a range, in one line', () => {
    for (const bad of ['', 'a-b', '3-1', '1-2:0', '1,,2', '-3', '0']) expect(() => (bad === '0' ? parseFrames(bad) : parseIntRange(bad, '--frames')), bad).toThrow();
    expectLanternError(() => parseIntRange('3-1', '--frames'), /ends before it starts/);
  });
  it('writes a list back short, and reads sample ranges as half-open', () => {
    expect(formatIntRange([0, 1, 2, 3, 7, 9, 10])).toBe('0-3,7-7,9-10');
    expect(parseIntRange(formatIntRange([0, 1, 2, 3, 7, 9, 10]), 'r')).toEqual([0, 1, 2, 3, 7, 9, 10]);
    expect(parseSampleRange('8-15', '--samples')).toEqual({ start: 8, end: 16 });
    expect(() => parseSampleRange('8', '--samples')).toThrow(/first-last/);
  });
});
