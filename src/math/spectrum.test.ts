import { describe, expect, it } from 'vitest';
import {
  cieXyz, E_WHITE_XYZ, heroWavelengths, integrateSpectrum, LAMBDA_MAX, LAMBDA_MIN, liftRgb, RGB_FROM_XYZ, sampleWavelength,
  spectralBasis, spectrumToRgb, wavelengthPdf,
} from './spectrum.ts';

describe('CIE 1931 colour matching (Wyman et al. 2013 fit)', () => {
  it('is close to the CIE table at its peaks', () => {
    // CIE 1931 2° table values: ȳ(555) = 1.0000, x̄(600) = 1.0622, z̄(445) = 1.7826, x̄(445) = 0.3481.
    expect(cieXyz(555)[1]).toBeCloseTo(1.0, 1);
    expect(cieXyz(600)[0]).toBeCloseTo(1.0622, 1);
    expect(cieXyz(445)[2]).toBeCloseTo(1.7826, 1);
    expect(cieXyz(445)[0]).toBeCloseTo(0.3481, 1);
  });
  it('puts the equal-energy white near x = y = 1/3', () => {
    const [x, y, z] = E_WHITE_XYZ;
    expect(x / (x + y + z)).toBeCloseTo(1 / 3, 2);
    expect(y / (x + y + z)).toBeCloseTo(1 / 3, 2);
  });
});

describe('wavelength sampling', () => {
  it('has a density that integrates to 1 and an inverse CDF that matches it', () => {
    expect(integrateSpectrum(wavelengthPdf, 8)).toBeCloseTo(1, 5);
    // The CDF of the sampled wavelength at u is u: integrate the pdf up to sampleWavelength(u).
    for (const u of [0.1, 0.37, 0.5, 0.9]) {
      const l = sampleWavelength(u);
      let cdf = 0;
      const steps = 20000;
      for (let i = 0; i < steps; i++) cdf += wavelengthPdf(LAMBDA_MIN + ((i + 0.5) * (l - LAMBDA_MIN)) / steps) * ((l - LAMBDA_MIN) / steps);
      expect(cdf).toBeCloseTo(u, 4);
    }
    expect(sampleWavelength(0)).toBeCloseTo(LAMBDA_MIN, 6);
    expect(sampleWavelength(1 - 1e-12)).toBeCloseTo(LAMBDA_MAX, 3);
  });
  it('gives four stratified wavelengths, the hero first', () => {
    const ls = heroWavelengths(0.3);
    expect(ls[0]).toBeCloseTo(sampleWavelength(0.3), 10);
    expect(ls[3]).toBeCloseTo(sampleWavelength(0.05), 10);
    expect(new Set(ls.map((l) => Math.round(l))).size).toBe(4);
  });
  it('estimates the colour of a spectrum without bias (hero + companions, importance weights)', () => {
    // Monte Carlo average of f(λ) cmf(λ)/pdf(λ) over stratified u matches the integral.
    const f = (l: number) => 0.5 + 0.5 * Math.sin(l / 40);
    const n = 4096;
    const acc = [0, 0, 0];
    for (let i = 0; i < n; i++) {
      for (const l of heroWavelengths((i + 0.5) / n)) {
        const c = cieXyz(l);
        for (let k = 0; k < 3; k++) acc[k]! += (f(l) * c[k]!) / wavelengthPdf(l) / (4 * n);
      }
    }
    const exact = [0, 1, 2].map((k) => integrateSpectrum((l) => f(l) * cieXyz(l)[k]!, 8));
    for (let k = 0; k < 3; k++) expect(acc[k]! / exact[k]!).toBeCloseTo(1, 3);
  });
});

describe('RGB → spectrum lift', () => {
  it('is a partition of unity of non-negative basis spectra', () => {
    for (let l = LAMBDA_MIN; l <= LAMBDA_MAX; l += 5) {
      const b = spectralBasis(l);
      expect(Math.min(...b)).toBeGreaterThanOrEqual(0);
      expect(b[0] + b[1] + b[2]).toBeCloseTo(1, 12);
    }
  });
  it('lifts white to the constant 1 and keeps reflectances in [0, 1]', () => {
    for (let l = LAMBDA_MIN; l <= LAMBDA_MAX; l += 7) expect(liftRgb([1, 1, 1], l)).toBeCloseTo(1, 12);
    const colours: [number, number, number][] = [[1, 0, 0], [0, 1, 0], [0, 0, 1], [0.63, 0.065, 0.05], [0.9, 0.8, 0.1], [0.05, 0.4, 0.95]];
    for (const c of colours) {
      for (let l = LAMBDA_MIN; l <= LAMBDA_MAX; l += 3) {
        const v = liftRgb(c, l);
        expect(v).toBeGreaterThanOrEqual(Math.min(...c) - 1e-12);
        expect(v).toBeLessThanOrEqual(Math.max(...c) + 1e-12);
      }
    }
  });
  it('round-trips RGB → spectrum → XYZ → RGB (within 2·10⁻⁴ for in-gamut colours, also emission > 1)', () => {
    const colours: [number, number, number][] = [[1, 1, 1], [1, 0, 0], [0, 1, 0], [0, 0, 1], [0.63, 0.065, 0.05], [0.14, 0.45, 0.091], [0.725, 0.71, 0.68], [0.2, 0.5, 0.8], [17, 12, 4]];
    for (const c of colours) {
      const rgb = spectrumToRgb((l) => liftRgb(c, l), 8);
      for (let k = 0; k < 3; k++) expect(Math.abs(rgb[k]! - c[k]!)).toBeLessThan(2e-4 * Math.max(1, ...c));
    }
  });
  it('balances white: the equal-energy spectrum shows as (1, 1, 1)', () => {
    const rgb = spectrumToRgb(() => 1, 16);
    for (const v of rgb) expect(v).toBeCloseTo(1, 6);
    expect(RGB_FROM_XYZ.length).toBe(3);
  });
});
