import { InvalidArgumentError } from 'commander';
import { describe, expect, it } from 'vitest';
import { numberListOption, pathOption } from './options.ts';

describe('option parsers', () => {
  it('takes a list of finite numbers within the limit, and names the one out of range', () => {
    const camera = numberListOption('--camera', [6], 1e7);
    expect(camera('1, 2, 3, -4e6, 0, 1e7')).toEqual([1, 2, 3, -4e6, 0, 1e7]);
    // 1e308 is finite, but the difference of two such numbers is not.
    expect(() => camera('1e308,0,0,0,0,0')).toThrow(new InvalidArgumentError('--camera takes numbers from -10000000 to 10000000, not 1e+308.'));
    expect(() => camera('0,0,0,0,0,-1.5e7')).toThrow(/not -15000000/);
    expect(() => camera('1,2,3,4,5')).toThrow(/takes 6 comma-separated numbers/);
    expect(() => camera('1,2,3,4,5,Infinity')).toThrow(/takes 6 comma-separated numbers/);
    expect(numberListOption('--sky', [2, 3])('1e308,5')).toEqual([1e308, 5]);
  });

  it('refuses an empty file name and one holding NUL', () => {
    const out = pathOption('--out');
    expect(out('a b/c.png')).toBe('a b/c.png');
    expect(() => out('')).toThrow(/--out needs a file name, not an empty one/);
    expect(() => out('  ')).toThrow(/--out needs a file name/);
    expect(() => out('a\0b')).toThrow(/NUL/);
  });
});
