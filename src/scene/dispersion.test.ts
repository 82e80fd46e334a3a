import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../expect-lantern-error.ts';
import { abbeNumberOf, cauchyFromAbbe, GLASSES, iorAt, LAMBDA_C, LAMBDA_D, LAMBDA_F, packDispersion, validateDispersion } from './dispersion.ts';

describe('dispersion laws', () => {
  it("give BK7's catalogue indices (Schott N-BK7: n_d 1.5168, n_F 1.5224, n_C 1.5143)", () => {
    // The catalogue prints four decimals: agree to within its rounding (and the lines' 0.1 nm).
    expect(Math.abs(iorAt(1.5168, GLASSES.BK7, 589.3) - 1.5168)).toBeLessThan(1e-4);
    expect(Math.abs(iorAt(1.5168, GLASSES.BK7, 486.1) - 1.5224)).toBeLessThan(1e-4);
    expect(Math.abs(iorAt(1.5168, GLASSES.BK7, 656.3) - 1.5143)).toBeLessThan(1e-4);
    // And the law itself, unscaled: scale ≈ 1 at BK7's own n_d.
    expect(packDispersion(1.5168, GLASSES.BK7).scale).toBeCloseTo(1, 3);
    expect(abbeNumberOf(1.5168, GLASSES.BK7)).toBeCloseTo(64.17, 0);
  });
  it('give the other named glasses their catalogue n_d and Abbe numbers', () => {
    const cases = [['F2', 1.62004, 36.37], ['SF11', 1.78472, 25.68], ['fused silica', 1.4585, 67.8]] as const;
    for (const [name, nd, vd] of cases) {
      const d = GLASSES[name];
      expect(packDispersion(nd, d).scale).toBeCloseTo(1, 3);
      expect(abbeNumberOf(nd, d)).toBeGreaterThan(vd - 0.6);
      expect(abbeNumberOf(nd, d)).toBeLessThan(vd + 0.6);
    }
  });
  it('pass through ior at 589.3 nm and keep the Abbe number when scaled to another ior', () => {
    expect(iorAt(1.7, GLASSES.BK7, LAMBDA_D)).toBeCloseTo(1.7, 10);
    expect(abbeNumberOf(1.7, GLASSES.BK7)).toBeCloseTo(abbeNumberOf(1.5168, GLASSES.BK7), 8);
    expect(iorAt(1.5, undefined, 400)).toBe(1.5);
  });
  it('turn an Abbe number into the Cauchy law with that n_d and n_F − n_C', () => {
    const d = { kind: 'abbe', abbeNumber: 40 } as const;
    expect(iorAt(1.6, d, LAMBDA_D)).toBeCloseTo(1.6, 10);
    expect(iorAt(1.6, d, LAMBDA_F) - iorAt(1.6, d, LAMBDA_C)).toBeCloseTo(0.6 / 40, 10);
    const c = cauchyFromAbbe(1.6, 40);
    expect(iorAt(1.6, c, 450)).toBeCloseTo(iorAt(1.6, d, 450), 10);
    // Normal dispersion: blue bends more.
    expect(iorAt(1.6, d, 450)).toBeGreaterThan(iorAt(1.6, d, 650));
  });
  it('refuse laws that give no index', () => {
    expectLanternError(() => validateDispersion('material "x"', 1.5, { kind: 'abbe', abbeNumber: 0 }), /Abbe number 0/);
    expectLanternError(() => validateDispersion('material "x"', 1.5, { kind: 'sellmeier', B: [1, 0, 0], C: [0.25, 0, 0] }), /pole/);
    expectLanternError(() => validateDispersion('material "x"', 1.5, { kind: 'cauchy', A: Number.NaN, B: 0 }), /A = NaN/);
    validateDispersion('material "x"', 1.5, GLASSES.SF11);
  });
});
