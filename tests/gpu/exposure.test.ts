/**
 * Automatic exposure on the GPU (passes/exposure-pass.ts), held to its CPU twin renderer/exposure.ts:
 * the two-pass log-average reduction of a known image whose size is not a whole number of the
 * reduction's 64-pixel tiles, the exponential adaptation over frames, the renderer's wiring (the
 * average it adapts to is that of the radiance it shows), and what it is for: E1M1, too dark at its
 * fixed exposure, readable by default (skipped where Freedoom is not installed).
 */
import { describe, expect, it } from 'vitest';
import { ExposurePass } from '../../src/passes/exposure-pass.ts';
import { adaptExposureStops, log2AverageLuminance, targetExposureStops } from '../../src/renderer/exposure.ts';
import { ViewUniform } from '../../src/gpu/view.ts';
import { Renderer } from '../../src/renderer/renderer.ts';
import { cornellBox } from '../../src/loaders/builtin/cornell.ts';
import { seededRandom } from '../../src/math/seeded-random.ts';
import { testGpu } from './gpu-context.ts';
import { loadDoomMap } from '../../src/loaders/doom/load.ts';
import { existsSync, readFileSync } from 'node:fs';
import { readWad, WadStack } from '../../src/loaders/doom/wad.ts';

const FREEDOOM1 = '/usr/share/games/doom/freedoom1.wad';

/** Fraction of pixels whose display luma is below 32/255 (what issue #16 counts as crushed). */
function crushed(image: Uint8Array): number {
  let dark = 0;
  for (let i = 0; i < image.length; i += 4) if (0.2126 * image[i]! + 0.7152 * image[i + 1]! + 0.0722 * image[i + 2]! < 32) dark++;
  return dark / (image.length / 4);
}

const W = 70;
const H = 45;

/** RGBA radiance spanning 2^-12 to 2^8, some pixels black (clamped, not −∞), `samples` summed per pixel. */
function knownImage(seed: number, samples: number, brightness = 1): Float32Array {
  const random = seededRandom(seed);
  const pixels = new Float32Array(W * H * 4);
  for (let i = 0; i < W * H; i++) {
    const black = random() < 0.05;
    const level = black ? 0 : brightness * 2 ** (-12 + 20 * random());
    for (let c = 0; c < 3; c++) pixels[i * 4 + c] = samples * level * (0.5 + random());
    pixels[i * 4 + 3] = 0;
  }
  return pixels;
}

