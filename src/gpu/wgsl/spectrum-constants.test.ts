/**
 * shaders/lib/spectrum.wgsl mirrors math/spectrum.ts (WGSL constants cannot be read back by
 * reflection): every number the shader uses is held to the TypeScript twin here.
 */
import { describe, expect, it } from 'vitest';
import {
  LAMBDA_MAX, LAMBDA_MIN, RGB_FROM_XYZ, SPECTRAL_BASIS_LOGITS, SPECTRAL_BASIS_X_CENTER, SPECTRAL_BASIS_X_SCALE, WAVELENGTH_CENTER,
  WAVELENGTH_SHARPNESS, Y_INTEGRAL,
} from '../../math/spectrum.ts';
import { SHADER_MODULES } from '../../shaders/index.ts';

const source = SHADER_MODULES.get('lib/spectrum')!;

function constant(name: string): number[] {
  const m = new RegExp(`const ${name}: (?:f32|vec3f) = (?:vec3f\\()?([^;]+?)\\)?;`).exec(source);
  if (!m) throw new Error(`lib/spectrum.wgsl has no constant ${name}`);
  return m[1]!.split(',').map((s) => Number(s.trim()));
}

describe('lib/spectrum.wgsl', () => {
  it('uses the span, sampling density and normalization of math/spectrum.ts', () => {
    expect(constant('SPECTRUM_LAMBDA_MIN')[0]).toBe(LAMBDA_MIN);
    expect(constant('SPECTRUM_LAMBDA_MAX')[0]).toBe(LAMBDA_MAX);
    expect(constant('SPECTRUM_SAMPLING_SHARPNESS')[0]).toBe(WAVELENGTH_SHARPNESS);
    expect(constant('SPECTRUM_SAMPLING_CENTER')[0]).toBe(WAVELENGTH_CENTER);
    expect(constant('SPECTRUM_SAMPLING_T0')[0]).toBeCloseTo(Math.tanh(WAVELENGTH_SHARPNESS * (LAMBDA_MIN - WAVELENGTH_CENTER)), 12);
    expect(constant('SPECTRUM_SAMPLING_T1')[0]).toBeCloseTo(Math.tanh(WAVELENGTH_SHARPNESS * (LAMBDA_MAX - WAVELENGTH_CENTER)), 12);
    expect(constant('SPECTRUM_Y_INTEGRAL')[0]).toBeCloseTo(Y_INTEGRAL, 6);
  });
  it('uses the basis logits of math/spectrum.ts', () => {
    expect(constant('SPECTRUM_BASIS_X_CENTER')[0]).toBe(SPECTRAL_BASIS_X_CENTER);
    expect(constant('SPECTRUM_BASIS_X_SCALE')[0]).toBe(SPECTRAL_BASIS_X_SCALE);
    SPECTRAL_BASIS_LOGITS.red.forEach((c, i) => expect(constant(`SPECTRUM_BASIS_RED_${i}`)[0]).toBe(c));
    SPECTRAL_BASIS_LOGITS.blue.forEach((c, i) => expect(constant(`SPECTRUM_BASIS_BLUE_${i}`)[0]).toBe(c));
  });
  it('uses the output matrix of math/spectrum.ts', () => {
    for (let r = 0; r < 3; r++) {
      const row = constant(`SPECTRUM_RGB_FROM_XYZ_${r}`);
      for (let c = 0; c < 3; c++) expect(row[c]).toBeCloseTo(RGB_FROM_XYZ[r]![c]!, 7);
    }
  });
});
