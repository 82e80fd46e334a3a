import { describe, expect, it } from 'vitest';
import { luminance, type Vec3 } from '../math/vec3.ts';
import { directionFromElevationAzimuth } from './environment.ts';
import { LUMENS_PER_WATT, SkyModel, SUN_ANGULAR_RADIUS_DEG } from './sky.ts';

const sky = (sunElevationDeg: number, turbidity = 3, groundAlbedo = 0.3, sunAzimuthDeg = 0) =>
  new SkyModel({ sunElevationDeg, sunAzimuthDeg, turbidity, groundAlbedo });
const at = (m: SkyModel, elevationDeg: number, azimuthDeg: number): Vec3 => m.radiance(directionFromElevationAzimuth(elevationDeg, azimuthDeg));
const lum = (c: Vec3) => luminance(c);

/** Illuminance (lux) on a horizontal plane from the sky dome alone, midpoint rule in (cos θ, φ). */
function skyIlluminance(m: SkyModel): number {
  const rows = 64, columns = 128;
  let e = 0;
  for (let j = 0; j < rows; j++) {
    const ct = (j + 0.5) / rows, st = Math.sqrt(1 - ct * ct);
    for (let k = 0; k < columns; k++) {
      const p = ((k + 0.5) / columns) * 2 * Math.PI;
      e += lum(m.radiance([st * Math.sin(p), ct, st * Math.cos(p)])) * ct;
    }
  }
  return (e * 2 * Math.PI * LUMENS_PER_WATT) / (rows * columns);
}

/** Direct-sun illuminance (lux) on a horizontal plane: L Ω sin(elevation). */
function sunIlluminance(m: SkyModel): number {
  return lum(m.sunRadiance) * 2 * Math.PI * (1 - m.sunCosMax) * m.sunDirection[1] * LUMENS_PER_WATT;
}

