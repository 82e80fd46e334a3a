import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../expect-lantern-error.ts';
import { encodeExr } from '../image/exr.ts';
import { loadEnvironmentImage } from './environment-image.ts';

describe('loadEnvironmentImage', () => {
  it('sniffs OpenEXR by its magic number, whatever the name', () => {
    const rgb = new Float32Array([1, 2, 3, 0.5, 0.25, 0.125]);
    const image = loadEnvironmentImage(encodeExr(2, 1, rgb), 'sky.hdr');
    expect([image.name, image.width, image.height]).toEqual(['sky.hdr', 2, 1]);
    expect(Array.from(image.rgb)).toEqual(Array.from(rgb));
  });

  it('sniffs Radiance .hdr by its #? line', () => {
    // One flat pixel: mantissas (128, 64, 32), exponent 129 → (m + 0.5) · 2^(129 − 136).
    const header = new TextEncoder().encode('#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 1\n');
    const image = loadEnvironmentImage(new Uint8Array([...header, 128, 64, 32, 129]), 'x.exr');
    expect(Array.from(image.rgb)).toEqual([128.5 / 128, 64.5 / 128, 32.5 / 128]);
  });

  it('refuses anything else with a LanternError', () => {
    expectLanternError(() => loadEnvironmentImage(new Uint8Array([0x89, 0x50, 0x4e, 0x47]), 'a.png'), /not a Radiance .hdr or OpenEXR/);
  });
});
