import { describe, expect, it } from 'vitest';
import { atrousSchedule, denoiseAtrousParams, denoiseSlopesParams, denoiseWeightsParams, EXACT_WEIGHT_ITERATIONS, isDenoiseChainPass, PING_PONG, type PairRegion } from './denoise-passes.ts';

/** The words a region's pairs occupy for the first pixels. */
const words = (r: PairRegion, pixels = 8) => new Set(Array.from({ length: pixels }, (_, i) => [r.stride * i + r.offset, r.stride * i + r.offset + 1]).flat().map((w) => `${r.array}${w}`));

describe('the à-trous schedule of the real-time chain', () => {
  for (const feedback of [false, true]) {
    it(`${feedback ? 'with' : 'without'} feedback: each iteration reads what the last wrote, never its own result's words, and ends in the output`, () => {
      const schedule = atrousSchedule(feedback);
      expect(schedule).toHaveLength(5);
      schedule.forEach((it, i) => {
        const p = denoiseAtrousParams(i, it);
        if (it.result === 'output') {
          expect(i).toBe(schedule.length - 1);
          // The output overwrites every word of the frame scratch: the source must lie elsewhere.
          expect(it.source.array).toBe('b');
          expect(p).toMatchObject({ mode: 2, result_array: 1 });
          return;
        }
        const next = schedule[i + 1]!;
        expect(next.source).toEqual(it.result);
        // Bound as source_words and other_words (renderer/recipes/real-time.ts): 0 is the source's own buffer.
        expect(p.result_array).toBe(it.result.array === it.source.array ? 0 : 1);
        expect(p).toMatchObject({ source_stride: it.source.stride, source_offset: it.source.offset, result_stride: it.result.stride, result_offset: it.result.offset });
        const read = words(it.source);
        for (const w of words(it.result)) expect(read.has(w)).toBe(false);
        expect(p.mode).toBe(it.copyHistory ? 1 : 0);
      });
      // Without feedback the first iteration keeps the unfiltered history (into other_words: the history).
      expect(schedule[0]!.copyHistory).toBe(!feedback);
    });
  }
});

describe('the weight sums of the à-trous iterations', () => {
  it('are read where a dispatch just wrote them, never where the same dispatch writes, and capped where they are an earlier step\'s', () => {
    for (const feedback of [false, true]) {
      const schedule = atrousSchedule(feedback);
      // Which region holds sums, and whether they are the reading iteration's own step.
      const held = new Map<number, { iteration: number; exact: boolean }>();
      expect(denoiseSlopesParams()).toMatchObject({ mode: 3, weights_read: 0, weights_write: 0 });
      schedule.forEach((it, i) => {
        if (i < EXACT_WEIGHT_ITERATIONS) {
          const w = denoiseWeightsParams(i, it);
          expect(w).toMatchObject({ mode: 4, weights_read: 0, step: denoiseAtrousParams(i, it).step });
          held.set(w.weights_write as number, { iteration: i, exact: true });
        } else {
          expect(() => denoiseWeightsParams(i, it)).toThrow();
        }
        const p = denoiseAtrousParams(i, it);
        const sums = held.get(p.weights_read as number);
        expect(sums).toBeDefined();
        // Exact sums are this iteration's own; otherwise the previous iteration's filter wrote them, and the coefficients are capped.
        expect(sums!.iteration).toBe(sums!.exact ? i : i - 1);
        expect(p.capped).toBe(sums!.exact ? 0 : 1);
        expect(p.weights_write).not.toBe(p.weights_read);
        if (p.weights_write !== 0) held.set(p.weights_write as number, { iteration: i, exact: false });
        // An iteration that reads an earlier step's sums needs its predecessor to have written them.
        if (i + 1 < schedule.length && i + 1 >= EXACT_WEIGHT_ITERATIONS) expect(p.weights_write).not.toBe(0);
      });
    }
  });
});

describe("the hybrid recipe's GI filter (PING_PONG, three iterations)", () => {
  it('reads one buffer and writes the other, steps 1, 2, 4, the last writing no sums for an iteration that does not run', () => {
    const params = [0, 1, 2].map((i) => denoiseAtrousParams(i, PING_PONG, 3));
    expect(params.map((p) => p.step)).toEqual([1, 2, 4]);
    for (const p of params) expect(p).toMatchObject({ source_stride: 2, source_offset: 0, result_array: 1, result_stride: 2, result_offset: 0, mode: 0 });
    expect(params.map((p) => p.capped)).toEqual([0, 0, 1]);
    // Iteration 2 (the second) leaves its sums for the third, which reads them; the third leaves none.
    expect(params[1]!.weights_write).toBe(params[2]!.weights_read);
    expect(params[2]!.weights_write).toBe(0);
    expect(denoiseWeightsParams(1, PING_PONG, 3).weights_write).toBe(params[1]!.weights_read);
    expect(() => denoiseAtrousParams(3, PING_PONG, 3)).toThrow();
    expect(() => denoiseAtrousParams(0, PING_PONG, 6)).toThrow();
  });
});

describe('isDenoiseChainPass', () => {
  it("names the real-time chain's passes and not the hybrid recipe's GI filter", () => {
    for (const label of ['temporal', 'a-trous slopes', 'a-trous 1 weights', 'a-trous 1', 'a-trous 5 weights', 'a-trous 5', 'denoise output']) expect(isDenoiseChainPass(label)).toBe(true);
    for (const label of ['a-trous GI 1', 'a-trous', 'path trace (frame)', 'frame G-buffer', 'taa']) expect(isDenoiseChainPass(label)).toBe(false);
  });
});
