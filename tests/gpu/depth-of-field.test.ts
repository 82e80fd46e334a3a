/**
 * Thin-lens depth of field (view/bindings.wgsl thin_lens_ray): an aperture of 0 renders the pinhole
 * image bit for bit; an edge on the plane of focus stays sharp; an edge off it is spread by the
 * analytic circle of confusion, 2A·|d − F|/d on the plane of focus (scene/lens.ts
 * blurDiameterPixels), found by fitting the blurred edge's profile; the G-buffer and the debug views
 * keep the chief ray through the lens centre.
 */
import { beforeAll, describe, expect, it } from 'vitest';
import { expectLanternError } from '../../src/expect-lantern-error.ts';
import { builtinScene } from '../../src/loaders/builtin/index.ts';
import { prepareScene } from '../../src/renderer/prepare.ts';
import { renderProgressive } from '../../src/renderer/progressive.ts';
import { Renderer } from '../../src/renderer/renderer.ts';
import { MeshBuilder } from '../../src/scene/builder.ts';
import { placeEachOnce } from '../../src/scene/instances.ts';
import { blurDiameterPixels } from '../../src/scene/lens.ts';
import type { Camera, Scene, ThinLens } from '../../src/scene/types.ts';
import { testGpu } from './gpu-context.ts';

const W = 64;
const H = 32;
const VFOV = 60;
const TAN_HALF = Math.tan((VFOV * Math.PI) / 360);
const pinhole: Camera = { position: [0, 0, 0], forward: [0, 0, 1], up: [0, 1, 0], vfovDegrees: VFOV };
const withLens = (lens: ThinLens): Camera => ({ ...pinhole, lens });

/**
 * An emitting half-plane facing the camera at depth z: x from −40 to edgeX (far beyond the image
 * elsewhere), radiance 1, nothing else. Screen right is forward × up = −x, so it fills the image's
 * right part and its edge is a vertical line.
 */
function halfPlane(z: number, edgeX: number): Scene {
  const b = new MeshBuilder('half-plane');
  const m = b.material({ kind: 'diffuse', name: 'emitter', albedo: [0, 0, 0], emission: [1, 1, 1] });
  b.quad(m, [-400, -400, z], [-400, 400, z], [edgeX, 400, z], [edgeX, -400, z]);
  const meshes = [b.build()];
  return { name: 'half-plane', meshes, instances: placeEachOnce(meshes), materials: b.materials, camera: pinhole };
}

/** The image column (continuous, pixels) where a half-plane's edge at (edgeX, ·, z) appears: its pinhole projection. */
const edgeColumn = (edgeX: number, z: number) => (W / 2) * (1 - edgeX / (z * TAN_HALF * (W / H)));

/** Fraction of a unit disk lying at coordinate < s (the edge response of a uniform blur disk). */
function diskFraction(s: number): number {
  if (s <= -1) return 0;
  if (s >= 1) return 1;
  return 0.5 + (s * Math.sqrt(1 - s * s) + Math.asin(s)) / Math.PI;
}

/**
 * The expected mean of each column: an edge at x0 rising to the right, blurred by a disk of diameter
 * `diameter` pixels and averaged over each pixel's width (the pixel jitter).
 */
function modelProfile(x0: number, diameter: number): number[] {
  const sub = 64;
  return Array.from({ length: W }, (_, i) => {
    let sum = 0;
    for (let k = 0; k < sub; k++) {
      const x = i + (k + 0.5) / sub;
      sum += diameter > 0 ? diskFraction((x - x0) / (diameter / 2)) : x > x0 ? 1 : 0;
    }
    return sum / sub;
  });
}

