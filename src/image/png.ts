/**
 * 8-bit RGBA PNG in and out: written here (one IDAT of Sub-filtered rows; the zlib step may be
 * Node's native one, which the CLI passes), read with fast-png, for tone-mapped output and reference
 * images. PNG: https://www.w3.org/TR/png/ (chunks §5, filters §7.3 and §9).
 */
import { convertIndexedToRgb, decode, type DecodedPng } from 'fast-png';
import { Unzlib, zlibSync } from 'fflate';
import { checkLimit } from '../budgets.ts';
import { LanternError } from '../errors.ts';

export interface RgbaImage {
  readonly width: number;
  readonly height: number;
  /** 4 bytes per pixel (sRGB-encoded RGBA, straight alpha), row-major, top row first. */
  readonly data: Uint8Array;
}

/** Compresses bytes into a zlib stream (RFC 1950: header, deflate data, Adler-32). */
export type Zlib = (raw: Uint8Array) => Uint8Array;

/** fflate at level 3: portable (the page, the exporters); the CLI passes Node's native zlib instead. */
const portableZlib: Zlib = (raw) => zlibSync(raw, { level: 3 });

const SIGNATURE = [0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a];
/** Filter type 1 (Sub): each byte minus the same channel of the pixel to its left; smooth images shrink. */
const FILTER_SUB = 1;

export function encodePng(width: number, height: number, rgba: Uint8Array, zlib: Zlib = portableZlib): Uint8Array {
  if (!(Number.isInteger(width) && Number.isInteger(height) && width > 0 && height > 0)) {
    throw new LanternError(`cannot write a PNG of ${width}×${height} pixels`);
  }
  if (rgba.length !== width * height * 4) {
    throw new LanternError(`cannot write a PNG: ${rgba.length} bytes given for ${width}×${height} RGBA pixels (${width * height * 4} expected)`);
  }
  const stride = width * 4;
  const filtered = new Uint8Array((stride + 1) * height);
  for (let y = 0; y < height; y++) {
    const row = y * stride, out = y * (stride + 1) + 1;
    filtered[out - 1] = FILTER_SUB;
    for (let i = 0; i < 4; i++) filtered[out + i] = rgba[row + i]!;
    for (let i = 4; i < stride; i++) filtered[out + i] = rgba[row + i]! - rgba[row + i - 4]!;
  }
  const ihdr = new Uint8Array(13);
  const header = new DataView(ihdr.buffer);
  header.setUint32(0, width);
  header.setUint32(4, height);
  ihdr.set([8, 6, 0, 0, 0], 8); // 8 bits, RGBA; deflate, adaptive filtering, no interlace
  const chunks = [chunk('IHDR', ihdr), chunk('IDAT', zlib(filtered)), chunk('IEND', new Uint8Array(0))];
  const file = new Uint8Array(SIGNATURE.length + chunks.reduce((n, c) => n + c.length, 0));
  file.set(SIGNATURE);
  let at = SIGNATURE.length;
  for (const c of chunks) {
    file.set(c, at);
    at += c.length;
  }
  return file;
}

/** Length, type, data, CRC-32 of type and data. */
function chunk(type: string, data: Uint8Array): Uint8Array {
  const out = new Uint8Array(12 + data.length);
  const view = new DataView(out.buffer);
  view.setUint32(0, data.length);
  for (let i = 0; i < 4; i++) out[4 + i] = type.charCodeAt(i);
  out.set(data, 8);
  view.setUint32(8 + data.length, crc32(out, 4, 8 + data.length));
  return out;
}

let crcTable: Uint32Array | undefined;

/** CRC-32 (ISO 3309, as PNG uses it) of bytes[start, end). */
function crc32(bytes: Uint8Array, start: number, end: number): number {
  if (!crcTable) {
    crcTable = new Uint32Array(256);
    for (let n = 0; n < 256; n++) {
      let c = n;
      for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
      crcTable[n] = c >>> 0;
    }
  }
  let c = 0xffffffff;
  for (let i = start; i < end; i++) c = crcTable[(c ^ bytes[i]!) & 255]! ^ (c >>> 8);
  return (c ^ 0xffffffff) >>> 0;
}

/**
 * Any PNG (grey, grey+alpha, RGB, RGBA, palette; 1 to 16 bits) converted to 8-bit RGBA, so callers
 * such as image comparisons handle one layout only. A grey/RGB tRNS colour key is ignored (opaque).
 */
