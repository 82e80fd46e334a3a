/** 8-bit RGBA PNG in and out, over fast-png, for tone-mapped output and reference images. */
import { convertIndexedToRgb, decode, encode, type DecodedPng } from 'fast-png';
import { LanternError } from '../errors.ts';

export interface RgbaImage {
  readonly width: number;
  readonly height: number;
  /** 4 bytes per pixel (sRGB-encoded RGBA, straight alpha), row-major, top row first. */
  readonly data: Uint8Array;
}

export function encodePng(width: number, height: number, rgba: Uint8Array): Uint8Array {
  if (!(Number.isInteger(width) && Number.isInteger(height) && width > 0 && height > 0)) {
    throw new LanternError(`cannot write a PNG of ${width}×${height} pixels`);
  }
  if (rgba.length !== width * height * 4) {
    throw new LanternError(`cannot write a PNG: ${rgba.length} bytes given for ${width}×${height} RGBA pixels (${width * height * 4} expected)`);
  }
  return encode({ width, height, data: rgba, channels: 4, depth: 8 });
}

/**
 * Any PNG (grey, grey+alpha, RGB, RGBA, palette; 1 to 16 bits) converted to 8-bit RGBA, so callers
 * such as image comparisons handle one layout only. A grey/RGB tRNS colour key is ignored (opaque).
 */
export function decodePng(bytes: Uint8Array, name = 'image.png'): RgbaImage {
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
