/**
 * The path tracers are compiled for the sampler their chain uses (lib/random.wgsl SAMPLER,
 * passes/path-trace-pass.ts TracingKernels): a change of the sampler setting compiles the other
 * sampler's kernels, and the estimate is then that sampler's, bit for bit as if it had been compiled
 * for it from the start; switching back gives back the first image.
 */
import { describe, expect, it } from 'vitest';
import { builtinScene } from '../../src/loaders/builtin/index.ts';
import { Renderer } from '../../src/renderer/renderer.ts';
import type { SamplerSetting } from '../../src/passes/variants.ts';
import { testGpu } from './gpu-context.ts';

async function image(renderer: Renderer, sampler: SamplerSetting): Promise<Float32Array> {
  renderer.updateSettings({ sampler });
  await renderer.accelSettled();
  renderer.resetAccumulation();
  renderer.accumulate(4);
  return (await renderer.readAccumulation()).radiance;
}

describe('path tracers compiled for their sampler', () => {
  it('trace with the sampler the setting names after a change, and give the same image for the same sampler', async () => {
    const renderer = await Renderer.create(await testGpu());
    await renderer.setScene(builtinScene('cornell'));
    await renderer.resize(8, 8);
    renderer.updateSettings({ maxBounces: 2, seed: 5 });
    const auto = await image(renderer, 'auto');
    const random = await image(renderer, 'random');
    const sobol = await image(renderer, 'sobol');
    const randomAgain = await image(renderer, 'random');
    renderer.destroy();
    expect(auto.reduce((a, b) => a + b, 0)).toBeGreaterThan(0);
    // 'auto' renders progressively with Sobol.
    expect(Array.from(sobol)).toEqual(Array.from(auto));
    expect(Array.from(random)).not.toEqual(Array.from(sobol));
    expect(Array.from(randomAgain)).toEqual(Array.from(random));
  });
});
