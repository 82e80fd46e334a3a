/**
 * Writes linear RGB as a single-part scanline OpenEXR file: channels B, G, R (the format wants them
 * sorted by name), 32-bit FLOAT by default or HALF, ZIP-compressed by default.
 */
import { LanternError } from '../errors.ts';
import { zlibSync } from 'fflate';
import { filterForCompression } from './exr-compression.ts';
import {
  COMPRESSION_NONE, COMPRESSION_ZIP, COMPRESSION_ZIPS, COMPRESSIONS, EXR_MAGIC, EXR_VERSION,
  PIXEL_FLOAT, PIXEL_HALF, PIXEL_SIZE,
} from './exr-format.ts';
import { floatToHalf } from './half.ts';

export interface ExrEncodeOptions {
  /** 'zip' (16 scanlines per chunk, the default), 'zips' (1 scanline) or 'none'. */
  compression?: 'zip' | 'zips' | 'none';
  /** 'float' (32-bit, the default: exact) or 'half' (16-bit: half the size, ~3 significant digits). */
  pixelType?: 'float' | 'half';
}

const COMPRESSION_CODES = { none: COMPRESSION_NONE, zips: COMPRESSION_ZIPS, zip: COMPRESSION_ZIP } as const;

/**
 * zlib (RFC 1950) compression of one chunk's filtered bytes (exr-compression.ts's
 * filterForCompression); the default is fflate's, at OpenEXR's own level 4. The CLI passes Node's.
 */
export type ChunkDeflate = (filtered: Uint8Array) => Uint8Array;

/** `rgb`: 3 floats per pixel, row-major, top row first. */
export function encodeExr(width: number, height: number, rgb: Float32Array, options: ExrEncodeOptions = {}, deflate: ChunkDeflate = zipDeflate): Uint8Array {
  const plan = planExr(width, height, rgb, options);
  return assembleExr(plan, plan.raws.map((raw) => (plan.compressed ? deflate(filterForCompression(raw)) : raw)));
}

/**
 * encodeExr with every chunk's compression handed over at once, so that `deflateAll` may run them in
 * parallel (the CLI: Node's zlib on its thread pool). The same file as encodeExr with a ChunkDeflate
 * that gives the same streams.
 */
export async function encodeExrAsync(width: number, height: number, rgb: Float32Array, options: ExrEncodeOptions, deflateAll: (filtered: Uint8Array[]) => Promise<Uint8Array[]>): Promise<Uint8Array> {
  const plan = planExr(width, height, rgb, options);
  return assembleExr(plan, plan.compressed ? await deflateAll(plan.raws.map(filterForCompression)) : plan.raws);
}

/** zlib level 4: what OpenEXR itself defaults to; most of level 9's ratio at a fraction of the time. */
const zipDeflate: ChunkDeflate = (filtered) => zlibSync(filtered, { level: 4 });

interface ExrPlan {
  readonly header: Uint8Array;
  /** Each chunk's raw scanlines, in file order. */
  readonly raws: Uint8Array[];
  readonly linesPerChunk: number;
  readonly compressed: boolean;
}

function planExr(width: number, height: number, rgb: Float32Array, options: ExrEncodeOptions): ExrPlan {
  if (!(Number.isInteger(width) && Number.isInteger(height) && width > 0 && height > 0)) {
    throw new LanternError(`cannot write an EXR of ${width}×${height} pixels`);
  }
  if (rgb.length !== width * height * 3) {
    throw new LanternError(`cannot write an EXR: ${rgb.length} floats given for ${width}×${height} RGB pixels (${width * height * 3} expected)`);
  }
  const compression = COMPRESSION_CODES[options.compression ?? 'zip'];
  const pixelType = options.pixelType === 'half' ? PIXEL_HALF : PIXEL_FLOAT;
  const linesPerChunk = COMPRESSIONS[compression]!.linesPerChunk;
  const raws: Uint8Array[] = [];
  for (let y = 0; y < height; y += linesPerChunk) raws.push(packLines(rgb, width, y, Math.min(linesPerChunk, height - y), pixelType));
  return { header: writeHeader(width, height, compression, pixelType), raws, linesPerChunk, compressed: compression !== COMPRESSION_NONE };
}

