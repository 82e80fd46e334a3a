/**
 * A shard: the per-pixel sums of samples [start, end) of one progressive estimate (a vec4f per pixel:
 * Σ radiance rgb, Σ luminance², as the path tracer accumulates them; not means), with what made them
 * (the render's command line) so that `lantern merge` can check that shards belong together and show
 * the merged estimate as `render` would. Shards merge exactly: each holds one dispatch's float32 sums
 * (the chunk's samples in one dispatch), and mergeShards adds them in sample order with float32
 * rounding after each addition, which is what the GPU's `accumulation += sum` does in a one-process
 * render whose dispatches are those chunks (`render --chunk C`): the same additions in the same
 * order, so the same bits.
 *
 * File: 'LANTERN-SHARD\n' (14 bytes), a u32 little-endian header length, the header (UTF-8 JSON),
 * zero padding to a multiple of 4, then width × height × 4 float32 little-endian.
 */
import { LanternError } from '../errors.ts';

const MAGIC = 'LANTERN-SHARD\n';
/** Float32Arrays are in the machine's byte order; the file's is little-endian. */
const LITTLE_ENDIAN = new Uint8Array(new Float32Array([1]).buffer)[3] === 0x3f;
export const SHARD_VERSION = 1;

export interface ShardHeader {
  readonly version: number;
  /** `render`'s arguments after `render` (scene first), without the options that say where outputs go or which samples. */
  readonly render: readonly string[];
  readonly width: number;
  readonly height: number;
  /** Samples [start, end) of the sequence. */
  readonly start: number;
  readonly end: number;
}

export interface Shard {
  readonly header: ShardHeader;
  /** A vec4f per pixel, row-major, top row first. */
  readonly sums: Float32Array;
}

export function encodeShard(shard: Shard): Uint8Array {
  const { header, sums } = shard;
  if (sums.length !== header.width * header.height * 4) throw new Error(`encodeShard: ${sums.length} floats for ${header.width}×${header.height}`);
  const json = new TextEncoder().encode(JSON.stringify(header));
  const headStart = MAGIC.length + 4;
  const dataStart = Math.ceil((headStart + json.length) / 4) * 4;
  const out = new Uint8Array(dataStart + sums.byteLength);
  out.set(new TextEncoder().encode(MAGIC), 0);
  new DataView(out.buffer).setUint32(MAGIC.length, json.length, true);
  out.set(json, headStart);
  if (LITTLE_ENDIAN) {
    out.set(new Uint8Array(sums.buffer, sums.byteOffset, sums.byteLength), dataStart);
  } else {
    const view = new DataView(out.buffer, dataStart);
    for (let i = 0; i < sums.length; i++) view.setFloat32(i * 4, sums[i]!, true);
  }
  return out;
}

/** Bytes of a shard's start that hold its header's length: a reader of headers reads this much first. */
export const SHARD_PREFIX_BYTES = 18;

/**
 * A shard's header from the file's first bytes (`prefix`, at least SHARD_PREFIX_BYTES and then as
 * many as the length there says) and its whole size, checked against what the header says; `name`
 * (the file) is named in errors. Throws `ShardPrefixShort` when the prefix is too short for the header.
 */
export function decodeShardHeader(prefix: Uint8Array, fileBytes: number, name: string): { header: ShardHeader; dataStart: number } {
  const fail = (why: string): never => {
    throw new LanternError(`${name} is not a Lantern shard: ${why}`, 'Give the .shard files that `render --shard` or a farm worker wrote');
  };
  if (fileBytes < SHARD_PREFIX_BYTES || prefix.length < SHARD_PREFIX_BYTES || new TextDecoder().decode(prefix.subarray(0, MAGIC.length)) !== MAGIC) fail('no LANTERN-SHARD header');
  const dv = new DataView(prefix.buffer, prefix.byteOffset, prefix.byteLength);
  const length = dv.getUint32(MAGIC.length, true);
  const headStart = MAGIC.length + 4;
  if (headStart + length > fileBytes) fail('its header is cut short');
  if (headStart + length > prefix.length) throw new ShardPrefixShort(headStart + length);
  let header: ShardHeader;
  try {
    header = JSON.parse(new TextDecoder().decode(prefix.subarray(headStart, headStart + length))) as ShardHeader;
  } catch {
    return fail('its header is not JSON');
  }
  if (header.version !== SHARD_VERSION) fail(`version ${String(header.version)}, this Lantern reads ${SHARD_VERSION}`);
  const { width, height, start, end } = header;
  if (![width, height, start, end].every((v) => Number.isInteger(v) && v >= 0) || width < 1 || height < 1 || end <= start) fail('its size or sample range is not valid');
  if (!Array.isArray(header.render) || !header.render.every((a) => typeof a === 'string') || header.render.length < 1) fail('it does not say what was rendered');
  const dataStart = Math.ceil((headStart + length) / 4) * 4;
  const floats = width * height * 4;
  if (fileBytes !== dataStart + floats * 4) fail(`${fileBytes - dataStart} bytes of sums where ${width}×${height} needs ${floats * 4}`);
  return { header, dataStart };
}

