/**
 * Reads Radiance RGBE (.hdr, .pic) images: G. Ward, "Real Pixels" (Graphics Gems II, 1991) and the
 * Radiance file format notes (radsite.lbl.gov, "Radiance File Formats": the picture file).
 *
 * File: a header of text lines ("#?RADIANCE" or "#?RGBE" first, then VARIABLE=value lines, ended by an
 * empty line), a resolution line, then scanlines. Each pixel is 4 bytes: a shared exponent e and three
 * mantissas m, meaning m · 2^(e − 136) (Radiance adds half a step, (m + 0.5) · 2^(e − 136), so decoded
 * values sit in the middle of their quantisation bin; e = 0 is black). Scanlines are either flat
 * (optionally with the old run-length scheme: a pixel (1, 1, 1, n) repeats the previous pixel n << s
 * times, s growing by 8 for each consecutive such pixel) or new-style: (2, 2, width >> 8, width & 255)
 * followed by the four components of the scanline one after the other, each as runs (a count byte
 * > 128: that many − 128 copies of the next byte) and literals (a count byte 1..128: that many bytes).
 */
import { checkLimit } from '../budgets.ts';
import { LanternError } from '../errors.ts';

export interface HdrImage {
  readonly width: number;
  readonly height: number;
  /** width × height × 3 floats, linear RGB, top row first. Divided by the header's EXPOSURE. */
  readonly rgb: Float32Array;
}

/** Largest side and pixel count we accept: 16k wide, 64 Mpx (768 MiB of floats). Larger is refused. */
export const HDR_MAX_SIDE = 32_768;
export const HDR_MAX_PIXELS = 64 * 1024 * 1024;
/** A header longer than this is not a Radiance header. */
const MAX_HEADER_BYTES = 64 * 1024;
/** New-style run-length scanlines exist only for widths in [8, 0x7fff]. */
const RLE_MIN_WIDTH = 8;
const RLE_MAX_WIDTH = 0x7fff;
/** A count byte above this starts a run of (count − RUN_FLAG) copies. */
const RUN_FLAG = 128;
/** The fewest bytes any scanline takes: one pixel (a flat scanline starts with a literal pixel, and a run-length one has a 4-byte header). */
const MIN_SCANLINE_BYTES = 4;
/** Radiance's exponent bias (128) plus the 8 bits of the mantissa. */
const EXPONENT_OFFSET = 136;

export function isHdr(bytes: Uint8Array): boolean {
  return bytes.length >= 2 && bytes[0] === 0x23 /* # */ && bytes[1] === 0x3f; /* ? */
}

