/**
 * The Doom picture format (https://doomwiki.org/wiki/Picture_format), used by wall patches and
 * sprites: an 8-byte header (int16 width, height, left offset, top offset), one uint32 offset per
 * column, and per column a list of posts: topdelta, length, an unused byte, `length` palette
 * indices, an unused byte; topdelta 0xFF ends the column. Pixels no post covers are transparent.
 *
 * Tall pictures (over 254 rows, from DeePsea and later tools) reuse topdelta as a relative step: a
 * topdelta not greater than the running top adds to it, as ZDoom and PrBoom read them. Ordinary
 * pictures, whose posts go strictly downward, read the same either way.
 *
 * Input may be garbage: every read is bounds-checked, and each loop advances through the data, so a
 * bad lump costs a warning or a LanternError, never a hang.
 */
import { LanternError } from '../../errors.ts';
import type { Texture } from '../../scene/types.ts';
import type { Palette } from './palette.ts';

export interface PictureHeader {
  readonly width: number;
  readonly height: number;
  /** Where the picture's origin lies, from its top-left corner (sprites; walls ignore these). */
  readonly leftOffset: number;
  readonly topOffset: number;
}

export interface Picture extends Texture, PictureHeader {}

/** Refused outright: far beyond any real picture (vanilla's are at most 320×200 or so; hi-res ones 4096²). */
export const MAX_PICTURE_PIXELS = 4096 * 4096;

const PNG_SIGNATURE = [0x89, 0x50, 0x4e, 0x47];

/** The header, checked against the lump: positive size, a column table that fits. */
export function readPictureHeader(bytes: Uint8Array, name: string): PictureHeader {
  if (PNG_SIGNATURE.every((b, i) => bytes[i] === b)) {
    throw new LanternError(`picture ${name} is a PNG`, 'Lantern reads Doom-format pictures only (PNG patches are a ZDoom extension)');
  }
  if (bytes.length < 8) throw new LanternError(`picture ${name} is too short (${bytes.length} bytes) to be a Doom picture`);
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const width = view.getInt16(0, true);
  const height = view.getInt16(2, true);
  if (width <= 0 || height <= 0) throw new LanternError(`picture ${name} has an invalid size ${width}×${height}`);
  if (8 + 4 * width > bytes.length) {
    throw new LanternError(`picture ${name} is corrupt: its ${width} column offsets run past the end of the ${bytes.length}-byte lump`);
  }
  if (width * height > MAX_PICTURE_PIXELS) throw new LanternError(`picture ${name} is implausibly large (${width}×${height})`);
  return { width, height, leftOffset: view.getInt16(4, true), topOffset: view.getInt16(6, true) };
}

/** An RGBA surface as 32-bit words (see Palette.packed). */
export interface PixelTarget {
  readonly width: number;
  readonly height: number;
  readonly pixels: Uint32Array;
}

/**
 * Draws the picture's posts into `target` with its top-left corner at (x, y), clipped to the target;
 * later draws overwrite earlier ones only where a post covers. Returns a description of any damage
 * found (columns pointing outside the lump, posts cut off by its end), or undefined when clean.
 */
export function drawPicture(bytes: Uint8Array, header: PictureHeader, palette: Palette, target: PixelTarget, x: number, y: number): string | undefined {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const { pixels, width: tw, height: th } = target;
  const colors = palette.packed;
  const end = bytes.length;
  let badColumns = 0;
  let truncated = 0;
  let garbled = 0;
  // A real column has about one post per run of rows (plus a few empty stepping posts in tall
  // pictures); far more means garbage, and bounding it bounds the work at about width × height.
  const maxPosts = 2 * header.height + 64;
  const x0 = Math.max(0, -x);
  const x1 = Math.min(header.width, tw - x);
  for (let c = x0; c < x1; c++) {
    let pos = view.getUint32(8 + 4 * c, true);
    if (pos >= end) {
      badColumns++;
      continue;
    }
    const tx = x + c;
    let top = -1;
    let posts = 0;
    // Each post advances pos by at least 4, so this also ends within (end - pos) / 4 steps.
    while (pos < end) {
      const delta = bytes[pos]!;
      if (delta === 0xff) break;
      if (++posts > maxPosts) {
        garbled++;
        break;
      }
      if (pos + 3 > end) {
        truncated++;
        break;
      }
      top = delta <= top ? top + delta : delta;
      const first = pos + 3;
      let length = bytes[pos + 1]!;
      if (first + length > end) {
        truncated++;
        length = Math.max(0, end - first);
      }
      // Rows of this post inside the target.
      const r0 = Math.max(0, -(y + top));
      const r1 = Math.min(length, th - (y + top));
      let out = (y + top + r0) * tw + tx;
      for (let r = r0; r < r1; r++, out += tw) pixels[out] = colors[bytes[first + r]!]!;
      pos = first + length + 1;
    }
  }
  if (badColumns === 0 && truncated === 0 && garbled === 0) return undefined;
  const parts: string[] = [];
  if (badColumns > 0) parts.push(`${badColumns} column(s) point past the end of the lump`);
  if (truncated > 0) parts.push(`${truncated} column(s) are cut off by the end of the lump`);
  if (garbled > 0) parts.push(`${garbled} column(s) have more posts than rows (garbage)`);
  return parts.join('; ');
}

/** A whole picture as RGBA, alpha 0 where no post covers. Damage is reported through onWarning. */
export function decodePicture(bytes: Uint8Array, name: string, palette: Palette, onWarning?: (message: string) => void): Picture {
  const header = readPictureHeader(bytes, name);
  const rgba = new Uint8Array(header.width * header.height * 4);
  const pixels = new Uint32Array(rgba.buffer);
  const damage = drawPicture(bytes, header, palette, { width: header.width, height: header.height, pixels }, 0, 0);
  if (damage) onWarning?.(`picture ${name}: ${damage}; drew the rest`);
  return { name, ...header, rgba };
}
