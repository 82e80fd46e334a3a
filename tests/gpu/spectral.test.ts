/**
 * Spectral mode (lib/spectrum.wgsl, docs/spectral.md): the white furnace stays exact, the Cornell box
 * agrees with RGB mode, the prism's spectrum lies where its dispersion law puts it (and its in-plane
 * screen is what makes it converge), and a glass ball shows chromatic fringes only in spectral mode.
 * One Renderer serves every test, so each pipeline variant compiles once (SwiftShader is slow at it).
 */
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { builtinScene } from '../../src/loaders/builtin/index.ts';
import { PRISM_GLASS, PRISM_IOR, prismCamera, prismScene, prismTransmittance, screenPosition } from '../../src/loaders/builtin/prism.ts';
import { cieXyz, mulVec, RGB_FROM_XYZ } from '../../src/math/spectrum.ts';
import { renderProgressive } from '../../src/renderer/progressive.ts';
import { Renderer, type Accumulation } from '../../src/renderer/renderer.ts';
import type { RenderSettings } from '../../src/renderer/settings.ts';
import { MeshBuilder } from '../../src/scene/builder.ts';
import { GLASSES, iorAt } from '../../src/scene/dispersion.ts';
import { placeEachOnce } from '../../src/scene/instances.ts';
import { uvSphere } from '../../src/scene/shapes.ts';
import { diffuse, type Camera, type DielectricMaterial, type Scene } from '../../src/scene/types.ts';
import { testGpu } from './gpu-context.ts';

let renderer: Renderer;

beforeAll(async () => {
  renderer = await Renderer.create(await testGpu());
  // Progressive renders only: the real-time chain's switches off, so that its passes are not compiled.
  await renderer.compile({ spectral: true, temporal: false, denoise: false });
});
afterAll(() => renderer?.destroy());

async function render(scene: Scene, o: { width: number; height: number; spp: number; settings: Partial<RenderSettings>; camera?: Camera }): Promise<Accumulation> {
  await renderer.setScene(scene);
  await renderer.resize(o.width, o.height);
  if (o.camera) renderer.setCamera(o.camera);
  renderer.updateSettings({ torch: { enabled: false }, maxBounces: 8, ...o.settings });
  await renderProgressive(renderer, { spp: o.spp });
  return await renderer.readAccumulation();
}

const channel = (a: Accumulation, k: number) => Array.from({ length: a.width * a.height }, (_, i) => a.radiance[i * 3 + k]!);
const mean = (v: readonly number[]) => v.reduce((s, x) => s + x, 0) / v.length;
/** Standard error of the mean of independent values. */
const standardError = (v: readonly number[]) => {
  const m = mean(v);
  return Math.sqrt(v.reduce((s, x) => s + (x - m) ** 2, 0) / (v.length - 1) / v.length);
};
/** Column means over all rows, per channel. */
function columnMeans(a: Accumulation, k: number, rows?: readonly number[]): number[] {
  const ys = rows ?? Array.from({ length: a.height }, (_, y) => y);
  return Array.from({ length: a.width }, (_, x) => mean(ys.map((y) => a.radiance[(y * a.width + x) * 3 + k]!)));
}

describe('spectral mode', () => {
  it('keeps the white furnace at 5.0 in every channel', async () => {
    const acc = await render(builtinScene('furnace'), { width: 16, height: 16, spp: 128, settings: { spectral: true, maxBounces: 128, seed: 3 } });
    for (let k = 0; k < 3; k++) {
      const v = channel(acc, k);
      // Every pixel estimates 5 (the image is uniform), so their spread is the Monte Carlo error.
      expect(Math.abs(mean(v) - 5)).toBeLessThan(4 * standardError(v) + 0.01);
    }
  });

  it('agrees with RGB mode on the Cornell box (to the upsampling: mean colour within 3 % + 4 standard errors)', async () => {
    const o = { width: 24, height: 24, spp: 64 };
    const rgb = await render(builtinScene('cornell'), { ...o, settings: { spectral: false, seed: 5 } });
    const spectral = await render(builtinScene('cornell'), { ...o, settings: { spectral: true, seed: 6 } });
    for (let k = 0; k < 3; k++) {
      // Per pixel the two renders estimate (nearly) the same value: their difference's spread over the
      // pixels is the Monte Carlo error of the difference of the means.
      const a = channel(rgb, k), b = channel(spectral, k);
      const diff = a.map((x, i) => b[i]! - x);
      const tolerance = 4 * standardError(diff) + 0.03 * mean(a);
      console.log(`Cornell box, channel ${k}: RGB ${mean(a).toFixed(4)}, spectral ${mean(b).toFixed(4)}, difference ${mean(diff).toFixed(4)} ± ${standardError(diff).toFixed(4)} (tolerance ${tolerance.toFixed(4)})`);
      expect(Math.abs(mean(diff))).toBeLessThan(tolerance);
    }
  });
});

