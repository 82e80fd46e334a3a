/**
 * The binary glTF container (glTF 2.0 §4.4): a 12-byte header (magic, version, the file's length)
 * and chunks of (length, type, data), JSON first, then an optional BIN. Read through `read` and the
 * file's size, so that a caller can check a file from a few byte ranges before reading it whole (the
 * CLI does, before the GPU starts). A truncated download or a damaged chunk table is named in the
 * file's own terms: what the header or a chunk claims, and what the file has.
 */
import { LanternError } from '../../errors.ts';

export const GLB_MAGIC = 0x46546c67; // 'glTF'
const CHUNK_JSON = 0x4e4f534a;
const CHUNK_BIN = 0x004e4942;
const HEADER_BYTES = 12;
const CHUNK_HEADER_BYTES = 8;

export interface ByteRange {
  readonly offset: number;
  readonly length: number;
}

export interface GlbChunks {
  readonly json: ByteRange;
  readonly bin?: ByteRange;
}

/** `length` bytes of the file from `offset` (never past its end: callers stay inside `size`). */
export type ReadRange = (offset: number, length: number) => Uint8Array;

const view = (bytes: Uint8Array) => new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);

export function isGlb(size: number, read: ReadRange): boolean {
  return size >= 4 && view(read(0, 4)).getUint32(0, true) === GLB_MAGIC;
}

/**
 * A byte count for people: "1.5 MB", "3.77 MB", "880 bytes". Two counts said together are both
 * exact when they would round to the same text (a file cut by a few bytes).
 */
export function byteSizes(...counts: number[]): string[] {
  const rounded = counts.map((n) => {
    if (n < 1000) return `${n} bytes`;
    const [value, unit] = n < 1e6 ? [n / 1e3, 'kB'] : n < 1e9 ? [n / 1e6, 'MB'] : [n / 1e9, 'GB'];
    return `${Number(value.toPrecision(3))} ${unit}`;
  });
  return new Set(rounded).size === rounded.length ? rounded : counts.map((n) => `${n.toLocaleString('en-US')} bytes`);
}

const TRUNCATED_HINT = 'The file was cut short (an interrupted download or copy): get it again';

function chunkName(type: number): string {
  return type === CHUNK_JSON ? 'JSON' : type === CHUNK_BIN ? 'BIN' : `0x${type.toString(16).padStart(8, '0')}`;
}

/**
 * The JSON and BIN chunks of a GLB of `size` bytes, checked to lie inside the length its header
 * gives and that length inside the file (trailing bytes past it are ignored; chunks of other types
 * are skipped, as the specification asks). Throws a LanternError naming the first thing wrong.
 */
export function glbChunks(name: string, size: number, read: ReadRange): GlbChunks {
  if (size < HEADER_BYTES) throw new LanternError(`${name} is truncated: ${size} bytes, fewer than a GLB header's 12`, TRUNCATED_HINT);
  const declared = view(read(0, HEADER_BYTES)).getUint32(8, true);
  if (declared > size) {
    const [claimed, has] = byteSizes(declared, size);
    throw new LanternError(`${name} is truncated: its GLB header gives its length as ${claimed}, the file has ${has}`, TRUNCATED_HINT);
  }
  let json: ByteRange | undefined;
  let bin: ByteRange | undefined;
  // Fewer bytes than a chunk header at the end are padding, as before: nothing can be read from them.
  for (let at = HEADER_BYTES; at + CHUNK_HEADER_BYTES <= declared; ) {
    const header = view(read(at, CHUNK_HEADER_BYTES));
    const length = header.getUint32(0, true);
    const type = header.getUint32(4, true);
    const offset = at + CHUNK_HEADER_BYTES;
    if (offset + length > declared) {
      const [claimed, left] = byteSizes(length, declared - offset);
      throw new LanternError(`${name} is damaged: its ${chunkName(type)} chunk at byte ${at.toLocaleString('en-US')} claims ${claimed}, the file has ${left} after it`, 'Re-export the model, or get the file again');
    }
    if (type === CHUNK_JSON && !json) json = { offset, length };
    else if (type === CHUNK_BIN && !bin) bin = { offset, length };
    at = offset + length;
  }
  if (!json) throw new LanternError(`${name}: a GLB file without a JSON chunk`, 'the file is damaged or truncated; re-export it');
  return bin ? { json, bin } : { json };
}
