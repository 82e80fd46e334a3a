import { describe, expect, it } from 'vitest';
import { megaRays } from './render.ts';

describe('render summary', () => {
  it('gives rays per second figures that fit the magnitude, never 0.0 for a slow adapter', () => {
    expect(megaRays(4_459_000_000)).toBe('4459');
    expect(megaRays(12_345_678)).toBe('12.3');
    expect(megaRays(52_345)).toBe('0.0523');
    expect(megaRays(0)).toBe('0');
  });
});
