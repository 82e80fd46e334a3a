/**
 * "Same seed, scene and settings: same image" (renderer/settings.ts), whatever the batching: the
 * dispatch planner splits a render into submits by timing, so an image must not depend on how its
 * samples were grouped into dispatches (each sample has its own random stream).
 */
import { describe, expect, it } from 'vitest';
import { builtinScene } from '../../src/loaders/builtin/index.ts';
import { Renderer } from '../../src/renderer/renderer.ts';
import { testGpu } from './gpu-context.ts';

async function render(batches: readonly number[]): Promise<Float32Array> {
  const renderer = await Renderer.create(await testGpu());
  await renderer.setScene(builtinScene('cornell'));
  await renderer.resize(8, 8);
  renderer.updateSettings({ maxBounces: 3, seed: 5 });
  for (const n of batches) renderer.accumulate(n);
  const acc = await renderer.readAccumulation();
  renderer.destroy();
  return acc.radiance;
}

describe('determinism', () => {
  it('8 samples in one dispatch, in eight, or 3 + 5 give the same image', async () => {
    const one = await render([8]);
    const eight = await render([1, 1, 1, 1, 1, 1, 1, 1]);
    const split = await render([3, 5]);
    let total = 0;
    for (const v of one) total += v;
    expect(total).toBeGreaterThan(0);
    for (let i = 0; i < one.length; i++) {
      // Only the order of float additions differs.
      expect(Math.abs(eight[i]! - one[i]!), `value ${i}`).toBeLessThanOrEqual(1e-5 * Math.max(1, one[i]!));
      expect(Math.abs(split[i]! - one[i]!), `value ${i}`).toBeLessThanOrEqual(1e-5 * Math.max(1, one[i]!));
    }
  });
});
