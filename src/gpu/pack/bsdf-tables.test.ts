import { describe, expect, it } from 'vitest';
import { SHADER_MODULES } from '../../shaders/index.ts';
import {
  BSDF_TABLE_GLASS_IOR_SIZE,
  BSDF_TABLE_GLASS_MU_SIZE,
  BSDF_TABLE_GLASS_ROUGHNESS_SIZE,
  BSDF_TABLE_IOR_MAX,
  BSDF_TABLE_IOR_MIN,
  BSDF_TABLE_LAYOUT,
  BSDF_TABLE_MU_SIZE,
  BSDF_TABLE_ROUGHNESS_SIZE,
  BSDF_TABLE_TEXTURE_WIDTH,
  bsdfTableTexture,
  bsdfTableData,
  conductorAlbedo,
  fresnelDielectric,
  ggxLambda,
  glassAlbedo,
} from './bsdf-tables.ts';

/** `const NAME: type = value;` lines of a WGSL module, by name. */
function wgslConstants(module: string): Map<string, number> {
  const source = SHADER_MODULES.get(module);
  if (source === undefined) throw new Error(`no module ${module}`);
  const out = new Map<string, number>();
  for (const m of source.matchAll(/^const\s+(\w+)\s*:\s*\w+\s*=\s*([0-9.eE+-]+)u?\s*;/gm)) out.set(m[1]!, Number(m[2]));
  return out;
}

/**
 * E1 by brute force over incident directions (not through the visible normals the table uses):
 * ∫ D G2 / (4 μo μi) μi dωi on a midpoint grid in (cos θi, φ), with the GGX D written out here.
 */
function conductorAlbedoBruteForce(mu: number, alpha: number, n = 400): number {
  const wo = [Math.sqrt(1 - mu * mu), 0, mu] as const;
  const a2 = alpha * alpha;
  let sum = 0;
  for (let i = 0; i < n; i++) {
    const ci = (i + 0.5) / n;
    const si = Math.sqrt(1 - ci * ci);
    for (let j = 0; j < n; j++) {
      const phi = ((j + 0.5) / n) * 2 * Math.PI;
      const wi = [si * Math.cos(phi), si * Math.sin(phi), ci];
      const h = [wo[0] + wi[0]!, wo[1] + wi[1]!, wo[2] + wi[2]!];
      const len = Math.hypot(h[0]!, h[1]!, h[2]!);
      const mz = h[2]! / len;
      const t = mz * mz * (a2 - 1) + 1;
      const d = a2 / (Math.PI * t * t);
      const g2 = 1 / (1 + ggxLambda(mu, alpha) + ggxLambda(ci, alpha));
      sum += (d * g2) / (4 * mu * ci) * ci;
    }
  }
  return sum * (1 / n) * ((2 * Math.PI) / n);
}

