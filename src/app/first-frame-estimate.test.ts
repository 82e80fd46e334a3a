import { describe, expect, it } from 'vitest';
import type { CompileProgress, PipelineCompile } from '../gpu/pipeline-compiles.ts';
import { adapterKey, describeEstimate, estimateFirstFrame, isSoftware, remainingCompileMs, withMeasuredCompiles, type AdapterFacts } from './first-frame-estimate.ts';

const SWIFTSHADER: AdapterFacts = { vendor: 'google', architecture: 'swiftshader', device: '', description: '', isFallbackAdapter: false };
const NVIDIA: AdapterFacts = { vendor: 'nvidia', architecture: 'hopper', device: '', description: 'NVIDIA H200', isFallbackAdapter: false };
const FALLBACK: AdapterFacts = { vendor: '', architecture: '', device: '', description: '', isFallbackAdapter: true };

describe('the first-frame estimate', () => {
  it('tells software adapters from hardware ones', () => {
    expect(isSoftware(SWIFTSHADER)).toBe(true);
    expect(isSoftware(FALLBACK)).toBe(true);
    expect(isSoftware({ ...NVIDIA, description: 'llvmpipe (LLVM 15.0.6, 256 bits)' })).toBe(true);
    expect(isSoftware(NVIDIA)).toBe(false);
  });

  it('expects a software adapter to take longer, and longer for more pixels', () => {
    const pixels = 640 * 400;
    const soft = estimateFirstFrame(SWIFTSHADER, pixels)!;
    const hard = estimateFirstFrame(NVIDIA, pixels)!;
    expect(soft.ms).toBeGreaterThan(5 * hard.ms);
    expect(estimateFirstFrame(SWIFTSHADER, 4 * pixels)!.ms).toBeGreaterThan(soft.ms);
    expect(soft.basis).toMatch(/software/);
    expect(estimateFirstFrame(undefined, pixels)).toBeUndefined();
  });

  it('uses a first frame measured on the same adapter at a similar size, and only then', () => {
    const record = { adapter: adapterKey(SWIFTSHADER), ms: 42_000, pixels: 100_000 };
    expect(estimateFirstFrame(SWIFTSHADER, 150_000, record)).toEqual({ ms: 42_000, basis: 'what it took on this computer last time' });
    // Another adapter, or an image more than twice as large: the model instead.
    expect(estimateFirstFrame(NVIDIA, 150_000, record)!.ms).not.toBe(42_000);
    expect(estimateFirstFrame(SWIFTSHADER, 250_000, record)!.ms).not.toBe(42_000);
  });

  it('says "about", rounded to one figure, and on what basis', () => {
    expect(describeEstimate({ ms: 42_000, basis: 'measured' })).toBe('First frame in about 40 s (measured).');
    expect(describeEstimate({ ms: 2_300, basis: 'b' })).toBe('First frame in about 2 s (b).');
    expect(describeEstimate({ ms: 380, basis: 'b' })).toBe('First frame in about 400 ms (b).');
    expect(describeEstimate({ ms: 95_000, basis: 'b' })).toBe('First frame in about 100 s (b).');
    expect(describeEstimate({ ms: 200_000, basis: 'b' })).toBe('First frame in about 3 min (b).');
  });
});

/** A compile of a batch at `now` = 100 000 ms: done (start, end), under way (start) or queued. */
const at = (key: string, startMs?: number, endMs?: number): PipelineCompile => ({ label: key, key, requestedMs: 0, startMs, endMs });
const batch = (compiles: PipelineCompile[], concurrency = 2): CompileProgress => ({ compiles, concurrency, needed: compiles.length, done: compiles.filter((c) => c.endMs !== undefined).length });
const NOW = 100_000;

