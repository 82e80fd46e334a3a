import { describe, expect, it } from 'vitest';
import { frameSelection, isFrameMode, samplesPerPixel } from './render-frames.ts';

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

describe('frame selection (--frames as a count or a list)', () => {
  it('keeps a count as frames 0 to n - 1 of a path that long, and a list as frames of the whole sequence', () => {
    expect(frameSelection({ frames: 3 })).toEqual({ frames: [0, 1, 2], total: undefined, sequence: true });
    expect(frameSelection({ frames: 1 })).toEqual({ frames: [0], total: undefined, sequence: false });
    expect(frameSelection({ path: 'p.json' })).toMatchObject({ total: 30, sequence: true });
    expect(frameSelection({ frames: { list: [2, 3, 47] }, path: 'p.json', pathFrames: 48 })).toEqual({ frames: [2, 3, 47], total: 48, sequence: true });
    expect(frameSelection({ frames: { list: [5] } })).toEqual({ frames: [5], total: undefined, sequence: true });
  });
  it('refuses a frame past the path, and --path-frames where it means nothing', () => {
    expect(() => frameSelection({ frames: { list: [30] }, path: 'p.json' })).toThrow(/path has 30 frames/);
    expect(() => frameSelection({ frames: 4, path: 'p.json', pathFrames: 10 })).toThrow(/--path-frames goes with a list/);
    expect(() => frameSelection({ frames: { list: [1] }, pathFrames: 10 })).toThrow(/applies with --path only/);
  });
});
