/**
 * Gzip inflated in slices with a running count, so a bomb is refused when its output passes the
 * decompressedBytes limit instead of after it has taken all memory: a 392 KB .ply.gz inflates to
 * 2.35 GB, a 1.5 MB one past 6 GB. The size in the gzip trailer is not trusted (it is mod 2^32 and
 * written by whoever made the file). A format whose header says how big its body will be (PLY's
 * counts) looks at the header first (`head`), so a 392 KB file declaring 10.3 million faces is
 * refused once its first slice is inflated, not after all 134 MB of it.
 */
import { Gunzip } from 'fflate';
import { LanternError } from '../errors.ts';
import { limits, overLimit } from '../budgets.ts';

/** Compressed bytes pushed at a time: deflate expands at most ~1032×, so one slice yields at most ~17 MB. */
const SLICE = 16 * 1024;

export function isGzip(bytes: Uint8Array): boolean {
  return bytes[0] === 0x1f && bytes[1] === 0x8b;
}

/** A look at the start of the inflated data before the rest is inflated: `check` throws to refuse the file. */
export interface GzipHead {
  /** How many inflated bytes `check` is given (fewer when the data is shorter). */
  readonly bytes: number;
  readonly check: (head: Uint8Array) => void;
}

/** The inflated bytes of a gzip file (every member), or a one-line LanternError: corrupt, truncated, or over the limit. */
export function gunzipCapped(bytes: Uint8Array, name: string, head?: GzipHead): Uint8Array {
  // A 10-byte header and an 8-byte trailer at the least; fflate takes a bare header for an empty stream.
  if (bytes.length < 18) throw new LanternError(`${name}: could not decompress the gzip data (only ${bytes.length} bytes)`, 'the file may be truncated');
  const cap = limits().decompressedBytes;
  // The trailer's size (mod 2^32, and only the last member's) is a hint, never trusted: when it is
  // plausible the output is written straight into one buffer of that size, which saves holding the
  // chunks and their copy at once; if the stream disagrees, the chunks are kept after all.
  const n = bytes.length;
  const hint = (bytes[n - 4]! | (bytes[n - 3]! << 8) | (bytes[n - 2]! << 16) | (bytes[n - 1]! << 24)) >>> 0;
  let direct = hint > 0 && hint <= cap && hint <= n * 1032 + 1024 ? new Uint8Array(hint) : undefined;
  const chunks: Uint8Array[] = [];
  let total = 0;
  let over = false;
  let finished = false;
  const inflater = new Gunzip((chunk, final) => {
    if (final) finished = true;
    if (over) return;
    if (total + chunk.length > cap) {
      over = true;
      total += chunk.length;
      return;
    }
    if (direct && total + chunk.length <= direct.length) direct.set(chunk, total);
    else {
      if (direct) chunks.push(direct.subarray(0, total));
      direct = undefined;
      chunks.push(chunk);
    }
    total += chunk.length;
  });
  // The head is looked at once enough is inflated (at most one slice's output past it), outside
  // fflate's callback, so that what `check` throws is its own error.
  let headPending = head !== undefined;
  const lookAtHead = () => {
    if (!headPending || !(total >= head!.bytes || finished || over)) return;
    headPending = false;
    head!.check(prefix(direct ? [direct.subarray(0, total)] : chunks, head!.bytes));
  };
  for (let at = 0; at < bytes.length && !over; at += SLICE) {
    const end = Math.min(at + SLICE, bytes.length);
    try {
      inflater.push(bytes.subarray(at, end), end === bytes.length);
    } catch (e) {
      throw new LanternError(`${name}: could not decompress the gzip data (${(e as Error).message})`, 'the file may be truncated', { cause: e });
    }
    lookAtHead();
  }
  if (over) throw overLimit('decompressedBytes', total, `${name}: inflated gzip data (at least)`);
  if (!finished) throw new LanternError(`${name}: the gzip data ends early`, 'the file may be truncated');
  if (direct && total === direct.length) return direct;
  if (direct) chunks.push(direct.subarray(0, total));
  const out = new Uint8Array(total);
  let at = 0;
  for (const c of chunks) {
    out.set(c, at);
    at += c.length;
  }
  return out;
}

/** The first `n` bytes of the chunks, joined. */
function prefix(chunks: readonly Uint8Array[], n: number): Uint8Array {
  const out = new Uint8Array(Math.min(n, chunks.reduce((sum, c) => sum + c.length, 0)));
  let at = 0;
  for (const c of chunks) {
    if (at >= out.length) break;
    out.set(c.subarray(0, out.length - at), at);
    at += Math.min(c.length, out.length - at);
  }
  return out;
}