export function decodeHdr(bytes: Uint8Array, name = 'image.hdr'): HdrImage {
  const fail = (what: string): LanternError =>
    new LanternError(`${name}: ${what}`, 'check that the file is a complete Radiance .hdr image');
  let pos = 0;
  const readLine = (): string => {
    const start = pos;
    while (pos < bytes.length && bytes[pos] !== 0x0a) {
      if (pos - start > MAX_HEADER_BYTES) throw fail('header line too long; not a Radiance header');
      pos++;
    }
    if (pos >= bytes.length) throw fail('truncated header (no end of line)');
    const line = new TextDecoder('latin1').decode(bytes.subarray(start, pos));
    pos++;
    return line.replace(/\r$/, '');
  };

  const magic = readLine();
  if (magic !== '#?RADIANCE' && magic !== '#?RGBE') {
    throw fail(`not a Radiance .hdr file (first line '${magic.slice(0, 40)}', expected '#?RADIANCE' or '#?RGBE')`);
  }
  let exposure = 1;
  for (;;) {
    if (pos > MAX_HEADER_BYTES) throw fail('header longer than 64 KiB');
    const line = readLine();
    if (line === '') break;
    const eq = line.indexOf('=');
    if (eq < 0 || line.startsWith('#')) continue;
    const key = line.slice(0, eq).trim();
    const value = line.slice(eq + 1).trim();
    if (key === 'FORMAT' && value !== '32-bit_rle_rgbe') {
      throw new LanternError(`${name}: pixel format '${value}' is not supported`, 'save the image as 32-bit_rle_rgbe (RGB, not XYZ)');
    }
    if (key === 'EXPOSURE') {
      // EXPOSURE is a multiplier already applied to the pixels; several lines multiply.
      const e = Number(value);
      if (!Number.isFinite(e) || e <= 0) throw fail(`invalid EXPOSURE '${value}'`);
      exposure *= e;
    }
  }

  const resolution = readLine();
  const m = /^\s*([-+])Y\s+(\d+)\s+([-+])X\s+(\d+)\s*$/.exec(resolution);
  if (!m) {
    throw new LanternError(
      `${name}: image orientation '${resolution.slice(0, 40)}' is not supported (only '-Y height +X width', top row first)`,
      'convert the image to the standard orientation',
    );
  }
  if (m[1] !== '-' || m[3] !== '+') {
    throw new LanternError(
      `${name}: image orientation '${resolution.trim()}' is not supported (only '-Y height +X width', top row first)`,
      'convert the image to the standard orientation',
    );
  }
  const height = Number(m[2]);
  const width = Number(m[4]);
  if (width < 1 || height < 1) throw fail(`empty image (${width}×${height})`);
  if (width > HDR_MAX_SIDE || height > HDR_MAX_SIDE || width * height > HDR_MAX_PIXELS) {
    throw new LanternError(`${name}: image of ${width}×${height} pixels is too large`, `use a map of at most ${HDR_MAX_PIXELS / (1024 * 1024)} Mpx, sides up to ${HDR_MAX_SIDE}`);
  }
  checkLimit('imagePixels', width * height, `${name}: ${width}×${height} pixels`);
  // A truncated file that claims a large image fails here, before its pixels are allocated.
  if (bytes.length - pos < height * MIN_SCANLINE_BYTES) {
    throw fail(`truncated: ${height} scanlines need at least ${height * MIN_SCANLINE_BYTES} bytes, ${bytes.length - pos} are left`);
  }

  const rgb = new Float32Array(width * height * 3);
  const scanline = new Uint8Array(width * 4);
  const scale = new Float32Array(256);
  for (let e = 1; e < 256; e++) scale[e] = 2 ** (e - EXPONENT_OFFSET) / exposure;

  for (let y = 0; y < height; y++) {
    if (pos + 4 > bytes.length) throw fail(`truncated at scanline ${y} of ${height}`);
    const b0 = bytes[pos]!, b1 = bytes[pos + 1]!, b2 = bytes[pos + 2]!, b3 = bytes[pos + 3]!;
    if (width >= RLE_MIN_WIDTH && width <= RLE_MAX_WIDTH && b0 === 2 && b1 === 2 && (b2 & 0x80) === 0) {
      if (((b2 << 8) | b3) !== width) throw fail(`scanline ${y} says width ${(b2 << 8) | b3}, the image is ${width} wide`);
      pos += 4;
      // Four planes: R mantissas, G, B, exponents, each `width` bytes as runs and literals.
      for (let c = 0; c < 4; c++) {
        let x = 0;
        while (x < width) {
          if (pos >= bytes.length) throw fail(`truncated in scanline ${y} of ${height}`);
          let count = bytes[pos++]!;
          if (count > RUN_FLAG) {
            count -= RUN_FLAG;
            if (x + count > width) throw fail(`run overruns scanline ${y}`);
            if (pos >= bytes.length) throw fail(`truncated in scanline ${y} of ${height}`);
            const v = bytes[pos++]!;
            for (let k = 0; k < count; k++) scanline[(x + k) * 4 + c] = v;
          } else {
            if (count === 0) throw fail(`zero-length literal in scanline ${y}`);
            if (x + count > width) throw fail(`literal overruns scanline ${y}`);
            if (pos + count > bytes.length) throw fail(`truncated in scanline ${y} of ${height}`);
            for (let k = 0; k < count; k++) scanline[(x + k) * 4 + c] = bytes[pos + k]!;
            pos += count;
          }
          x += count;
        }
      }
    } else {
      // Flat pixels, with the old run-length scheme.
      let x = 0;
      let shift = 0;
      while (x < width) {
        if (pos + 4 > bytes.length) throw fail(`truncated in scanline ${y} of ${height}`);
        const r = bytes[pos]!, g = bytes[pos + 1]!, b = bytes[pos + 2]!, e = bytes[pos + 3]!;
        pos += 4;
        if (r === 1 && g === 1 && b === 1) {
          if (x === 0) throw fail(`old-style run with no pixel to repeat in scanline ${y}`);
          const count = e * 2 ** shift;
          if (x + count > width) throw fail(`old-style run overruns scanline ${y}`);
          for (let k = 0; k < count; k++) scanline.copyWithin((x + k) * 4, (x - 1) * 4, x * 4);
          x += count;
          shift += 8;
        } else {
          scanline[x * 4] = r;
          scanline[x * 4 + 1] = g;
          scanline[x * 4 + 2] = b;
          scanline[x * 4 + 3] = e;
          x++;
          shift = 0;
        }
      }
    }
    let o = y * width * 3;
    for (let x = 0; x < width; x++) {
      const e = scanline[x * 4 + 3]!;
      if (e === 0) {
        rgb[o] = rgb[o + 1] = rgb[o + 2] = 0;
      } else {
        const f = scale[e]!;
        rgb[o] = (scanline[x * 4]! + 0.5) * f;
        rgb[o + 1] = (scanline[x * 4 + 1]! + 0.5) * f;
        rgb[o + 2] = (scanline[x * 4 + 2]! + 0.5) * f;
      }
      o += 3;
    }
  }
  return { width, height, rgb };
}
