/**
 * Bytes of an HDR panorama (Radiance .hdr or OpenEXR, told apart by their first bytes, not the name)
 * → an EnvironmentImage: linear RGB, lat-long, top row first (scene/environment.ts).
 */
import { LanternError } from '../errors.ts';
import { decodeExrRgb } from '../image/exr.ts';
import { EXR_MAGIC } from '../image/exr-format.ts';
import { decodeHdr, isHdr } from '../image/hdr.ts';
import type { EnvironmentImage } from '../scene/environment.ts';

/** An OpenEXR file starts with its magic number as a little-endian u32. */
export function isExr(bytes: Uint8Array): boolean {
  return bytes.length >= 4 && new DataView(bytes.buffer, bytes.byteOffset, 4).getUint32(0, true) === EXR_MAGIC;
}

export function loadEnvironmentImage(bytes: Uint8Array, name: string): EnvironmentImage {
  if (isHdr(bytes)) {
    const { width, height, rgb } = decodeHdr(bytes, name);
    return { name, width, height, rgb };
  }
  if (isExr(bytes)) {
    const { width, height, rgb } = decodeExrRgb(bytes, name);
    return { name, width, height, rgb };
  }
  throw new LanternError(`${name}: not a Radiance .hdr or OpenEXR image`, 'use an equirectangular .hdr or .exr panorama');
}
