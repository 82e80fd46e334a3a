/**
 * Reads single-part scanline OpenEXR files: Lantern's own and the common output of other tools.
 * Compressions NONE, RLE, ZIPS and ZIP; channel types HALF, FLOAT and UINT (all returned as float).
 * Anything else (tiles, deep data, multi-part, PIZ/PXR24/B44/DWA, subsampled channels) is refused with
 * a LanternError that says what it found.
 */
import { checkLimit } from '../budgets.ts';
import { LanternError } from '../errors.ts';
import { rleDecompress, zipDecompress } from './exr-compression.ts';
import {
  COMPRESSION_NONE, COMPRESSION_RLE, COMPRESSION_ZIP, COMPRESSION_ZIPS, COMPRESSIONS, compressionName,
  EXR_MAGIC, EXR_VERSION, FLAG_DEEP, FLAG_LONG_NAMES, FLAG_MULTIPART, FLAG_TILED,
  PIXEL_FLOAT, PIXEL_HALF, PIXEL_SIZE, PIXEL_UINT,
} from './exr-format.ts';
import { halfTable } from './half.ts';

export interface ExrImage {
  readonly width: number;
  readonly height: number;
  /** One float per pixel per channel, row-major, top row (lowest y of the data window) first. */
  readonly channels: Readonly<Record<string, Float32Array>>;
}

interface Channel {
  name: string;
  type: number;
}

interface Header {
  channels: Channel[];
  compression: number;
  xMin: number;
  yMin: number;
  width: number;
  height: number;
}

/**
 * How much a compression can expand data: deflate ~1032×, RLE 128 bytes from 2; stored data not at
 * all. A header promising more pixels than the file could hold is corrupt.
 */
function maxExpansion(compression: number): number {
  if (compression === COMPRESSION_NONE) return 1;
  if (compression === COMPRESSION_RLE) return 64;
  return 1100;
}

/** Every channel as a plane of its own. */
export function decodeExr(bytes: Uint8Array, name = 'image.exr'): ExrImage {
  const out: Record<string, Float32Array> = {};
  const { width, height } = decodeInto(bytes, name, (header) =>
    header.channels.map((c) => {
      const plane = new Float32Array(header.width * header.height);
      out[c.name] = plane;
      return { target: plane, offset: 0, stride: 1 };
    }),
  );
  return { width, height, channels: out };
}

/**
 * Interleaved RGB (3 floats per pixel) from the R, G, B channels (or a grey Y repeated), decoded
 * straight into place; other channels (A, Z, ...) are skipped. What `lantern diff` and environment
 * maps need, in a third of the memory of the planes and their interleaved copy at once (an
 * 8192×4096 RGBA image: 384 MB rather than 896 MB).
 */
export function decodeExrRgb(bytes: Uint8Array, name = 'image.exr'): { width: number; height: number; rgb: Float32Array } {
  let rgb = new Float32Array(0);
  let grey = false;
  const { width, height } = decodeInto(bytes, name, (header) => {
    const names = header.channels.map((c) => c.name);
    const has = (n: string) => names.includes(n);
    grey = !(has('R') && has('G') && has('B'));
    if (grey && !has('Y')) throw noRgb(name, names);
    rgb = new Float32Array(header.width * header.height * 3);
    const offset: Record<string, number> = grey ? { Y: 0 } : { R: 0, G: 1, B: 2 };
    return names.map((n) => (offset[n] === undefined ? undefined : { target: rgb, offset: offset[n], stride: 3 }));
  });
  if (grey) for (let i = 0; i < rgb.length; i += 3) rgb[i + 1] = rgb[i + 2] = rgb[i]!;
  return { width, height, rgb };
}

/** Where one channel's samples go: pixel p's to target[offset + p · stride]; undefined: skipped. */
interface ChannelSink {
  readonly target: Float32Array;
  readonly offset: number;
  readonly stride: number;
}

/**
 * Reads the header, checks it against the file and the limits, asks `place` where each channel goes
 * (once nothing is left to refuse from the header alone), then decodes every chunk into place.
 */