/** The blur diameter (pixels) whose model profile fits the measured one best (least squares over a fine grid), and the worst residual. */
function fitDiameter(profile: readonly number[], x0: number, maxDiameter: number): { diameter: number; residual: number } {
  let best = { diameter: 0, sse: Infinity, residual: Infinity };
  for (let d = 0; d <= maxDiameter; d += 0.02) {
    const model = modelProfile(x0, d);
    let sse = 0, worst = 0;
    profile.forEach((p, i) => {
      const e = p - model[i]!;
      sse += e * e;
      worst = Math.max(worst, Math.abs(e));
    });
    if (sse < best.sse) best = { diameter: d, sse, residual: worst };
  }
  return { diameter: best.diameter, residual: best.residual };
}

let renderer: Renderer;
beforeAll(async () => {
  renderer = await Renderer.create(await testGpu());
  await renderer.resize(W, H);
});

/** The mean radiance (red channel) of each column after `spp` samples. */
async function columnProfile(scene: Scene, camera: Camera, spp: number): Promise<number[]> {
  await renderer.setScene(scene);
  // The PCG stream ('random'), whose column means these fits were derived with. With the Sobol default
  // the in-focus edge fits 0.54 px at 32 spp (CI, issue #15): not yet understood — a correlation of the
  // jitter and lens dimension pairs across a column is suspected — so it is kept apart, not hidden.
  renderer.updateSettings({ maxBounces: 0, seed: 7, sampler: 'random' });
  renderer.setCamera(camera);
  await renderProgressive(renderer, { spp });
  const { radiance } = await renderer.readAccumulation();
  return Array.from({ length: W }, (_, x) => {
    let sum = 0;
    for (let y = 0; y < H; y++) sum += radiance[(y * W + x) * 3]!;
    return sum / H;
  });
}

describe('aperture 0', () => {
  it('renders the pinhole image bit for bit, progressive and real-time', async () => {
    const cornell = prepareScene(builtinScene('cornell'));
    await renderer.setScene(cornell);
    renderer.updateSettings({ maxBounces: 3, seed: 3, temporal: true, denoise: false, denoiseView: 'output' });
    const camera = cornell.scene.camera;
    // One dispatch of 4 samples each time: renderProgressive batches samples by measured time, and
    // two batchings of the same samples round differently in the f32 sums (a flake under load).
    const progressive = async (c: Camera) => {
      renderer.setCamera(c);
      renderer.accumulate(4);
      await renderer.finish();
      return (await renderer.readAccumulation()).radiance;
    };
    // Real-time frames draw from the denoiser's running sample index: each comparison frame is the first of a fresh renderer.
    const frame = async (c: Camera) => {
      const fresh = await Renderer.create(await testGpu());
      await fresh.resize(W, H);
      await fresh.compile({}, { frames: true });
      await fresh.setScene(cornell);
      fresh.updateSettings(renderer.settings);
      fresh.setCamera(c);
      fresh.renderFrame(2);
      const { radiance } = await fresh.readFrame();
      fresh.destroy();
      return radiance;
    };
    const closed = { apertureRadius: 0, focusDistance: 800 };
    const a = await progressive(camera);
    // A closed lens focused anywhere takes the pinhole branch: not a ray through the focus point, which would round differently.
    expect(await progressive({ ...camera, lens: closed })).toEqual(a);
    expect(await frame({ ...camera, lens: closed })).toEqual(await frame(camera));
    // The test can fail: an open aperture changes the image (and draws more random numbers).
    const open = await progressive({ ...camera, lens: { apertureRadius: 20, focusDistance: 800 } });
    expect(open).not.toEqual(a);
    // setCamera refuses a lens that cannot be (the viewer's click-to-focus goes through it).
    expectLanternError(() => renderer.setCamera({ ...camera, lens: { apertureRadius: -1, focusDistance: 800 } }), /aperture radius -1/);
    expectLanternError(() => renderer.setCamera({ ...camera, lens: { apertureRadius: 1, focusDistance: 0 } }), /focus distance 0/);
  });
});

