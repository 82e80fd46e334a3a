/**
 * Image bytes → 8-bit RGBA: PNG through fast-png (src/image/png.ts), JPEG through jpeg-js (pure JS,
 * so it runs in a Web Worker as well as in Node). Sniffed by signature, not by MIME type or file
 * extension, which exporters get wrong. Other formats (WebP, KTX2, AVIF) are not decoded: the caller
 * substitutes a neutral texture and warns.
 *
 * The size comes from the header first (`readImage`: PNG's IHDR, JPEG's start of frame), so
 * the caller can charge the texture budget before anything is decoded; a JPEG's scans are counted
 * there too: jpeg-js passes over every block of the image once per scan, so a few bytes per scan
 * (end-of-band runs) made a 1 MB progressive JPEG of 30,000 scans decode for minutes.
 */
import { decode as decodeJpeg } from 'jpeg-js';
import { limits } from '../../budgets.ts';
import { decodePng } from '../../image/png.ts';

export interface DecodedImage {
  readonly width: number;
  readonly height: number;
  readonly rgba: Uint8Array;
}

export type ImageDecodeResult = { readonly ok: true; readonly image: DecodedImage } | { readonly ok: false; readonly reason: string };

/** An image whose header was read: its size, and its pixels on demand. */
export type ImageSource =
  | { readonly ok: true; readonly width: number; readonly height: number; decode(): ImageDecodeResult }
  | { readonly ok: false; readonly reason: string };

const PNG_SIGNATURE = [0x89, 0x50, 0x4e, 0x47];
const JPEG_SIGNATURE = [0xff, 0xd8, 0xff];

/**
 * Scans one JPEG may have. libjpeg's progressive script writes 10 for colour images (6 for grey),
 * mozjpeg's optimised ones about as many; the format allows hundreds, and each costs a pass over
 * the image: a 4096² JPEG of 32 (end-of-band) scans took 6.4 s through `lantern info` on the loaded
 * 2-core machine, one of 100 scans 11 s, and the texel budget admits eight such images.
 */
export const MAX_JPEG_SCANS = 32;

/**
 * Width and height from the header (PNG's IHDR, JPEG's start of frame), nothing decompressed, or why
 * the image cannot be decoded; `decode` then decodes it.
 */
export function readImage(bytes: Uint8Array, name: string): ImageSource {
  if (startsWith(bytes, PNG_SIGNATURE)) {
    // IHDR is the first chunk: width and height at bytes 16 and 20, big-endian.
    if (bytes.length < 24) return { ok: false, reason: 'it is a PNG cut short before its size' };
    const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
    return { ok: true, width: view.getUint32(16), height: view.getUint32(20), decode: () => decoded(() => decodePng(bytes, name)) };
  }
  if (startsWith(bytes, JPEG_SIGNATURE)) {
    const size = jpegSize(bytes);
    if (!size.ok) return size;
    const options = { useTArray: true as const, formatAsRGBA: true, maxResolutionInMP: limits().imagePixels / 1e6, maxMemoryUsageInMB: Math.ceil((limits().imagePixels * 8) / 2 ** 20) };
    return { ...size, decode: () => decoded(() => decodeJpeg(bytes, options)) };
  }
  return { ok: false, reason: `its format (${formatName(bytes)}) is not supported; only PNG and JPEG are` };
}

function decoded(decode: () => { width: number; height: number; data: Uint8Array }): ImageDecodeResult {
  try {
    const { width, height, data } = decode();
    return { ok: true, image: { width, height, rgba: new Uint8Array(data.buffer, data.byteOffset, data.byteLength) } };
  } catch (e) {
    return { ok: false, reason: `it could not be decoded (${(e as Error).message})` };
  }
}

/**
 * A JPEG's size from its start-of-frame segment, after walking every marker to count the scans
 * (start-of-scan segments; the entropy-coded data after each is skipped to the next marker).
 */
function jpegSize(bytes: Uint8Array): { readonly ok: true; readonly width: number; readonly height: number } | { readonly ok: false; readonly reason: string } {
  let size: { width: number; height: number } | undefined;
  let scans = 0;
  let at = 2;
  while (at + 1 < bytes.length) {
    if (bytes[at] !== 0xff) {
      // Entropy-coded data (after a start of scan): up to the next marker, skipping stuffed 0xFF 00 and restarts.
      at++;
      continue;
    }
    const marker = bytes[at + 1]!;
    if (marker === 0xff || marker === 0x00 || (marker >= 0xd0 && marker <= 0xd7) || marker === 0x01) {
      at += marker === 0xff ? 1 : 2; // fill byte, stuffed zero, restart marker, TEM: no length
      continue;
    }
    if (marker === 0xd9) break; // end of image
    if (at + 4 > bytes.length) break;
    const length = (bytes[at + 2]! << 8) | bytes[at + 3]!;
    // SOF0–SOF15 but DHT (C4), JPG (C8) and DAC (CC): precision, height, width.
    if (marker >= 0xc0 && marker <= 0xcf && marker !== 0xc4 && marker !== 0xc8 && marker !== 0xcc && !size && at + 9 <= bytes.length) {
      size = { height: (bytes[at + 5]! << 8) | bytes[at + 6]!, width: (bytes[at + 7]! << 8) | bytes[at + 8]! };
    }
    if (marker === 0xda && ++scans > MAX_JPEG_SCANS) {
      return { ok: false, reason: `it is a JPEG of more than ${MAX_JPEG_SCANS} scans, which Lantern does not decode (encoders write about 10; each scan is a pass over the whole image)` };
    }
    at += 2 + length;
  }
  if (!size) return { ok: false, reason: 'it is a JPEG without a frame header (no size)' };
  return { ok: true, ...size };
}

function startsWith(bytes: Uint8Array, signature: readonly number[]): boolean {
  return signature.every((b, i) => bytes[i] === b);
}

function formatName(bytes: Uint8Array): string {
  const ascii = (from: number, to: number) => String.fromCharCode(...bytes.subarray(from, to));
  if (ascii(0, 4) === 'RIFF' && ascii(8, 12) === 'WEBP') return 'WebP';
  if (bytes[0] === 0xab && ascii(1, 7) === 'KTX 20') return 'KTX2';
  if (ascii(4, 12) === 'ftypavif') return 'AVIF';
  return 'unknown';
}