function decodeInto(bytes: Uint8Array, name: string, place: (header: Header) => readonly (ChannelSink | undefined)[]): { width: number; height: number } {
  const r = new Reader(bytes, name);
  if (bytes.length < 8 || r.int32() !== EXR_MAGIC) {
    throw new LanternError(`${name}: not an OpenEXR file (bad magic number)`);
  }
  const versionField = r.int32();
  const version = versionField & 0xff;
  const flags = versionField & ~0xff;
  if (version !== EXR_VERSION) throw new LanternError(`${name}: unsupported OpenEXR version ${version}`);
  if (flags & FLAG_TILED) throw unsupported(name, 'tiled images');
  if (flags & FLAG_DEEP) throw unsupported(name, 'deep data');
  if (flags & FLAG_MULTIPART) throw unsupported(name, 'multi-part files');
  if (flags & ~FLAG_LONG_NAMES) throw new LanternError(`${name}: unknown OpenEXR version flags 0x${flags.toString(16)}`);

  const header = readHeader(r);
  const { width, height, channels } = header;
  const pixelBytes = channels.reduce((s, c) => s + PIXEL_SIZE[c.type]!, 0);
  // The header alone decides: nothing is allocated or inflated for an image over the pixel limit
  // (a 410 KB file claiming a huge data window once made `lantern diff` take 5.2 GB and 183 s).
  if (width * height * pixelBytes > Math.max(bytes.length, 1 << 16) * maxExpansion(header.compression)) {
    throw new LanternError(`${name}: the data window (${width}×${height}) is far larger than the file could hold`, 'the file is corrupt');
  }
  checkLimit('imagePixels', width * height, `${name}: ${width}×${height} pixels`);
  const linesPerChunk = COMPRESSIONS[header.compression]!.linesPerChunk;
  const chunkCount = Math.ceil(height / linesPerChunk);
  const offsets: number[] = [];
  for (let i = 0; i < chunkCount; i++) offsets.push(r.uint64(`line offset ${i}`));

  const sinks = place(header);
  const seen = new Uint8Array(chunkCount);
  offsets.forEach((offset, i) => {
    r.seek(offset, `chunk ${i}`);
    const y = r.int32() - header.yMin;
    const size = r.int32();
    const chunk = y / linesPerChunk;
    if (!Number.isInteger(chunk) || chunk < 0 || chunk >= chunkCount || seen[chunk]) {
      throw new LanternError(`${name}: chunk ${i} (at byte ${offset}) has an invalid scanline y = ${y + header.yMin}`, 'the file is corrupt');
    }
    seen[chunk] = 1;
    const lines = Math.min(linesPerChunk, height - y);
    const raw = decompress(r.bytes(size, `chunk ${i}`), lines * width * pixelBytes, header.compression, `${name}: chunk ${i} (scanline ${y + header.yMin})`);
    unpack(raw, sinks, channels, width, y, lines);
  });
  return { width, height };
}

/** Interleaved RGB (3 floats per pixel) from R, G, B channels, or a grey Y channel repeated. */
export function exrToRgb(image: ExrImage, name = 'image.exr'): Float32Array {
  const { R, G, B, Y } = image.channels;
  const [r, g, b] = R && G && B ? [R, G, B] : Y ? [Y, Y, Y] : [];
  if (!r || !g || !b) throw noRgb(name, Object.keys(image.channels));
  const rgb = new Float32Array(image.width * image.height * 3);
  for (let i = 0; i < r.length; i++) {
    rgb[3 * i] = r[i]!;
    rgb[3 * i + 1] = g[i]!;
    rgb[3 * i + 2] = b[i]!;
  }
  return rgb;
}

const noRgb = (name: string, channels: readonly string[]): LanternError => new LanternError(`${name}: no R, G, B (or Y) channels; it has ${channels.join(', ') || 'none'}`);

const unsupported = (name: string, what: string): LanternError =>
  new LanternError(`${name}: OpenEXR ${what} are not supported`, 'Lantern reads single-part scanline files');

function readHeader(r: Reader): Header {
  let channels: Channel[] | undefined, compression: number | undefined, window: number[] | undefined;
  for (;;) {
    const attribute = r.string('attribute name');
    if (attribute === '') break;
    const type = r.string(`type of attribute '${attribute}'`);
    const size = r.int32();
    const value = new Reader(r.bytes(size, `attribute '${attribute}'`), `${r.name}: attribute '${attribute}'`);
    if (attribute === 'channels' && type === 'chlist') channels = readChannels(value);
    else if (attribute === 'compression' && type === 'compression') compression = value.uint8();
    else if (attribute === 'dataWindow' && type === 'box2i') window = [value.int32(), value.int32(), value.int32(), value.int32()];
    // Other attributes (displayWindow, lineOrder, ...) do not change how the pixels are read:
    // chunks carry their own y, so any line order decodes the same way.
  }
  const name = r.name;
  if (!channels || channels.length === 0) throw new LanternError(`${name}: the OpenEXR header has no channels`);
  if (compression === undefined || !window) throw new LanternError(`${name}: the OpenEXR header lacks a compression or dataWindow attribute`);
  if (![COMPRESSION_NONE, COMPRESSION_RLE, COMPRESSION_ZIPS, COMPRESSION_ZIP].includes(compression)) {
    throw new LanternError(
      `${name}: OpenEXR compression ${compressionName(compression)} is not supported`,
      'Lantern reads NO_COMPRESSION, RLE, ZIPS and ZIP; re-save the image with one of those',
    );
  }
  const [xMin, yMin, xMax, yMax] = window as [number, number, number, number];
  const width = xMax - xMin + 1, height = yMax - yMin + 1;
  if (!(width > 0 && height > 0)) throw new LanternError(`${name}: the OpenEXR data window is empty (${xMin},${yMin})–(${xMax},${yMax})`);
  return { channels, compression, xMin, yMin, width, height };
}