describe('the wait for the pipelines under way', () => {
  it('is what each pipeline left took on this computer before, less what it has run, scheduled so many at a time', () => {
    const known = { tracer: 20_000, frame: 30_000, tonemap: 1_000, temporal: 2_000 };
    // The tracer has run 5 s of its 20; the frame kernel 10 of 30; tonemap and temporal wait for a slot.
    const p = batch([at('tracer', NOW - 5_000), at('frame', NOW - 10_000), at('tonemap'), at('temporal')]);
    // Slots free at 15 s and 20 s: tonemap runs 15–16 s, temporal 16–18 s; the frame kernel ends last, at 20 s.
    expect(remainingCompileMs(p, NOW, known, SWIFTSHADER)).toBe(20_000);
    // With one slot, the frame kernel waits for the tracer: 15 + 30 + 1 + 2 s.
    const serial = batch([at('tracer', NOW - 5_000), at('frame'), at('tonemap'), at('temporal')], 1);
    expect(remainingCompileMs(serial, NOW, known, SWIFTSHADER)).toBe(48_000);
    // No limit: everything runs at once; the longest left decides.
    expect(remainingCompileMs(batch([at('tracer', NOW), at('frame', NOW), at('tonemap', NOW)], Infinity), NOW, known, SWIFTSHADER)).toBe(30_000);
    // Done compiles cost nothing more.
    expect(remainingCompileMs(batch([at('tracer', 0, 20_000), at('frame', 0, 30_000)]), NOW, known, SWIFTSHADER)).toBe(0);
  });

  it('expects a pipeline never measured to take the mean of those measured, or the adapter kind\'s figure where that is longer', () => {
    const p = batch([at('new kernel')], 1);
    expect(remainingCompileMs(p, NOW, { a: 10_000, b: 20_000 }, SWIFTSHADER)).toBe(15_000);
    const soft = remainingCompileMs(p, NOW, {}, SWIFTSHADER);
    const hard = remainingCompileMs(p, NOW, {}, NVIDIA);
    expect(soft).toBeGreaterThan(5 * hard);
    expect(hard).toBeGreaterThan(0);
    // Small passes measured first do not make a tracing kernel look like a second's work.
    expect(remainingCompileMs(p, NOW, { tonemap: 300, present: 400 }, SWIFTSHADER)).toBe(soft);
  });

  it('never says a compile under way longer than expected is done', () => {
    const left = remainingCompileMs(batch([at('tracer', NOW - 50_000)]), NOW, { tracer: 20_000 }, SWIFTSHADER);
    expect(left).toBeGreaterThan(0);
    expect(left).toBeLessThan(20_000);
  });

  it('follows the compiles as they complete: each one done is remembered by its key, the latest measurement winning', () => {
    const known = { tracer: 20_000 };
    const compiles = [at('tracer', 1_000, 13_000), at('tonemap', 1_000, 1_500), at('frame', 2_000)];
    const next = withMeasuredCompiles(known, compiles);
    expect(next).toEqual({ tracer: 12_000, tonemap: 500 });
    expect(known).toEqual({ tracer: 20_000 });
    // Nothing new: the same record (the page then has nothing to save).
    expect(withMeasuredCompiles(next, compiles)).toBe(next);
    // The record stays small: the least recently measured go first.
    const capped = withMeasuredCompiles(next, [at('frame', 2_000, 9_000), at('tracer', 3_000, 14_000)], 2);
    expect(Object.entries(capped)).toEqual([['frame', 7_000], ['tracer', 11_000]]);
    // The frame kernel, never measured, is now expected to take the mean of those measured (or the software figure, longer).
    expect(remainingCompileMs(batch(compiles), 2_000, next, SWIFTSHADER)).toBe(Math.max(6_250, remainingCompileMs(batch([at('frame')]), 2_000, {}, SWIFTSHADER)));
    expect(remainingCompileMs(batch(compiles), 2_000, withMeasuredCompiles(next, [at('tracer', 0, 30_000)]), SWIFTSHADER)).toBe(15_250);
  });
});