/** decodeShardHeader was given fewer bytes than the header needs: read `bytes` and ask again. */
export class ShardPrefixShort extends Error {
  readonly bytes: number;
  constructor(bytes: number) {
    super(`a shard header needs its first ${bytes} bytes`);
    this.bytes = bytes;
  }
}

/**
 * Reads a shard; `name` (the file) is named in errors. The sums are a view of `bytes` where the
 * machine is little-endian and they sit at a multiple of 4 (no copy of a 4K shard's 127 MiB).
 */
export function decodeShard(bytes: Uint8Array, name: string): Shard {
  const { header, dataStart } = decodeShardHeader(bytes, bytes.length, name);
  const floats = header.width * header.height * 4;
  if (LITTLE_ENDIAN && (bytes.byteOffset + dataStart) % 4 === 0) return { header, sums: new Float32Array(bytes.buffer, bytes.byteOffset + dataStart, floats) };
  const sums = new Float32Array(floats);
  const data = new DataView(bytes.buffer, bytes.byteOffset + dataStart, floats * 4);
  for (let i = 0; i < floats; i++) sums[i] = data.getFloat32(i * 4, true);
  return { header, sums };
}

export interface Merged {
  readonly render: readonly string[];
  readonly width: number;
  readonly height: number;
  readonly start: number;
  readonly end: number;
  /** Σ over the shards in sample order, float32 after each addition. */
  readonly sums: Float32Array;
}

/** A shard to merge: its header, and its sums when asked for (so that only one shard's sums need be in memory at a time). */
export interface ShardSource {
  readonly name: string;
  readonly header: ShardHeader;
  readonly sums: () => Float32Array;
}

/**
 * Adds shards of one render in sample order (whatever order they are given in), float32 after each
 * addition, as a one-process render's accumulation adds its dispatches. They must be of the same
 * render and size and cover one contiguous range of samples without overlap (checked from the
 * headers before any sums are read).
 */
export function mergeShards(shards: readonly (ShardSource | { readonly shard: Shard; readonly name: string })[]): Merged {
  if (shards.length === 0) throw new LanternError('merge needs at least one shard');
  const sources: ShardSource[] = shards.map((s) => ('shard' in s ? { name: s.name, header: s.shard.header, sums: () => s.shard.sums } : s));
  const sorted = sources.sort((a, b) => a.header.start - b.header.start);
  const first = sorted[0]!;
  const key = JSON.stringify(first.header.render);
  const { width, height } = first.header;
  for (const { header, name } of sorted) {
    if (JSON.stringify(header.render) !== key) throw new LanternError(`${name} is of another render than ${first.name} (render ${header.render.join(' ')} against ${first.header.render.join(' ')})`);
    if (header.width !== width || header.height !== height) throw new LanternError(`${name} is ${header.width}×${header.height}, ${first.name} ${width}×${height}`);
  }
  for (let i = 1; i < sorted.length; i++) {
    const prev = sorted[i - 1]!;
    const cur = sorted[i]!;
    if (cur.header.start < prev.header.end) throw new LanternError(`${cur.name} (samples ${cur.header.start}-${cur.header.end - 1}) overlaps ${prev.name} (samples ${prev.header.start}-${prev.header.end - 1})`);
    if (cur.header.start > prev.header.end) throw new LanternError(`samples ${prev.header.end}-${cur.header.start - 1} are missing between ${prev.name} and ${cur.name}`, 'Merge every shard of the range');
  }
  const sums = new Float32Array(width * height * 4);
  for (const source of sorted) {
    const s = source.sums();
    if (s.length !== sums.length) throw new LanternError(`${source.name} changed while it was merged`);
    // Float32Array stores round each addition to float32, as the GPU's does.
    for (let i = 0; i < sums.length; i++) sums[i] = sums[i]! + s[i]!;
  }
  return { render: first.header.render, width, height, start: first.header.start, end: sorted[sorted.length - 1]!.header.end, sums };
}
