/**
 * Image bytes → 8-bit RGBA: PNG through fast-png (src/image/png.ts), JPEG through jpeg-js (pure JS,
 * so it runs in a Web Worker as well as in Node). Sniffed by signature, not by MIME type or file
 * extension, which exporters get wrong. Other formats (WebP, KTX2, AVIF) are not decoded: the caller
 * substitutes a neutral texture and warns.
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

const PNG_SIGNATURE = [0x89, 0x50, 0x4e, 0x47];
const JPEG_SIGNATURE = [0xff, 0xd8, 0xff];

export function decodeImage(bytes: Uint8Array, name: string): ImageDecodeResult {
  try {
    if (startsWith(bytes, PNG_SIGNATURE)) {
      const png = decodePng(bytes, name);
      return { ok: true, image: { width: png.width, height: png.height, rgba: png.data } };
    }
    if (startsWith(bytes, JPEG_SIGNATURE)) {
      const img = decodeJpeg(bytes, { useTArray: true, formatAsRGBA: true, maxResolutionInMP: limits().imagePixels / 1e6, maxMemoryUsageInMB: Math.ceil((limits().imagePixels * 8) / 2 ** 20) });
      return { ok: true, image: { width: img.width, height: img.height, rgba: new Uint8Array(img.data.buffer, img.data.byteOffset, img.data.byteLength) } };
    }
  } catch (e) {
    return { ok: false, reason: `it could not be decoded (${(e as Error).message})` };
  }
  return { ok: false, reason: `its format (${formatName(bytes)}) is not supported; only PNG and JPEG are` };
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
