/**
 * A farm's samples split exactly (issue #31): shards of samples [s0, s1) rendered alone (the
 * estimate restarted at s0) and merged in sample order (farm/shard.ts, float32 after each addition)
 * give the accumulation of one render whose dispatches are those chunks, bit for bit; and a
 * render batched otherwise differs only in the last bits (the order of float additions).
 */
import { describe, expect, it } from 'vitest';
import { builtinScene } from '../../src/loaders/builtin/index.ts';
import { Renderer } from '../../src/renderer/renderer.ts';
import { mergeShards, SHARD_VERSION } from '../../src/farm/shard.ts';
import { testGpu } from './gpu-context.ts';

const W = 8, H = 6;

async function withRenderer<T>(body: (r: Renderer) => Promise<T>): Promise<T> {
  const renderer = await Renderer.create(await testGpu());
  try {
    await renderer.setScene(builtinScene('cornell'));
    await renderer.resize(W, H);
    renderer.updateSettings({ maxBounces: 3, seed: 5 });
    return await body(renderer);
  } finally {
    renderer.destroy();
  }
}

describe('farm shards', () => {
  it('merged in sample order equal one render in dispatches of the chunk size, bit for bit', async () => {
    const chunks = [[0, 3], [3, 6], [6, 7]] as const;
    const one = await withRenderer(async (r) => {
      for (const [a, b] of chunks) r.accumulate(b - a);
      return r.readAccumulationSums();
    });
    const shards = await withRenderer(async (r) => {
      const out = [];
      // Rendered out of order, as workers finish them.
      for (const [a, b] of [chunks[2], chunks[0], chunks[1]]) {
        r.resetAccumulation(a);
        r.accumulate(b - a);
        out.push({ name: `${a}-${b}`, shard: { header: { version: SHARD_VERSION, render: ['cornell'], width: W, height: H, start: a, end: b }, sums: await r.readAccumulationSums() } });
      }
      return out;
    });
    const merged = mergeShards(shards);
    expect(merged.end - merged.start).toBe(7);
    let total = 0;
    for (const v of one) total += v;
    expect(total).toBeGreaterThan(0);
    expect(Buffer.from(merged.sums.buffer).equals(Buffer.from(one.buffer))).toBe(true);
    // Batched otherwise (7 samples in one dispatch), the sums agree to float rounding only.
    const single = await withRenderer(async (r) => {
      r.accumulate(7);
      return r.readAccumulationSums();
    });
    let differing = 0;
    for (let i = 0; i < one.length; i++) {
      expect(Math.abs(single[i]! - one[i]!)).toBeLessThanOrEqual(1e-5 * Math.max(1, one[i]!));
      if (single[i] !== one[i]) differing++;
    }
    console.log(`7 samples as 3+3+1 against one dispatch: ${differing} of ${one.length} floats differ in the last bits`);
  });
});