describe('automatic exposure on the GPU', () => {
  it('reduces the log-average luminance as the CPU does, and adapts exponentially toward its target', async () => {
    const { device } = await testGpu();
    const pass = await ExposurePass.create(device);
    const view = new ViewUniform(device);
    view.update({ position: [0, 0, 0], forward: [0, 0, -1], up: [0, 1, 0], vfovDegrees: 60 }, W, H);
    const buffer = (data: Float32Array) => {
      const b = device.createBuffer({ label: 'exposure test radiance', size: data.byteLength, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST });
      device.queue.writeBuffer(b, 0, data);
      return b;
    };
    const run = async (radiance: GPUBuffer, sampleCount: number, keep: number, compensationStops = 0) => {
      const encoder = device.createCommandEncoder();
      pass.encode(encoder, { view, radiance, width: W, height: H, input: { sampleCount, keep, compensationStops } });
      device.queue.submit([encoder.finish()]);
      return pass.read();
    };
    const dark = knownImage(1, 3);
    const bright = knownImage(2, 1, 64);
    const [darkBuffer, brightBuffer] = [buffer(dark), buffer(bright)];
    try {
      const darkAverage = log2AverageLuminance(dark, 4, 1 / 3);
      const brightAverage = log2AverageLuminance(bright, 4);
      // Over 3150 pixels in f32: agreement to a thousandth of a stop.
      const first = await run(darkBuffer, 3, 0, 0.5);
      expect(first.log2Average).toBeCloseTo(darkAverage, 3);
      expect(first.stops).toBeCloseTo(targetExposureStops(darkAverage, 0.5), 3);
      // Frames of 0.1 s with τ = 0.5 s after the lights go up: the CPU's law step by step.
      let expected = first.stops;
      const target = targetExposureStops(brightAverage, 0.5);
      for (let frame = 0; frame < 6; frame++) {
        const got = await run(brightBuffer, 1, Math.exp(-0.1 / 0.5), 0.5);
        expected = adaptExposureStops(expected, target, 0.1, 0.5);
        expect(got.log2Average).toBeCloseTo(brightAverage, 3);
        expect(got.stops).toBeCloseTo(expected, 3);
      }
      // After 0.6 s = 1.2 τ, 1 − e^−1.2 of the 6-stop change is made: the exponential law, not a step or a ramp.
      expect((expected - first.stops) / (target - first.stops)).toBeCloseTo(1 - Math.exp(-1.2), 6);
      expect(target - first.stops).toBeCloseTo(darkAverage - brightAverage, 6);
    } finally {
      darkBuffer.destroy();
      brightBuffer.destroy();
      view.destroy();
      pass.destroy();
    }
  });

  it('adapts the renderer to the radiance it shows, and leaves manual exposure alone', async () => {
    const renderer = await Renderer.create(await testGpu());
    try {
      await renderer.setScene(cornellBox());
      await renderer.resize(24, 24);
      renderer.updateSettings({ maxBounces: 2, exposureStops: 'auto', exposureCompensation: -1 });
      expect(renderer.exposureChoice.kind).toBe('auto');
      renderer.accumulate(2);
      const autoImage = await renderer.readImage();
      const { radiance } = await renderer.readAccumulation();
      const exposure = await renderer.readExposure();
      expect(exposure.log2Average).toBeCloseTo(log2AverageLuminance(radiance, 3), 3);
      expect(exposure.stops).toBeCloseTo(targetExposureStops(exposure.log2Average, -1), 3);
      // The Cornell box keeps its camera's exposure unless told: a reference scene.
      renderer.updateSettings({ exposureStops: undefined });
      expect(renderer.exposureChoice).toEqual({ kind: 'manual', stops: 0 });
      const manual = await renderer.readImage();
      // At the adapted exposure's stops, manual gives the same picture.
      renderer.updateSettings({ exposureStops: exposure.stops });
      const same = await renderer.readImage();
      let diff = 0;
      for (let i = 0; i < same.length; i++) diff = Math.max(diff, Math.abs(same[i]! - autoImage[i]!));
      expect(diff).toBeLessThanOrEqual(1);
      expect(Buffer.compare(Buffer.from(manual), Buffer.from(autoImage))).not.toBe(0);
    } finally {
      renderer.destroy();
    }
  });

  // E1M1 from the player start at 64 × 40, 4 spp: 80 % of the pixels crushed at the fixed exposure the
  // map had before (issue #16 counted 76–79 % in the viewer), 26 % adapted.
  it.skipIf(!existsSync(FREEDOOM1))('E1M1 adapts by default, leaving far fewer pixels crushed than its fixed exposure', async () => {
    const stack = new WadStack([readWad(readFileSync(FREEDOOM1), 'freedoom1.wad')]);
    const scene = loadDoomMap(stack, 'E1M1').scene;
    expect(scene.autoExposure).toBe(true);
    const renderer = await Renderer.create(await testGpu());
    try {
      await renderer.setScene(scene);
      await renderer.resize(64, 40);
      renderer.updateSettings({ maxBounces: 3 });
      expect(renderer.exposureChoice.kind).toBe('auto');
      renderer.accumulate(4);
      const adapted = crushed(await renderer.readImage());
      // The same estimate at the scene camera's fixed exposure.
      renderer.updateSettings({ exposureStops: 0 });
      const fixed = crushed(await renderer.readImage());
      console.log(`E1M1 start, 64×40, 4 spp: ${(100 * fixed).toFixed(0)} % crushed at the fixed exposure, ${(100 * adapted).toFixed(0)} % adapted`);
      expect(fixed).toBeGreaterThan(0.6);
      expect(adapted).toBeLessThan(fixed / 2);
    } finally {
      renderer.destroy();
    }
  });
});