describe('the prism', () => {
  // 48 columns across the spectrum (screen positions −4.35 … 1.65 cm: 400 nm lands at −3.26, 700 nm at
  // 0.56); rows are all alike (the scene is flat), so a few suffice.
  const W = 48, H = 4, CENTER = -1.35, HALF = 3;
  const camera = prismCamera(CENTER, HALF, W / H);
  const position = (x: number) => CENTER + (((x + 0.5) / W) * 2 - 1) * HALF;
  /** Centroid of a (signed) column profile in screen cm. */
  const centroid = (profile: readonly number[]) => profile.reduce((s, v, x) => s + v * position(x), 0) / profile.reduce((s, v) => s + v, 0);

  /**
   * The oracle: where each channel's light lands, from the dispersion law alone. The beam's axis at λ
   * meets the screen at screenPosition(λ) (Snell at both faces with SF11's Sellmeier n(λ)); the
   * channel's weight at λ is its row of RGB_FROM_XYZ · cmf(λ) (equal-energy light) times the Fresnel
   * transmittance of both faces. The beam's spread is symmetric about its axis, so it moves no
   * centroid to first order.
   */
  function expectedCentroid(k: number): number {
    let num = 0, den = 0;
    for (let l = 380; l <= 780; l += 1) {
      const w = mulVec(RGB_FROM_XYZ, cieXyz(l))[k]! * prismTransmittance(iorAt(PRISM_IOR, PRISM_GLASS, l));
      num += w * screenPosition(l)!;
      den += w;
    }
    return num / den;
  }
  const spp = 1024;
  let inPlane: Accumulation;

  it('shows the spectrum where SF11’s dispersion law puts it: red bent least, blue most', { timeout: 900_000 }, async () => {
    inPlane = await render(prismScene(), { width: W, height: H, spp, camera, settings: { spectral: true, seed: 11 } });
    const measured = [0, 1, 2].map((k) => centroid(columnMeans(inPlane, k)));
    const expected = [0, 1, 2].map(expectedCentroid);
    console.log(`prism: channel centroids (cm on the screen) measured ${measured.map((v) => v.toFixed(3)).join(', ')}, expected ${expected.map((v) => v.toFixed(3)).join(', ')}; 450 nm at ${screenPosition(450)!.toFixed(3)}, 650 nm at ${screenPosition(650)!.toFixed(3)}`);
    // Order: red lands on the side of least deviation (+ along the screen), then green, then blue.
    expect(measured[0]!).toBeGreaterThan(measured[1]!);
    expect(measured[1]!).toBeGreaterThan(measured[2]!);
    // Positions and the red–blue spread, each to 0.3 cm (the red–blue spread is ~1.8 cm, a wavelength's
    // band ~1.7 cm wide; one pixel is 0.125 cm).
    for (let k = 0; k < 3; k++) expect(Math.abs(measured[k]! - expected[k]!)).toBeLessThan(0.3);
    expect(Math.abs(measured[0]! - measured[2]! - (expected[0]! - expected[2]!))).toBeLessThan(0.3);
  });

  it('converges thanks to its in-plane screen (measured against a Lambertian screen)', { timeout: 900_000 }, async () => {
    const lambertianSpp = spp / 4;
    const lambertian = await render(prismScene({ inPlaneScreen: false }), { width: W, height: H, spp: lambertianSpp, camera, settings: { spectral: true, seed: 11 } });
    // Relative standard error of the spectrum's total brightness (luminance summed over the image),
    // from the per-pixel variance the accumulation keeps.
    const relativeError = (a: Accumulation) => {
      let sum = 0, variance = 0;
      for (let i = 0; i < a.width * a.height; i++) {
        sum += 0.2126 * a.radiance[i * 3]! + 0.7152 * a.radiance[i * 3 + 1]! + 0.0722 * a.radiance[i * 3 + 2]!;
        variance += a.luminanceVariance[i]! / a.samples;
      }
      return sum > 0 ? Math.sqrt(variance) / sum : Infinity;
    };
    // At equal samples: the Lambertian render took a quarter as many, so its error is scaled by ½.
    const errors = { inPlane: relativeError(inPlane), lambertian: relativeError(lambertian) * Math.sqrt(lambertianSpp / spp) };
    console.log(`prism at ${W}×${H}, ${spp} spp: relative standard error of the spectrum's brightness ${errors.inPlane.toFixed(4)} (in-plane screen) vs ${errors.lambertian.toFixed(4)} (Lambertian, scaled to ${spp} spp)`);
    expect(errors.inPlane * 2).toBeLessThan(errors.lambertian);
  });
});