describe('defocus', () => {
  const F = 4;
  const A = 0.72;

  it('keeps an edge on the plane of focus sharp (edge width about one pixel)', async () => {
    const edgeX = 0.03; // not on a pixel boundary
    const x0 = edgeColumn(edgeX, F);
    const profile = await columnProfile(halfPlane(F, edgeX), withLens({ apertureRadius: A, focusDistance: F }), 32);
    const fit = fitDiameter(profile, x0, 4);
    expect(fit.diameter).toBeLessThan(0.3);
    // Only the column the edge crosses lies between dark and bright.
    expect(profile.filter((p) => p > 0.02 && p < 0.98).length).toBeLessThanOrEqual(1);
    expect(profile[0]).toBe(0);
    expect(profile[W - 1]).toBe(1);
  });

  for (const depth of [2, 12]) {
    it(`spreads an edge at depth ${depth} (focus at ${F}) over the analytic circle of confusion`, async () => {
      const edgeX = 0.05 * depth;
      const x0 = edgeColumn(edgeX, depth);
      const camera = withLens({ apertureRadius: A, focusDistance: F });
      const expected = blurDiameterPixels(camera, depth, H);
      // 2A·|d − F|/d over the pixel size 2F·tan(30°)/H: 9.98 px at d = 2, 6.65 px at d = 12.
      expect(expected).toBeGreaterThan(6);
      const profile = await columnProfile(halfPlane(depth, edgeX), camera, 64);
      const fit = fitDiameter(profile, x0, 2 * expected);
      console.log(`edge at depth ${depth}, focus ${F}, aperture radius ${A}: blur diameter ${fit.diameter.toFixed(2)} px fitted, ${expected.toFixed(2)} px analytic; worst residual ${fit.residual.toFixed(3)}`);
      expect(fit.diameter).toBeGreaterThan(expected * 0.95);
      expect(fit.diameter).toBeLessThan(expected * 1.05);
      expect(fit.residual).toBeLessThan(0.06);
      // The blur is centred on the chief ray's projection: the profile's midpoint crossing lies at x0.
      const mid = profile.findIndex((p) => p >= 0.5);
      const crossing = mid - 1 + (0.5 - profile[mid - 1]!) / (profile[mid]! - profile[mid - 1]!) + 0.5;
      expect(Math.abs(crossing - x0)).toBeLessThan(0.35);
      // The pinhole sees the same edge sharp.
      const sharp = fitDiameter(await columnProfile(halfPlane(depth, edgeX), pinhole, 16), x0, 4);
      expect(sharp.diameter).toBeLessThan(0.3);
    });
  }
});

describe('G-buffer and debug views with a lens', () => {
  it('keep the chief ray through the lens centre: the same depth, normals and debug values as the pinhole', async () => {
    const cornell = prepareScene(builtinScene('cornell'));
    await renderer.setScene(cornell);
    await renderer.compile({}, { frames: true });
    await renderer.compile({ debugView: 'normals' }, { frames: true });
    const camera = cornell.scene.camera;
    const lensed = { ...camera, lens: { apertureRadius: 30, focusDistance: 500 } };
    const gbuffer = async (c: Camera, view: 'depth' | 'normal') => {
      renderer.updateSettings({ debugView: 'none', temporal: false, denoise: false, denoiseView: view, maxBounces: 1 });
      renderer.resetHistory();
      renderer.setCamera(c);
      renderer.renderFrame(1);
      return (await renderer.readFrame()).radiance;
    };
    for (const view of ['depth', 'normal'] as const) expect(await gbuffer(lensed, view)).toEqual(await gbuffer(camera, view));
    const debug = async (c: Camera) => {
      renderer.updateSettings({ debugView: 'normals', debugLayout: 'replace' });
      renderer.setCamera(c);
      return renderer.readDebugValues();
    };
    expect(await debug(lensed)).toEqual(await debug(camera));
    renderer.updateSettings({ debugView: 'none' });
  });
});
