import { describe, expect, it } from 'vitest';
import { adapterKey, describeEstimate, estimateFirstFrame, isSoftware, type AdapterFacts } from './first-frame-estimate.ts';

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
