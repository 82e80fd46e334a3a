import { describe, expect, it } from 'vitest';
import { isFrameMode } from './render-frames.ts';

describe('frame mode', () => {
  it('is turned on by the real-time switches, --path, --frames and the hybrid recipe, and off without them', () => {
    expect(isFrameMode({})).toBe(false);
    for (const o of [{ temporal: true }, { denoise: true }, { restir: true }, { path: 'p.json' }, { frames: 1 }, { mode: 'hybrid' }]) expect(isFrameMode(o), JSON.stringify(o)).toBe(true);
  });
});
