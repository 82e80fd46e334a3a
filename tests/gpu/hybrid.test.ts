/**
 * The hybrid recipe (renderer/hybrid.ts): its raster first hit is the ray tracer's first hit, and
 * its light adds up to the analytic answer of the white furnace, where
 *   L = Le + direct (a·Le) + a · GI(B bounces) = Σ_{k=0..B+1} a^k Le
 * in expectation at every pixel, whatever the GI buffer's scale and with or without its filter.
 */
import { beforeAll, describe, expect, it } from 'vitest';
import { builtinScene } from '../../src/loaders/builtin/index.ts';
import { furnaceRadiance } from '../../src/loaders/builtin/furnace.ts';
import { primaryRay } from '../../src/gpu/view.ts';
import { prepareScene } from '../../src/renderer/prepare.ts';
import { Renderer } from '../../src/renderer/renderer.ts';
import { DEFAULT_SETTINGS } from '../../src/renderer/settings.ts';
import { haltonJitter } from '../../src/renderer/hybrid.ts';
import { traceScene } from '../../src/bvh/levels.ts';
import { testGpu } from './gpu-context.ts';

const SIZE = 24;
let renderer: Renderer;

beforeAll(async () => {
  renderer = await Renderer.create(await testGpu());
  await renderer.enableHybrid();
  await renderer.resize(SIZE, SIZE);
});

/** Mean radiance (per channel mean) over `frames` hybrid frames, every pixel. */
async function meanOfFrames(frames: number): Promise<{ mean: number; pixels: Float64Array }> {
  const pixels = new Float64Array(SIZE * SIZE);
  for (let f = 0; f < frames; f++) {
    renderer.renderFrame(1);
    const img = await renderer.readFrame();
    for (let i = 0; i < SIZE * SIZE; i++) pixels[i]! += (img.radiance[i * 3]! + img.radiance[i * 3 + 1]! + img.radiance[i * 3 + 2]!) / 3 / frames;
  }
  return { mean: pixels.reduce((a, b) => a + b, 0) / pixels.length, pixels };
}

describe('hybrid recipe: the white furnace', () => {
  for (const [giScale, giFilter, giBounces] of [[1, false, 2], [0.5, true, 2], [0.25, false, 1]] as const) {
    it(`converges to Σ a^k up to B + 1 bounces (GI scale ${giScale}, filter ${giFilter}, B = ${giBounces})`, async () => {
      await renderer.setScene(builtinScene('furnace'));
      renderer.setCamera(builtinScene('furnace').camera);
      renderer.updateSettings({ recipe: 'hybrid', maxBounces: 8, seed: 3, torch: { enabled: false }, hybrid: { ...DEFAULT_SETTINGS.hybrid, giScale, giFilter, giBounces, giSamples: 2, lightSamples: 2, taa: false } });
      renderer.resetHistory();
      const { mean, pixels } = await meanOfFrames(12);
      const expected = furnaceRadiance(giBounces + 1);
      console.log(giScale, mean, expected);
      expect(mean).toBeGreaterThan(expected * 0.98);
      expect(mean).toBeLessThan(expected * 1.02);
      // No part of the image strays either (no seam, no hole, no light lost at edges): 6 × 6 blocks.
      for (let by = 0; by < SIZE; by += 6) {
        for (let bx = 0; bx < SIZE; bx += 6) {
          let sum = 0;
          for (let y = by; y < by + 6; y++) for (let x = bx; x < bx + 6; x++) sum += pixels[y * SIZE + x]!;
          expect(Math.abs(sum / 36 - expected)).toBeLessThan(0.1 * expected);
        }
      }
    });
  }
});

describe('hybrid recipe: raster first hit', () => {
  it('sees at every pixel the surface a camera ray through the jittered point hits (the CPU oracle)', async () => {
    const scene = builtinScene('cornell');
    const prepared = prepareScene(scene);
    await renderer.setScene(prepared);
    renderer.setCamera(scene.camera);
    // Emission only: the image is the emitter where the first hit is the light, black elsewhere.
    renderer.updateSettings({ recipe: 'hybrid', maxBounces: 0, torch: { enabled: false }, hybrid: { ...DEFAULT_SETTINGS.hybrid, taa: false } });
    renderer.resetHistory();
    renderer.renderFrame(1);
    const img = await renderer.readFrame();
    const [jx, jy] = haltonJitter(0);
    let agree = 0;
    for (let y = 0; y < SIZE; y++) {
      for (let x = 0; x < SIZE; x++) {
        const ray = primaryRay(scene.camera, SIZE, SIZE, x + 0.5 + jx, y + 0.5 + jy);
        const hit = traceScene(prepared.scene, prepared.triangles, prepared.bvh, prepared.levels, { origin: ray.origin, direction: ray.direction });
        const material = hit ? prepared.triangles.materialIds[hit.triangle]! : -1;
        const emits = material >= 0 && scene.materials[material]!.emission.some((c) => c > 0);
        const seen = img.radiance[(y * SIZE + x) * 3]! > 0;
        if (emits === seen) agree++;
      }
    }
    expect(agree).toBe(SIZE * SIZE);
  });
});
