import { existsSync, readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../expect-lantern-error.ts';
import { decodeHdr } from './hdr.ts';

/** The test's own RGBE encoder: the shared exponent of the largest component, Radiance's rounding. */
function rgbe(r: number, g: number, b: number): [number, number, number, number] {
  const max = Math.max(r, g, b);
  if (max < 1e-32) return [0, 0, 0, 0];
  const e = Math.ceil(Math.log2(max * (1 + 1e-9)));
  // max ≤ 2^e, so the mantissas m = v · 256 / 2^e are below 256.
  const f = 256 / 2 ** e;
  return [Math.floor(r * f), Math.floor(g * f), Math.floor(b * f), e + 128];
}

type Scanlines = 'flat' | 'rle' | 'old-rle';

function encodeHdr(width: number, height: number, rgb: ArrayLike<number>, mode: Scanlines, header = 'FORMAT=32-bit_rle_rgbe\n'): Uint8Array {
  const out: number[] = [...new TextEncoder().encode(`#?RADIANCE\n# test\n${header}\n-Y ${height} +X ${width}\n`)];
  for (let y = 0; y < height; y++) {
    const pixels: [number, number, number, number][] = [];
    for (let x = 0; x < width; x++) {
      const i = (y * width + x) * 3;
      pixels.push(rgbe(rgb[i]!, rgb[i + 1]!, rgb[i + 2]!));
    }
    if (mode === 'rle') {
      out.push(2, 2, width >> 8, width & 255);
      for (let c = 0; c < 4; c++) {
        const plane = pixels.map((p) => p[c]!);
        let x = 0;
        while (x < width) {
          let run = 1;
          while (x + run < width && run < 127 && plane[x + run] === plane[x]) run++;
          if (run >= 3) {
            out.push(128 + run, plane[x]!);
            x += run;
          } else {
            const n = Math.min(128, width - x, 2);
            out.push(n, ...plane.slice(x, x + n));
            x += n;
          }
        }
      }
    } else if (mode === 'old-rle') {
      // Repeats of the previous pixel become one run (1, 1, 1, n), n < 256 (a second run marker
      // in a row would mean n << 8).
      let x = 0;
      while (x < width) {
        const p = pixels[x]!;
        out.push(...p);
        let n = 0;
        while (x + 1 + n < width && n < 255 && pixels[x + 1 + n]!.every((v, k) => v === p[k])) n++;
        if (n > 0) out.push(1, 1, 1, n);
        x += 1 + n;
      }
    } else {
      for (const p of pixels) out.push(...p);
    }
  }
  return new Uint8Array(out);
}

/** A test image with runs (constant stretches) and noise, values spanning many exponents. */
function testImage(width: number, height: number): Float32Array {
  const rgb = new Float32Array(width * height * 3);
  let seed = 7;
  const rand = () => ((seed = (Math.imul(seed, 1664525) + 1013904223) >>> 0) / 2 ** 32);
  for (let i = 0; i < width * height; i++) {
    const x = i % width;
    const stretch = x % 16 < 8;
    for (let c = 0; c < 3; c++) rgb[i * 3 + c] = stretch ? 0.25 * (c + 1) : rand() * 10 ** (rand() * 8 - 4);
  }
  return rgb;
}

/** RGBE keeps 8 bits per component relative to the largest one: error ≤ 2^e / 256 per component. */
function expectClose(decoded: Float32Array, original: Float32Array): void {
  expect(decoded.length).toBe(original.length);
  for (let i = 0; i < original.length; i += 3) {
    const max = Math.max(original[i]!, original[i + 1]!, original[i + 2]!);
    const step = 2 ** Math.ceil(Math.log2(max * (1 + 1e-9))) / 256;
    for (let c = 0; c < 3; c++) expect(Math.abs(decoded[i + c]! - original[i + c]!)).toBeLessThanOrEqual(step * 0.5 + 1e-30);
  }
}

describe('Radiance .hdr decoder', () => {
  for (const mode of ['rle', 'flat', 'old-rle'] as const) {
    it(`decodes ${mode} scanlines to within half an RGBE step`, () => {
      const w = 40, h = 5;
      const rgb = testImage(w, h);
      const image = decodeHdr(encodeHdr(w, h, rgb, mode));
      expect([image.width, image.height]).toEqual([w, h]);
      expectClose(image.rgb, rgb);
    });
  }

  it('RLE actually compresses (the test encoder exercises runs)', () => {
    const rgb = testImage(64, 4);
    expect(encodeHdr(64, 4, rgb, 'rle').length).toBeLessThan(encodeHdr(64, 4, rgb, 'flat').length);
  });

  it('reads narrow images (< 8 pixels) flat and keeps the top row first', () => {
    const rgb = new Float32Array([1, 1, 1, 2, 2, 2, 4, 4, 4, 8, 8, 8]); // 2×2: rows (1, 2), (4, 8)
    const image = decodeHdr(encodeHdr(2, 2, rgb, 'flat'));
    expect(Array.from(image.rgb)).toEqual(Array.from(rgb).map((v) => v * (1 + 0.5 / 128)));
  });

  it('divides by EXPOSURE (cumulative) and accepts #?RGBE', () => {
    const rgb = new Float32Array(8 * 3).fill(1);
    const radiance = encodeHdr(8, 1, rgb, 'rle', 'EXPOSURE=2\nFORMAT=32-bit_rle_rgbe\nEXPOSURE=4\n');
    expect(decodeHdr(radiance).rgb[0]).toBeCloseTo((1 + 0.5 / 128) / 8, 6);
    const text = new TextDecoder('latin1').decode(radiance).replace('#?RADIANCE', '#?RGBE');
    const rgbeMagic = new Uint8Array([...text].map((ch) => ch.charCodeAt(0)));
    expect(decodeHdr(rgbeMagic).rgb[0]).toBeCloseTo((1 + 0.5 / 128) / 8, 6);
  });

  it('refuses other orientations, other formats, bad magic, absurd sizes', () => {
    const rgb = new Float32Array(8 * 2 * 3).fill(0.5);
    const good = new TextDecoder('latin1').decode(encodeHdr(8, 2, rgb, 'flat'));
    const bytes = (s: string) => new Uint8Array([...s].map((ch) => ch.charCodeAt(0)));
    expectLanternError(() => decodeHdr(bytes(good.replace('-Y 2 +X 8', '+Y 2 +X 8'))), /orientation '\+Y 2 \+X 8'/);
    expectLanternError(() => decodeHdr(bytes(good.replace('-Y 2 +X 8', '-X 8 +Y 2'))), /orientation/);
    expectLanternError(() => decodeHdr(bytes(good.replace('32-bit_rle_rgbe', '32-bit_rle_xyze'))), /xyze/);
    expectLanternError(() => decodeHdr(bytes(good.replace('#?RADIANCE', '#?PFM'))), /not a Radiance/);
    expectLanternError(() => decodeHdr(bytes(good.replace('-Y 2 +X 8', '-Y 100000 +X 100000'))), /too large/);
    expectLanternError(() => decodeHdr(bytes(good.replace('-Y 2 +X 8', '-Y 0 +X 8'))), /empty/);
    // A few bytes that claim 4096 × 4096 pixels: refused before 192 MiB of floats are allocated.
    expectLanternError(() => decodeHdr(bytes(good.replace('-Y 2 +X 8', '-Y 4096 +X 4096'))), /truncated: 4096 scanlines need at least 16384 bytes, \d+ are left/);
  });

  it('reports truncation and malformed runs, never hangs', () => {
    const w = 32, h = 3;
    const rgb = testImage(w, h);
    for (const mode of ['rle', 'flat'] as const) {
      const file = encodeHdr(w, h, rgb, mode);
      for (const cut of [10, 40, file.length - 200, file.length - 1]) {
        expectLanternError(() => decodeHdr(file.subarray(0, cut)), /truncated/);
      }
    }
    const file = encodeHdr(w, 1, rgb, 'rle');
    const start = file.length - (file.length - new TextEncoder().encode(`#?RADIANCE\n# test\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X ${w}\n`).length);
    const overrun = file.slice();
    overrun[start + 4] = 128 + 100; // a run of 100 in a 32-wide scanline
    expectLanternError(() => decodeHdr(overrun), /overruns/);
    const zero = file.slice();
    zero[start + 4] = 0;
    expectLanternError(() => decodeHdr(zero), /zero-length/);
    const wrongWidth = file.slice();
    wrongWidth[start + 3] = w + 1;
    expectLanternError(() => decodeHdr(wrongWidth), /width 33/);
  });

  const real = '/work/shared/assets/hdr/spiaggia_di_mondello_1k.hdr';
  it.skipIf(!existsSync(real))('decodes the real 1k map (Poly Haven, RLE) to plausible radiance', () => {
    const t0 = performance.now();
    const image = decodeHdr(new Uint8Array(readFileSync(real)), 'spiaggia_di_mondello_1k.hdr');
    const ms = performance.now() - t0;
    expect([image.width, image.height]).toEqual([1024, 512]);
    let sum = 0, max = 0, maxAt = 0, bad = 0;
    for (let i = 0; i < image.rgb.length; i++) {
      const v = image.rgb[i]!;
      if (!Number.isFinite(v) || v < 0) bad++;
      sum += v;
      if (v > max) [max, maxAt] = [v, i];
    }
    expect(bad).toBe(0);
    // A sunny beach: the brightest pixel is the sun, in the upper half (the sky: top row first),
    // thousands of times the mean.
    const row = Math.floor(maxAt / 3 / 1024);
    expect(row).toBeLessThan(256);
    expect(max).toBeGreaterThan(1000 * (sum / image.rgb.length));
    expect(ms).toBeLessThan(1000);
  });
});
if (!existsSync('/work/shared/assets/hdr/spiaggia_di_mondello_1k.hdr')) console.warn('hdr.test: real map absent, its test is skipped');
