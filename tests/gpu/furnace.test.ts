import { describe, expect, it } from 'vitest';
import { furnaceRadiance } from '../../src/loaders/builtin/furnace.ts';
import { builtinScene } from '../../src/loaders/builtin/index.ts';
import { Renderer } from '../../src/renderer/renderer.ts';
import { testGpu } from './gpu-context.ts';

async function renderFurnace(options: { width: number; height: number; spp: number; maxBounces: number; lightSampling: 'mis' | 'bsdf' }) {
  const renderer = await Renderer.create(await testGpu());
  await renderer.setScene(builtinScene('furnace'));
  await renderer.resize(options.width, options.height);
  renderer.updateSettings({ maxBounces: options.maxBounces, lightSampling: options.lightSampling, seed: 7 });
  for (let done = 0; done < options.spp; done += 16) renderer.accumulate(Math.min(16, options.spp - done));
  const acc = await renderer.readAccumulation();
  renderer.destroy();
  return acc;
}

function luminanceOf(rgb: Float32Array, i: number): number {
  return 0.2126 * rgb[i * 3]! + 0.7152 * rgb[i * 3 + 1]! + 0.0722 * rgb[i * 3 + 2]!;
}

describe('white furnace', () => {
  for (const lightSampling of ['mis', 'bsdf'] as const) {
    it(`converges to 5.0 everywhere (${lightSampling})`, async () => {
      const acc = await renderFurnace({ width: 16, height: 16, spp: 256, maxBounces: 128, lightSampling });
      const n = acc.width * acc.height;
      let sum = 0;
      let worst = 0;
      for (let i = 0; i < n; i++) {
        const l = luminanceOf(acc.radiance, i);
        sum += l;
        // Standard error of this pixel's mean from its own sample variance.
        const sigma = Math.sqrt(acc.luminanceVariance[i]! / acc.samples);
        worst = Math.max(worst, Math.abs(l - 5) / Math.max(sigma, 1e-3));
      }
      const mean = sum / n;
      expect(Math.abs(mean - 5) / 5).toBeLessThan(0.01);
      // 256 pixels: |z| > 5 has probability ~1.5e-4 over the image if the estimator is unbiased.
      expect(worst).toBeLessThan(5);
    });
  }

  it('with 2 bounces converges to 1 + 0.8 + 0.64', async () => {
    const acc = await renderFurnace({ width: 8, height: 8, spp: 256, maxBounces: 2, lightSampling: 'mis' });
    let sum = 0;
    for (let i = 0; i < 64; i++) sum += luminanceOf(acc.radiance, i);
    expect(sum / 64).toBeCloseTo(furnaceRadiance(2), 1);
    expect(Math.abs(sum / 64 - furnaceRadiance(2)) / furnaceRadiance(2)).toBeLessThan(0.01);
  });
});
