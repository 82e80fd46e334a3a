/**
 * Wolfenstein 3D's maps: MAPHEAD (the RLEW tag, then one 32-bit offset into GAMEMAPS per map) and
 * GAMEMAPS ("TED5v1.0", then per map a 38-byte header: three plane offsets u32, three compressed
 * plane lengths u16, width u16, height u16, a 16-byte NUL-padded name). Each plane is Carmack-
 * compressed, and what that yields is RLEW-compressed (ModdingWiki, "GameMaps Format", "Carmack
 * compression", "RLEW compression"). All little-endian. Every offset, length and count is checked
 * against the file and against the map's size before it is used, so a truncated or lying file is a
 * LanternError naming the file, the map and what is wrong, never a RangeError or a runaway loop.
 * Pure.
 */
import { LanternError } from '../../errors.ts';
import type { NamedBytes } from '../format.ts';
import type { WolfMap, WolfMapInfo } from './types.ts';

/** MAPHEAD as read: the RLEW tag and, per map slot, its header's offset in GAMEMAPS (undefined: no map). */
export interface MapHead {
  readonly name: string;
  readonly rlewTag: number;
  readonly offsets: readonly (number | undefined)[];
}

/** The game's table holds 100 maps (NUMMAPS in the released source); later slots are not read. */
export const MAX_MAPS = 100;
/** Bytes of one map header in GAMEMAPS. */
export const MAP_HEADER_SIZE = 38;
const NAME_BYTES = 16;
/** The Carmack stream's markers: a near pointer (back by a byte's worth of words), a far pointer (from the start). */
export const NEAR_TAG = 0xa7;
export const FAR_TAG = 0xa8;
/**
 * A plane's expanded size is stored as a 16-bit byte count (the first word of the RLEW data), so a
 * plane holds at most 32767 words: this bounds every allocation here whatever a header claims.
 */
const MAX_PLANE_WORDS = 0x7fff;
const HINT = 'the file is truncated or damaged; use the files of one installation of the game';

/** The 0-based map index as its id: `E1L1` for 0, `E2L3` for 12 (the game's 10 maps per episode). */
export function mapId(index: number): string {
  return `E${Math.floor(index / 10) + 1}L${(index % 10) + 1}`;
}

/** The index an id (`E1L3`, any case) or a 1-based map number (`3`) names, or undefined for neither. */
export function mapIndexOf(name: string): number | undefined {
  const trimmed = name.trim();
  const id = /^E(\d{1,2})L(\d{1,2})$/i.exec(trimmed);
  if (id) {
    const episode = Number(id[1]);
    const level = Number(id[2]);
    if (episode < 1 || level < 1 || level > 10) return undefined;
    return (episode - 1) * 10 + level - 1;
  }
  if (/^\d{1,3}$/.test(trimmed)) {
    const n = Number(trimmed);
    return n >= 1 && n <= MAX_MAPS ? n - 1 : undefined;
  }
  return undefined;
}

export function readMapHead(file: NamedBytes): MapHead {
  const { bytes, name } = file;
  if (bytes.length < 6) throw new LanternError(`${name}: not a MAPHEAD file (${bytes.length} bytes: too short for the RLEW tag and one map offset)`, HINT);
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const count = Math.min(MAX_MAPS, Math.floor((bytes.length - 2) / 4));
  const offsets: (number | undefined)[] = [];
  for (let i = 0; i < count; i++) {
    const offset = view.getUint32(2 + 4 * i, true);
    offsets.push(offset === 0 || offset === 0xffffffff ? undefined : offset);
  }
  return { name, rlewTag: view.getUint16(0, true), offsets };
}

/** The bytes GAMEMAPS starts with (TED5, the map editor, wrote it); only checked by sniffing. */
export const GAMEMAPS_SIGNATURE = 'TED5v1.0';

interface MapHeader extends WolfMapInfo {
  readonly planeOffsets: readonly [number, number, number];
  readonly planeLengths: readonly [number, number, number];
}

function where(gamemaps: NamedBytes, index: number): string {
  return `${gamemaps.name}: map ${index + 1} (${mapId(index)})`;
}

function readHeader(head: MapHead, gamemaps: NamedBytes, index: number): MapHeader | undefined {
  const offset = head.offsets[index];
  if (offset === undefined) return undefined;
  const { bytes } = gamemaps;
  const at = where(gamemaps, index);
  if (offset + MAP_HEADER_SIZE > bytes.length) {
    throw new LanternError(`${at}: its header at offset ${offset} (from ${head.name}) runs past the end of the ${bytes.length}-byte file`, HINT);
  }
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const planeOffsets = [0, 1, 2].map((p) => view.getUint32(offset + 4 * p, true)) as [number, number, number];
  const planeLengths = [0, 1, 2].map((p) => view.getUint16(offset + 12 + 2 * p, true)) as [number, number, number];
  const width = view.getUint16(offset + 18, true);
  const height = view.getUint16(offset + 20, true);
  let title = '';
  for (let i = 0; i < NAME_BYTES; i++) {
    const c = bytes[offset + 22 + i]!;
    if (c === 0) break;
    title += String.fromCharCode(c);
  }
  if (width === 0 || height === 0 || width * height > MAX_PLANE_WORDS) {
    throw new LanternError(`${at}: its header says ${width} × ${height} tiles (a plane holds 1 to ${MAX_PLANE_WORDS} tiles)`, HINT);
  }
  for (let p = 0; p < 3; p++) {
    if (planeOffsets[p]! + planeLengths[p]! > bytes.length) {
      throw new LanternError(`${at}: plane ${p} (${planeLengths[p]} bytes at offset ${planeOffsets[p]}) runs past the end of the ${bytes.length}-byte file`, HINT);
    }
  }
  return { index, id: mapId(index), title: title.trim(), width, height, planeOffsets, planeLengths };
}