function readChannels(r: Reader): Channel[] {
  const channels: Channel[] = [];
  for (;;) {
    const name = r.string('channel name');
    if (name === '') return channels;
    const type = r.int32();
    r.bytes(4, 'channel flags'); // pLinear and three reserved bytes
    const xSampling = r.int32(), ySampling = r.int32();
    if (type !== PIXEL_UINT && type !== PIXEL_HALF && type !== PIXEL_FLOAT) {
      throw new LanternError(`${r.name}: channel '${name}' has unknown pixel type ${type}`);
    }
    if (xSampling !== 1 || ySampling !== 1) {
      throw new LanternError(`${r.name}: channel '${name}' is subsampled (${xSampling}×${ySampling}), which is not supported`);
    }
    channels.push({ name, type });
  }
}

function decompress(data: Uint8Array, expected: number, compression: number, where: string): Uint8Array {
  // A chunk no smaller than its raw size was stored raw: writers fall back when compression does not help.
  if (compression === COMPRESSION_NONE || data.length >= expected) {
    if (data.length !== expected) throw new LanternError(`${where} holds ${data.length} bytes, expected ${expected}`, 'the file is corrupt');
    return data;
  }
  let raw: Uint8Array | undefined;
  try {
    raw = compression === COMPRESSION_RLE ? rleDecompress(data, expected) : zipDecompress(data, expected);
  } catch (e) {
    throw new LanternError(`${where} could not be decompressed (${(e as Error).message})`, 'the file is corrupt', { cause: e });
  }
  if (!raw) throw new LanternError(`${where} does not decompress to the expected ${expected} bytes`, 'the file is corrupt');
  return raw;
}

/** Scatters a chunk's scanlines (each: every channel's samples in turn) to the channels' sinks. */
function unpack(raw: Uint8Array, sinks: readonly (ChannelSink | undefined)[], channels: Channel[], width: number, y0: number, lines: number): void {
  const view = new DataView(raw.buffer, raw.byteOffset, raw.byteLength);
  const half = halfTable();
  let o = 0;
  for (let line = 0; line < lines; line++) {
    channels.forEach((c, k) => {
      const sink = sinks[k];
      const size = PIXEL_SIZE[c.type]!;
      if (!sink) {
        o += size * width;
        return;
      }
      const { target, stride } = sink;
      let at = (y0 + line) * width * stride + sink.offset;
      if (c.type === PIXEL_FLOAT) {
        for (let x = 0; x < width; x++, o += 4, at += stride) target[at] = view.getFloat32(o, true);
      } else if (c.type === PIXEL_HALF) {
        for (let x = 0; x < width; x++, o += 2, at += stride) target[at] = half[view.getUint16(o, true)]!;
      } else {
        for (let x = 0; x < width; x++, o += 4, at += stride) target[at] = view.getUint32(o, true);
      }
    });
  }
}

/** Bounds-checked little-endian reads; every overrun names what was being read. */
class Reader {
  private pos = 0;
  private readonly view: DataView;

  constructor(
    private readonly data: Uint8Array,
    readonly name: string,
  ) {
    this.view = new DataView(data.buffer, data.byteOffset, data.byteLength);
  }

  private need(n: number, what: string): number {
    const p = this.pos;
    if (n < 0 || p + n > this.data.length) {
      throw new LanternError(`${this.name}: truncated at byte ${p} (reading ${what})`, 'the file is incomplete or corrupt');
    }
    this.pos = p + n;
    return p;
  }

  seek(offset: number, what: string): void {
    if (!(offset >= 0 && offset + 8 <= this.data.length)) {
      throw new LanternError(`${this.name}: ${what} starts at byte ${offset}, past the end of the file (${this.data.length} bytes)`, 'the file is truncated');
    }
    this.pos = offset;
  }

  uint8(): number {
    return this.data[this.need(1, 'a byte')]!;
  }

  int32(): number {
    return this.view.getInt32(this.need(4, 'an integer'), true);
  }

  uint64(what: string): number {
    const p = this.need(8, what);
    return this.view.getUint32(p, true) + this.view.getUint32(p + 4, true) * 2 ** 32;
  }

  bytes(n: number, what: string): Uint8Array {
    const p = this.need(n, what);
    return this.data.subarray(p, p + n);
  }

  /** A null-terminated name; OpenEXR caps names at 255 bytes (long-name files), so stop looking there. */
  string(what: string): string {
    const start = this.pos;
    const end = this.data.subarray(start, start + 256).indexOf(0);
    if (end < 0) {
      throw new LanternError(`${this.name}: no terminated ${what} at byte ${start}`, 'the file is truncated or not an OpenEXR file');
    }
    this.pos = start + end + 1;
    let s = '';
    for (let i = start; i < start + end; i++) s += String.fromCharCode(this.data[i]!);
    return s;
  }
}