describe('a glass ball in front of a black/white edge', () => {
  /** An SF11 ball (radius 1) 3 units in front of a wall that emits white left of x = 0 and nothing right of it. */
  function ballScene(dispersive: boolean): Scene {
    const b = new MeshBuilder('edge wall');
    const white = b.material(diffuse('white', [0, 0, 0], [1, 1, 1]));
    const black = b.material(diffuse('black', [0, 0, 0]));
    const glass: DielectricMaterial = {
      kind: 'dielectric', name: 'SF11', emission: [0, 0, 0], ior: 1.78472, roughness: 0, tint: [1, 1, 1], attenuationDistance: Infinity, attenuationColor: [1, 1, 1],
      ...(dispersive ? { dispersion: GLASSES.SF11 } : {}),
    };
    const glassId = b.material(glass);
    // Counter-clockwise seen from +z: the emitting side faces the ball and the camera.
    b.quad(white, [-10, -10, -3], [0, -10, -3], [0, 10, -3], [-10, 10, -3]);
    b.quad(black, [0, -10, -3], [10, -10, -3], [10, 10, -3], [0, 10, -3]);
    const meshes = [b.build(), uvSphere('ball', 1, 96, 48, glassId)];
    return {
      name: 'glass ball', meshes, instances: placeEachOnce(meshes), materials: b.materials,
      camera: { position: [0, 0, 5], forward: [0, 0, -1], up: [0, 1, 0], vfovDegrees: 2 * Math.atan(1.1 / 5) * 180 / Math.PI },
    };
  }

  /** Σ over columns of (column mean of R − B)² over the rows through the ball's middle. */
  function fringeEnergy(a: Accumulation): number {
    const rows = Array.from({ length: a.height / 2 }, (_, i) => i + a.height / 4);
    const r = columnMeans(a, 0, rows), b = columnMeans(a, 2, rows);
    return r.reduce((s, v, x) => s + (v - b[x]!) ** 2, 0);
  }

  it('shows chromatic fringes in spectral mode and none in RGB mode', async () => {
    const o = { width: 32, height: 32, spp: 64 };
    const rgb = await render(ballScene(true), { ...o, settings: { spectral: false, seed: 2 } });
    const spectral = await render(ballScene(true), { ...o, settings: { spectral: true, seed: 2 } });
    // The control: the same spectral render without dispersion (its R − B is wavelength noise alone).
    const control = await render(ballScene(false), { ...o, settings: { spectral: true, seed: 2 } });
    const e = { rgb: fringeEnergy(rgb), spectral: fringeEnergy(spectral), control: fringeEnergy(control) };
    console.log(`glass ball: fringe energy Σ(R − B)² over columns: RGB ${e.rgb.toExponential(2)}, spectral ${e.spectral.toExponential(3)}, spectral without dispersion ${e.control.toExponential(3)}`);
    // RGB mode ignores dispersion: grey in, grey out, exactly.
    expect(e.rgb).toBeLessThan(1e-10);
    expect(e.spectral).toBeGreaterThan(4 * e.control);
  });
});