describe('BSDF energy tables', () => {
  it('has the layout the WGSL module reads (sizes, offsets, ior range)', () => {
    const start = performance.now();
    const cpu = process.cpuUsage();
    bsdfTableData();
    const used = process.cpuUsage(cpu);
    console.log(`bsdf tables built in ${(performance.now() - start).toFixed(0)} ms (${((used.user + used.system) / 1000).toFixed(0)} ms of CPU)`);
    const c = wgslConstants('scene/bsdf-tables');
    expect(c.get('BSDF_TABLE_MU_SIZE')).toBe(BSDF_TABLE_MU_SIZE);
    expect(c.get('BSDF_TABLE_ROUGHNESS_SIZE')).toBe(BSDF_TABLE_ROUGHNESS_SIZE);
    expect(c.get('BSDF_TABLE_GLASS_MU_SIZE')).toBe(BSDF_TABLE_GLASS_MU_SIZE);
    expect(c.get('BSDF_TABLE_GLASS_ROUGHNESS_SIZE')).toBe(BSDF_TABLE_GLASS_ROUGHNESS_SIZE);
    expect(c.get('BSDF_TABLE_GLASS_IOR_SIZE')).toBe(BSDF_TABLE_GLASS_IOR_SIZE);
    expect(c.get('BSDF_TABLE_IOR_MIN')).toBeCloseTo(BSDF_TABLE_IOR_MIN, 6);
    expect(c.get('BSDF_TABLE_IOR_MAX')).toBeCloseTo(BSDF_TABLE_IOR_MAX, 6);
    for (const [key, value] of Object.entries(BSDF_TABLE_LAYOUT)) expect(c.get(`BSDF_TABLE_${key}`), key).toBe(value);
    expect(bsdfTableData().length).toBe(BSDF_TABLE_LAYOUT.SIZE);
    // The texture holds every value, rows of the width the WGSL lookup divides by.
    expect(c.get('BSDF_TABLE_TEXTURE_WIDTH')).toBe(BSDF_TABLE_TEXTURE_WIDTH);
    const texture = bsdfTableTexture();
    expect(texture.width * texture.height).toBeGreaterThanOrEqual(BSDF_TABLE_LAYOUT.SIZE);
    expect(Array.from(texture.data.subarray(0, BSDF_TABLE_LAYOUT.SIZE))).toEqual(Array.from(bsdfTableData()));
  });

  it('is built once per process (the second call returns the cached array)', () => {
    const start = performance.now();
    const t = bsdfTableData();
    console.log(`bsdf tables: ${(performance.now() - start).toFixed(0)} ms (first call in this file: the layout test)`);
    expect(bsdfTableData()).toBe(t);
  });

  it('E1 agrees with a brute-force integral over incident directions (to the table\'s ~1e-3)', () => {
    for (const [mu, alpha] of [[0.9, 1], [0.3, 1], [0.1, 0.5625], [0.6, 0.25], [0.5, 0.0625]] as const) {
      const reference = conductorAlbedoBruteForce(mu, alpha);
      expect(Math.abs(conductorAlbedo(mu, alpha).e1 - reference), `μ ${mu} α ${alpha}: ${reference}`).toBeLessThan(2e-3);
    }
  });

  it('shows the energy single scattering loses: a rough white conductor keeps under half on average', () => {
    const t = bsdfTableData();
    const L = BSDF_TABLE_LAYOUT;
    const last = (BSDF_TABLE_ROUGHNESS_SIZE - 1) * BSDF_TABLE_MU_SIZE;
    // Roughness 1: E1 ≈ 0.31 at normal incidence and E1avg ≈ 0.41 — the compensation lobe has to
    // bring back up to ~60 % (the GPU furnace test shows it does, to 1 %).
    expect(t[L.E1_AVG_OFFSET + BSDF_TABLE_ROUGHNESS_SIZE - 1]!).toBeLessThan(0.6);
    expect(t[L.E1_OFFSET + last + BSDF_TABLE_MU_SIZE - 1]!).toBeLessThan(0.8);
    // Smooth: nothing lost, E1 = 1, and E5 = (1 − μ)⁵ (the Schlick weight at the mirror normal).
    for (const j of [1, 8, 20, 31]) {
      const mu = j / (BSDF_TABLE_MU_SIZE - 1);
      expect(t[L.E1_OFFSET + j]!).toBeCloseTo(1, 3);
      expect(t[L.E5_OFFSET + j]!).toBeCloseTo((1 - mu) ** 5, 3);
    }
    // Every albedo is in [0, 1].
    expect(Math.min(...t)).toBeGreaterThanOrEqual(0);
    expect(Math.max(...t)).toBeLessThanOrEqual(1 + 1e-6);
  });

  it('E1avg is 2∫E1(μ)μ dμ of the tabulated curve', () => {
    const t = bsdfTableData();
    const L = BSDF_TABLE_LAYOUT;
    for (const i of [5, 16, 31]) {
      // Fine midpoint rule over the piecewise-linear interpolant.
      const n = 20000;
      let sum = 0;
      for (let k = 0; k < n; k++) {
        const mu = (k + 0.5) / n;
        const x = mu * (BSDF_TABLE_MU_SIZE - 1);
        const j = Math.min(Math.floor(x), BSDF_TABLE_MU_SIZE - 2);
        const f = x - j;
        const e = t[L.E1_OFFSET + i * BSDF_TABLE_MU_SIZE + j]! * (1 - f) + t[L.E1_OFFSET + i * BSDF_TABLE_MU_SIZE + j + 1]! * f;
        sum += 2 * e * mu / n;
      }
      expect(t[L.E1_AVG_OFFSET + i]!).toBeCloseTo(sum, 5);
    }
  });

  it('smooth glass keeps all the energy (R + T = 1, total internal reflection from inside); rough glass loses some', () => {
    expect(glassAlbedo(0.7, 1e-4, 1.5)).toBeCloseTo(1, 3);
    expect(glassAlbedo(0.7, 1e-4, 1 / 1.5)).toBeCloseTo(1, 3);
    // Beyond the critical angle (cos θc = √(1 − 1/1.5²) ≈ 0.745) from inside: R = 1.
    expect(fresnelDielectric(0.5, 1 / 1.5)).toBe(1);
    expect(glassAlbedo(0.5, 1e-4, 1 / 1.5)).toBeCloseTo(1, 3);
    expect(glassAlbedo(1, 1, 1.5)).toBeLessThan(0.95);
    // At normal incidence F = ((η − 1)/(η + 1))².
    expect(fresnelDielectric(1, 1.5)).toBeCloseTo(0.04, 6);
  });
});
