import { describe, expect, it } from 'vitest';
import { isFrameMode, samplesPerPixel } from './render-frames.ts';

describe('frame mode', () => {
  it('is turned on by the real-time switches, --path, --frames and the hybrid recipe, and off without them', () => {
    expect(isFrameMode({})).toBe(false);
    for (const o of [{ temporal: true }, { denoise: true }, { restir: true }, { path: 'p.json' }, { frames: 1 }, { mode: 'hybrid' }]) expect(isFrameMode(o), JSON.stringify(o)).toBe(true);
  });
});

describe('samples per pixel', () => {
  it('defaults to 64 for a progressive render and to 1 a frame in frame mode; --spp always wins', () => {
    expect(samplesPerPixel({})).toBe(64);
    expect(samplesPerPixel({ temporal: true, denoise: true })).toBe(1);
    expect(samplesPerPixel({ frames: 16, path: 'walk.json' })).toBe(1);
    expect(samplesPerPixel({ spp: 4, temporal: true })).toBe(4);
    expect(samplesPerPixel({ spp: 256 })).toBe(256);
  });
});
