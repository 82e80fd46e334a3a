/**
 * VSWAP, the game's page file (ModdingWiki, "VSWAP Format"): a header of three u16 (chunk count,
 * first sprite chunk, first sound chunk), then each chunk's offset (u32) and length (u16). Chunks
 * before the sprite start are wall pages: 64 × 64 palette indices, column-major (byte x · 64 + y).
 * Chunks from the sprite start to the sound start are sprites in the game's compiled form: leftpix,
 * rightpix (u16), one u16 offset per column from leftpix to rightpix, and at each offset the column's
 * posts, three u16 each (end row · 2, source offset, start row · 2) up to a 0 word, the texel of
 * row y being byte source offset + y of the chunk. Sound chunks are not read. All little-endian;
 * offsets and lengths are checked against the file when it is read, posts when a page is decoded.
 * Pure.
 */
import { LanternError } from '../../errors.ts';
import type { NamedBytes } from '../format.ts';
import type { WolfImage } from './types.ts';

/** Wall and sprite pages are 64 texels square. */
export const PAGE_SIZE = 64;
export const WALL_PAGE_BYTES = PAGE_SIZE * PAGE_SIZE;
const HINT = 'the file is truncated or damaged; use the files of one installation of the game';

export interface Chunk {
  /** 0 for a chunk the file leaves out (a sparse page). */
  readonly offset: number;
  readonly length: number;
}

export interface VswapFile {
  readonly name: string;
  readonly bytes: Uint8Array;
  readonly chunks: readonly Chunk[];
  readonly spriteStart: number;
  readonly soundStart: number;
}

export function readVswap(file: NamedBytes): VswapFile {
  const { name, bytes } = file;
  if (bytes.length < 6) throw new LanternError(`${name}: not a VSWAP file (${bytes.length} bytes: too short for its 6-byte header)`, HINT);
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const count = view.getUint16(0, true);
  const spriteStart = view.getUint16(2, true);
  const soundStart = view.getUint16(4, true);
  if (!(spriteStart <= soundStart && soundStart <= count)) {
    throw new LanternError(`${name}: the header's chunk counts do not fit together (sprites from ${spriteStart}, sounds from ${soundStart}, ${count} chunks)`, HINT);
  }
  // Checked before anything is allocated: the table must fit in the file.
  const tableEnd = 6 + 6 * count;
  if (tableEnd > bytes.length) throw new LanternError(`${name}: the table of ${count} chunks runs past the end of the ${bytes.length}-byte file`, HINT);
  const chunks: Chunk[] = [];
  for (let i = 0; i < count; i++) {
    const offset = view.getUint32(6 + 4 * i, true);
    const length = view.getUint16(6 + 4 * count + 2 * i, true);
    // Sound chunks are never read, so only graphics pages must lie inside the file.
    if (i < soundStart && offset !== 0 && (offset < tableEnd || offset + length > bytes.length)) {
      throw new LanternError(`${name}: chunk ${i} (${length} bytes at offset ${offset}) lies outside the file's ${bytes.length} bytes of data`, HINT);
    }
    chunks.push({ offset, length });
  }
  return { name, bytes, chunks, spriteStart, soundStart };
}

function chunkBytes(vswap: VswapFile, index: number): Uint8Array {
  const chunk = vswap.chunks[index]!;
  return chunk.offset === 0 ? new Uint8Array(0) : vswap.bytes.subarray(chunk.offset, chunk.offset + chunk.length);
}

/** Wall page `page` (0-based) in RGBA, opaque. A sparse (absent) page is black, as the game would show its zeroed memory. */
export function decodeWall(vswap: VswapFile, page: number, palette: Uint8Array): WolfImage {
  if (!Number.isInteger(page) || page < 0 || page >= vswap.spriteStart) {
    throw new LanternError(`${vswap.name} has ${vswap.spriteStart} wall pages; there is no wall page ${page}`);
  }
  const data = chunkBytes(vswap, page);
  if (data.length !== 0 && data.length < WALL_PAGE_BYTES) {
    throw new LanternError(`${vswap.name}: wall page ${page} holds ${data.length} bytes, not ${WALL_PAGE_BYTES}`, HINT);
  }
  const rgba = new Uint8Array(WALL_PAGE_BYTES * 4);
  for (let y = 0; y < PAGE_SIZE; y++) {
    for (let x = 0; x < PAGE_SIZE; x++) {
      const c = data.length === 0 ? 0 : data[x * PAGE_SIZE + y]!;
      const o = (y * PAGE_SIZE + x) * 4;
      rgba[o] = palette[3 * c]!;
      rgba[o + 1] = palette[3 * c + 1]!;
      rgba[o + 2] = palette[3 * c + 2]!;
      rgba[o + 3] = 255;
    }
  }
  return { width: PAGE_SIZE, height: PAGE_SIZE, rgba };
}

/** Sprite `index` (0 = the first sprite chunk) in RGBA, alpha 0 where no post draws. */
export function decodeSprite(vswap: VswapFile, index: number, palette: Uint8Array): WolfImage {
  const count = vswap.soundStart - vswap.spriteStart;
  if (!Number.isInteger(index) || index < 0 || index >= count) throw new LanternError(`${vswap.name} has ${count} sprites; there is no sprite ${index}`);
  const data = chunkBytes(vswap, vswap.spriteStart + index);
  const rgba = new Uint8Array(WALL_PAGE_BYTES * 4);
  const image = { width: PAGE_SIZE, height: PAGE_SIZE, rgba };
  if (data.length === 0) return image;
  const at = `${vswap.name}: sprite ${index} (chunk ${vswap.spriteStart + index})`;
  const word = (offset: number): number => {
    if (offset + 2 > data.length) throw new LanternError(`${at}: reads past the end of its ${data.length} bytes (at byte ${offset})`, HINT);
    return data[offset]! | (data[offset + 1]! << 8);
  };
  const left = word(0);
  const right = word(2);
  if (left > right || right >= PAGE_SIZE) throw new LanternError(`${at}: columns ${left} to ${right} are not within 0 to ${PAGE_SIZE - 1}`, HINT);
  for (let x = left; x <= right; x++) {
    let post = word(4 + 2 * (x - left));
    // Each post is six bytes and covers at least one of the 64 rows, so a column of more than 64 posts
    // is damaged (this also bounds the loop whatever the data says).
    for (let n = 0; ; n++) {
      const end2 = word(post);
      if (end2 === 0) break;
      if (n >= PAGE_SIZE) throw new LanternError(`${at}: column ${x} does not end its list of posts`, HINT);
      const source = word(post + 2);
      const start2 = word(post + 4);
      if (end2 % 2 !== 0 || start2 % 2 !== 0 || start2 >= end2 || end2 > 2 * PAGE_SIZE) {
        throw new LanternError(`${at}: column ${x} has a post from row ${start2 / 2} to row ${end2 / 2}, not within 0 to ${PAGE_SIZE}`, HINT);
      }
      for (let y = start2 / 2; y < end2 / 2; y++) {
        // The game adds in 16 bits: the source offset is stored less the start row.
        const s = (source + y) & 0xffff;
        if (s >= data.length) throw new LanternError(`${at}: column ${x}, row ${y} reads texel ${s}, past its ${data.length} bytes`, HINT);
        const c = data[s]!;
        const o = (y * PAGE_SIZE + x) * 4;
        rgba[o] = palette[3 * c]!;
        rgba[o + 1] = palette[3 * c + 1]!;
        rgba[o + 2] = palette[3 * c + 2]!;
        rgba[o + 3] = 255;
      }
      post += 6;
    }
  }
  return image;
}