/** The maps MAPHEAD lists, in order, with their headers checked against GAMEMAPS. */
export function listMaps(head: MapHead, gamemaps: NamedBytes): WolfMapInfo[] {
  const maps: WolfMapInfo[] = [];
  for (let i = 0; i < head.offsets.length; i++) {
    const header = readHeader(head, gamemaps, i);
    if (header) maps.push({ index: header.index, id: header.id, title: header.title, width: header.width, height: header.height });
  }
  return maps;
}

/** Decodes map `index` (0-based, MAPHEAD's slot): its three planes, Carmack- then RLEW-expanded. */
export function readMap(head: MapHead, gamemaps: NamedBytes, index: number): WolfMap {
  if (!Number.isInteger(index) || index < 0 || index >= head.offsets.length) {
    throw new LanternError(`${head.name} lists ${head.offsets.length} map slots; there is no map ${index + 1}`);
  }
  const header = readHeader(head, gamemaps, index);
  if (!header) throw new LanternError(`${head.name}: map slot ${index + 1} (${mapId(index)}) is empty`);
  const words = header.width * header.height;
  const planes = [0, 1, 2].map((p) => {
    const at = `${where(gamemaps, index)}, plane ${p}`;
    const start = header.planeOffsets[p]!;
    const compressed = gamemaps.bytes.subarray(start, start + header.planeLengths[p]!);
    const rlew = carmackExpand(compressed, at);
    return rlewExpand(rlew, head.rlewTag, words, at);
  }) as [Uint16Array, Uint16Array, Uint16Array];
  return { index: header.index, id: header.id, title: header.title, width: header.width, height: header.height, planes };
}

/**
 * Carmack expansion: the first word is the expanded size in bytes; then words, where a word whose
 * high byte is 0xA7 copies (low byte) words from (next byte) words back, 0xA8 copies (low byte)
 * words from (next word) words after the start of the output, and either with a count of 0 is an
 * escape: the word itself, tag byte high and the next byte low. Anything else is itself.
 */
export function carmackExpand(input: Uint8Array, at: string): Uint16Array {
  if (input.length < 2) throw new LanternError(`${at}: ${input.length} compressed bytes, too few for the expanded size`, HINT);
  const sizeBytes = input[0]! | (input[1]! << 8);
  if (sizeBytes % 2 !== 0 || sizeBytes === 0) throw new LanternError(`${at}: Carmack-expanded size of ${sizeBytes} bytes is not a positive whole number of words`, HINT);
  const out = new Uint16Array(sizeBytes / 2);
  let o = 0;
  let i = 2;
  const byte = (): number => {
    if (i >= input.length) throw new LanternError(`${at}: the Carmack data ends after ${o} of ${out.length} words`, HINT);
    return input[i++]!;
  };
  while (o < out.length) {
    const lo = byte();
    const hi = byte();
    if (hi !== NEAR_TAG && hi !== FAR_TAG) {
      out[o++] = lo | (hi << 8);
      continue;
    }
    const count = lo;
    if (count === 0) {
      out[o++] = (hi << 8) | byte();
      continue;
    }
    let from: number;
    if (hi === NEAR_TAG) {
      const back = byte();
      if (back === 0 || back > o) throw new LanternError(`${at}: a near pointer at word ${o} reaches ${back} words back, before the data's start`, HINT);
      from = o - back;
    } else {
      from = byte() | (byte() << 8);
      if (from >= o) throw new LanternError(`${at}: a far pointer at word ${o} refers to word ${from}, not yet written`, HINT);
    }
    if (o + count > out.length) throw new LanternError(`${at}: a copy of ${count} words at word ${o} runs past the expanded size of ${out.length} words`, HINT);
    // Word by word: a copy may overlap what it writes (a run repeats).
    for (let k = 0; k < count; k++) out[o++] = out[from + k]!;
  }
  return out;
}

/**
 * RLEW expansion of Carmack's output: its first word is the expanded size in bytes (which must be
 * the map's width · height words), then words, where `tag count value` is `count` copies of
 * `value` and any other word is itself.
 */
export function rlewExpand(input: Uint16Array, tag: number, words: number, at: string): Uint16Array {
  if (input.length < 1) throw new LanternError(`${at}: no RLEW data`, HINT);
  if (input[0] !== words * 2) throw new LanternError(`${at}: expands to ${input[0]} bytes, not the map's ${words} tiles (${words * 2} bytes)`, HINT);
  const out = new Uint16Array(words);
  let o = 0;
  let i = 1;
  while (o < words) {
    if (i >= input.length) throw new LanternError(`${at}: the RLEW data ends after ${o} of ${words} tiles`, HINT);
    const w = input[i++]!;
    if (w !== tag) {
      out[o++] = w;
      continue;
    }
    if (i + 1 >= input.length) throw new LanternError(`${at}: the RLEW data ends inside a run at tile ${o}`, HINT);
    const count = input[i++]!;
    const value = input[i++]!;
    if (o + count > words) throw new LanternError(`${at}: a run of ${count} tiles at tile ${o} runs past the map's ${words} tiles`, HINT);
    out.fill(value, o, o + count);
    o += count;
  }
  return out;
}