describe('Hosek–Wilkie sky', () => {
  it('is positive, finite and continuous over the upper hemisphere (no seams in the fit)', () => {
    for (const [elevation, turbidity] of [[5, 2], [30, 4], [70, 8]] as const) {
      const m = sky(elevation, turbidity);
      let worst = 0;
      // Steps of 0.25° in elevation and azimuth everywhere above the horizon, sun included.
      for (let e = 0.5; e < 89.5; e += 3) {
        for (let a = 0; a < 360; a += 3) {
          const l0 = lum(at(m, e, a));
          expect(Number.isFinite(l0) && l0 > 0).toBe(true);
          const l1 = lum(at(m, e + 0.25, a)), l2 = lum(at(m, e, a + 0.25));
          worst = Math.max(worst, Math.abs(l1 - l0) / l0, Math.abs(l2 - l0) / l0);
        }
      }
      // The steepest place, the aureole near the sun, changes by a few % per 0.25°; a seam or a
      // wrong parameter order shows as jumps of tens of %.
      expect(worst).toBeLessThan(0.1);
    }
  });

  it('is brighter on the sun side than opposite it, at the same elevation', () => {
    for (const elevation of [10, 30, 60]) {
      const m = sky(elevation, 3, 0.3, 40);
      for (const viewElevation of [5, 20, 45]) expect(lum(at(m, viewElevation, 40 + 20))).toBeGreaterThan(lum(at(m, viewElevation, 40 + 180)));
    }
  });

  it('brightens toward the horizon away from the sun (clear skies), and fits continuously to the zenith', () => {
    // Horizon brightening of clear skies (the model's (1 + A e^{B / cos θ}) term, A < 0): at 90° of
    // azimuth from the sun, 5° above the horizon is brighter than the zenith.
    for (const t of [2, 3, 5]) {
      for (const elevation of [10, 30, 60]) {
        const m = sky(elevation, t);
        expect(lum(at(m, 5, 90))).toBeGreaterThan(lum(at(m, 90, 90)));
        // The zenith is one direction: every azimuth agrees there.
        expect(lum(at(m, 90, 0))).toBeCloseTo(lum(at(m, 90, 180)), 9);
      }
    }
  });

  it('is bluer at the zenith than at the horizon (Rayleigh), and whitens with turbidity', () => {
    const blueness = (c: Vec3) => c[2] / c[0];
    for (const t of [2, 5, 9]) {
      const m = sky(40, t);
      expect(blueness(at(m, 90, 0))).toBeGreaterThan(blueness(at(m, 2, 180)));
    }
    const zenith = [1.5, 3, 5, 7, 9].map((t) => blueness(at(sky(40, t), 90, 0)));
    for (let i = 1; i < zenith.length; i++) expect(zenith[i]!).toBeLessThan(zenith[i - 1]!);
  });

  it('turbidity brightens the sky dome and dims the sun (more scattering, less direct light)', () => {
    const dome = [2, 4, 6, 8, 10].map((t) => skyIlluminance(sky(45, t)));
    const sun = [2, 4, 6, 8, 10].map((t) => sunIlluminance(sky(45, t)));
    for (let i = 1; i < dome.length; i++) {
      expect(dome[i]!).toBeGreaterThan(dome[i - 1]!);
      expect(sun[i]!).toBeLessThan(sun[i - 1]!);
    }
  });

  it('the sky dome brightens as the sun rises', () => {
    const dome = [5, 15, 30, 50, 80].map((e) => skyIlluminance(sky(e)));
    for (let i = 1; i < dome.length; i++) expect(dome[i]!).toBeGreaterThan(dome[i - 1]!);
  });

  it('gives daylight in measured ranges: clear sky, sun at 45°', () => {
    // Measured clear-sky daylight (e.g. CIE 110-1994 and IES daylight tables): direct sun on the
    // ground 50–90 klx, diffuse sky 10–25 klx, zenith luminance 2–8 kcd/m².
    const m = sky(45, 3);
    expect(sunIlluminance(m)).toBeGreaterThan(50_000);
    expect(sunIlluminance(m)).toBeLessThan(90_000);
    expect(skyIlluminance(m)).toBeGreaterThan(10_000);
    expect(skyIlluminance(m)).toBeLessThan(25_000);
    const zenith = lum(at(m, 90, 0)) * LUMENS_PER_WATT;
    expect(zenith).toBeGreaterThan(2000);
    expect(zenith).toBeLessThan(8000);
  });

  it('sun: disk of 0.2667° pointing at the given elevation and azimuth, reddened low', () => {
    const m = sky(30, 3, 0.3, 90);
    expect(Math.acos(m.sunCosMax) * (180 / Math.PI)).toBeCloseTo(SUN_ANGULAR_RADIUS_DEG, 6);
    // Azimuth 90: from +z toward +x, so the sun is in +x at 30° elevation.
    expect(m.sunDirection[0]).toBeCloseTo(Math.cos(Math.PI / 6), 9);
    expect(m.sunDirection[1]).toBeCloseTo(0.5, 9);
    expect(m.sunDirection[2]).toBeCloseTo(0, 9);
    const low = sky(3).sunRadiance, high = sky(60).sunRadiance;
    expect(low[2] / low[0]).toBeLessThan(high[2] / high[0]);
    expect(sky(-5).sunVisible).toBe(false);
    expect(sky(-5).sunRadiance).toEqual([0, 0, 0]);
  });

  it('below the horizon shows a Lambertian ground: albedo × (sky + sun irradiance) / π', () => {
    const m = sky(45, 3, 0.5);
    const ground = lum(at(m, -30, 0));
    const expected = (0.5 / Math.PI) * (skyIlluminance(m) + sunIlluminance(m)) / LUMENS_PER_WATT;
    expect(ground / expected).toBeGreaterThan(0.99);
    expect(ground / expected).toBeLessThan(1.01);
    expect(lum(at(sky(45, 3, 0), -30, 0))).toBe(0);
  });
});
