import { describe, expect, it } from 'vitest';
import { fromTrs, IDENTITY, invertAffine, multiply, translation } from './mat4.ts';

describe('invertAffine', () => {
  it('gives the inverse of rotations, mirrors, non-uniform scales and translations', () => {
    const q = [0.2, 0.3, 0.1, Math.sqrt(1 - 0.14)] as const;
    for (const m of [fromTrs([1, 2, 3], q, [2, -1, 0.5]), translation([4, -5, 6]), IDENTITY]) {
      for (const p of [multiply(m, invertAffine(m)), multiply(invertAffine(m), m)]) p.forEach((x, k) => expect(x).toBeCloseTo(IDENTITY[k]!, 12));
    }
  });

  it('refuses a singular transform', () => {
    expect(() => invertAffine(fromTrs([0, 0, 0], [0, 0, 0, 1], [1, 0, 1]))).toThrow(RangeError);
  });
});