/** The file: header, offset table, chunks (each its compressed bytes where they are smaller than its raw ones). */
function assembleExr(plan: ExrPlan, packed: readonly Uint8Array[]): Uint8Array {
  const chunks = plan.raws.map((raw, c) => {
    // OpenEXR readers take a chunk whose size equals the raw size as stored uncompressed, so
    // incompressible chunks (noise) are written raw rather than grown.
    const data = packed[c]!.length < raw.length ? packed[c]! : raw;
    const chunk = new Uint8Array(8 + data.length);
    const view = new DataView(chunk.buffer);
    view.setInt32(0, c * plan.linesPerChunk, true);
    view.setInt32(4, data.length, true);
    chunk.set(data, 8);
    return chunk;
  });
  const tableOffset = plan.header.length;
  let offset = tableOffset + 8 * chunks.length;
  const size = chunks.reduce((s, c) => s + c.length, offset);
  const file = new Uint8Array(size);
  const view = new DataView(file.buffer);
  file.set(plan.header, 0);
  chunks.forEach((chunk, i) => {
    view.setBigUint64(tableOffset + 8 * i, BigInt(offset), true);
    file.set(chunk, offset);
    offset += chunk.length;
  });
  return file;
}

/** Scanlines y0 .. y0+lines-1 in file order: per line, all of B, then G, then R. */
function packLines(rgb: Float32Array, width: number, y0: number, lines: number, pixelType: number): Uint8Array {
  const sampleSize = PIXEL_SIZE[pixelType]!;
  const raw = new Uint8Array(lines * width * 3 * sampleSize);
  const view = new DataView(raw.buffer);
  let o = 0;
  for (let line = 0; line < lines; line++) {
    const row = (y0 + line) * width * 3;
    for (const channel of [2, 1, 0]) {
      for (let x = 0; x < width; x++) {
        const value = rgb[row + 3 * x + channel]!;
        if (pixelType === PIXEL_HALF) view.setUint16(o, floatToHalf(value), true);
        else view.setFloat32(o, value, true);
        o += sampleSize;
      }
    }
  }
  return raw;
}

/** The header: magic, version, the required attributes, and the terminating empty name. */
function writeHeader(width: number, height: number, compression: number, pixelType: number): Uint8Array {
  const w = new ByteWriter();
  w.int32(EXR_MAGIC);
  w.int32(EXR_VERSION); // no flags: single-part, scanline, short names
  const attribute = (name: string, type: string, value: (w: ByteWriter) => void) => {
    const body = new ByteWriter();
    value(body);
    w.string(name);
    w.string(type);
    w.int32(body.length);
    w.bytes(body.finish());
  };
  attribute('channels', 'chlist', (b) => {
    for (const name of ['B', 'G', 'R']) {
      b.string(name);
      b.int32(pixelType);
      b.bytes([0, 0, 0, 0]); // pLinear = 0, three reserved bytes
      b.int32(1); // x sampling
      b.int32(1); // y sampling
    }
    b.bytes([0]);
  });
  attribute('compression', 'compression', (b) => b.bytes([compression]));
  const box = (b: ByteWriter) => [0, 0, width - 1, height - 1].forEach((v) => b.int32(v));
  attribute('dataWindow', 'box2i', box);
  attribute('displayWindow', 'box2i', box);
  attribute('lineOrder', 'lineOrder', (b) => b.bytes([0])); // INCREASING_Y
  attribute('pixelAspectRatio', 'float', (b) => b.float32(1));
  attribute('screenWindowCenter', 'v2f', (b) => (b.float32(0), b.float32(0)));
  attribute('screenWindowWidth', 'float', (b) => b.float32(1));
  w.bytes([0]);
  return w.finish();
}

class ByteWriter {
  private data: number[] = [];
  private readonly scratch = new DataView(new ArrayBuffer(4));

  get length(): number {
    return this.data.length;
  }

  bytes(b: ArrayLike<number>): void {
    for (let i = 0; i < b.length; i++) this.data.push(b[i]!);
  }

  /** Attribute and channel names are plain ASCII; null-terminated in the file. */
  string(s: string): void {
    for (let i = 0; i < s.length; i++) this.data.push(s.charCodeAt(i) & 0xff);
    this.data.push(0);
  }

  int32(v: number): void {
    this.scratch.setInt32(0, v, true);
    this.bytes(new Uint8Array(this.scratch.buffer));
  }

  float32(v: number): void {
    this.scratch.setFloat32(0, v, true);
    this.bytes(new Uint8Array(this.scratch.buffer));
  }

  finish(): Uint8Array {
    return new Uint8Array(this.data);
  }
}