export function decodePng(bytes: Uint8Array, name = 'image.png'): RgbaImage {
  // The size from IHDR (the first chunk, bytes 16–23) is checked before anything is inflated.
  if (bytes.length >= 24 && bytes[12] === 0x49 && bytes[13] === 0x48 && bytes[14] === 0x44 && bytes[15] === 0x52) {
    const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
    const [width, height] = [view.getUint32(16), view.getUint32(20)];
    checkLimit('imagePixels', width * height, `${name}: ${width}×${height} pixels`);
    checkInflatedSize(bytes, name, rawBytes(width, height, bytes[24]!, bytes[25]!, bytes[28]!));
  }
  let png: DecodedPng;
  try {
    // CRCs checked: a damaged reference image should fail loudly, not compare as different pixels.
    png = decode(bytes, { checkCrc: true });
  } catch (e) {
    throw new LanternError(`${name}: not a readable PNG (${(e as Error).message})`, undefined, { cause: e });
  }
  const { width, height } = png;
  let { channels, depth } = png;
  if (channels === 4 && depth === 8 && !png.palette) return { width, height, data: new Uint8Array(png.data) }; // already RGBA8
  let samples: ArrayLike<number> = png.data;
  if (png.palette) {
    // fast-png merges tRNS alpha into the palette entries, so these come out RGB or RGBA.
    try {
      samples = convertIndexedToRgb(png);
    } catch (e) {
      throw new LanternError(`${name}: broken palette image (${(e as Error).message})`, undefined, { cause: e });
    }
    channels = png.palette[0]?.length ?? 3;
    depth = 8;
  } else if (depth < 8) {
    samples = unpackGrey(png.data, width, height, depth);
  }
  const max = 2 ** depth - 1;
  const rgba = new Uint8Array(width * height * 4);
  const grey = channels <= 2, alpha = channels === 2 || channels === 4;
  for (let i = 0, s = 0; i < width * height; i++, s += channels) {
    rgba[4 * i] = Math.round((samples[s]! * 255) / max);
    rgba[4 * i + 1] = Math.round((samples[grey ? s : s + 1]! * 255) / max);
    rgba[4 * i + 2] = Math.round((samples[grey ? s : s + 2]! * 255) / max);
    rgba[4 * i + 3] = alpha ? Math.round((samples[s + channels - 1]! * 255) / max) : 255;
  }
  return { width, height, data: rgba };
}

/** Channels per pixel of each PNG colour type (grey, RGB, palette, grey + alpha, RGBA). */
const CHANNELS: Readonly<Record<number, number>> = { 0: 1, 2: 3, 3: 1, 4: 2, 6: 4 };
/** Adam7's seven passes: first column and row, and the steps between them. */
const ADAM7 = [[0, 0, 8, 8], [4, 0, 8, 8], [0, 4, 4, 8], [2, 0, 4, 4], [0, 2, 2, 4], [1, 0, 2, 2], [0, 1, 1, 2]] as const;

/** The bytes the image data inflates to (filter byte and packed samples per row, per pass when interlaced); undefined for a header fast-png will refuse. */
function rawBytes(width: number, height: number, depth: number, colourType: number, interlace: number): number | undefined {
  const channels = CHANNELS[colourType];
  if (channels === undefined || ![1, 2, 4, 8, 16].includes(depth)) return undefined;
  const rows = (w: number, h: number) => (w === 0 || h === 0 ? 0 : h * (1 + Math.ceil((w * channels * depth) / 8)));
  if (interlace !== 1) return rows(width, height);
  return ADAM7.reduce((n, [x0, y0, dx, dy]) => n + rows(Math.ceil(Math.max(0, width - x0) / dx), Math.ceil(Math.max(0, height - y0) / dy)), 0);
}

/** Slack over the exact size before a stream counts as too long (some encoders write a little more). */
const INFLATE_SLACK = 64 * 1024;
/** Deflate's largest expansion (a 258-byte match in two bits). */
const DEFLATE_RATIO = 1032;
/** Compressed bytes inflated at a time: one slice yields at most ~66 MB (16 KB slices were a third slower). */
const INFLATE_SLICE = 64 * 1024;

/**
 * Inflates the IDAT chunks' zlib stream and counts it, keeping nothing, and refuses a stream that
 * passes what the header's size needs: fast-png inflates the whole stream before it looks, so a
 * 520 KB PNG of 16×16 pixels whose stream inflates to 512 MB took 8 s and 1.5 GB. A stream that is
 * broken is left to fast-png, which says how. The check is a second inflate (on a 2048² RGB
 * texture, half of fast-png's own decoding time again), skipped when the file is too small to
 * inflate to more than twice what it needs.
 */
function checkInflatedSize(bytes: Uint8Array, name: string, expected: number | undefined): void {
  if (expected === undefined || bytes.length * DEFLATE_RATIO <= 2 * expected + INFLATE_SLACK) return;
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  let total = 0;
  const inflater = new Unzlib((chunk) => void (total += chunk.length));
  try {
    for (let at = 8; at + 8 <= bytes.length; ) {
      const length = view.getUint32(at);
      const type = view.getUint32(at + 4);
      const data = bytes.subarray(at + 8, Math.min(bytes.length, at + 8 + length));
      if (type === 0x49444154) {
        // IDAT
        for (let s = 0; s < data.length && total <= expected + INFLATE_SLACK; s += INFLATE_SLICE) inflater.push(data.subarray(s, s + INFLATE_SLICE));
      }
      if (total > expected + INFLATE_SLACK) break;
      at += 12 + length;
    }
  } catch {
    return;
  }
  if (total > expected + INFLATE_SLACK) {
    throw new LanternError(`${name}: its image data inflates past the ${expected.toLocaleString('en-US')} bytes its ${view.getUint32(16)}×${view.getUint32(20)} pixels need`, 'the file is damaged or hostile');
  }
}

/** 1/2/4-bit grey stays packed, most significant bits first, each row starting on a byte boundary. */
function unpackGrey(data: ArrayLike<number>, width: number, height: number, depth: number): Uint8Array {
  const out = new Uint8Array(width * height);
  const perByte = 8 / depth, rowBytes = Math.ceil(width / perByte), mask = (1 << depth) - 1;
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const byte = data[y * rowBytes + Math.floor(x / perByte)]!;
      out[y * width + x] = (byte >> (8 - depth * ((x % perByte) + 1))) & mask;
    }
  }
  return out;
}
