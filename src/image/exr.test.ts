import { zlibSync } from 'fflate';
import { describe, expect, it } from 'vitest';
import { LanternError } from '../errors.ts';
import { filterForCompression } from './exr-compression.ts';
import { decodeExr, decodeExrRgb, encodeExr, encodeExrAsync, exrToRgb } from './exr.ts';
import { floatToHalf, halfToFloat } from './half.ts';
import { expectLanternError } from '../expect-lantern-error.ts';

/** Deterministic values covering signs, zero, -0, huge, tiny (float subnormal), inf and NaN. */
function awkwardFloats(n: number, seed: number): Float32Array {
  const special = [0, -0, 1, -1, 1e30, -3.4e38, 1e-40, -1e-42, Infinity, -Infinity, NaN, 65504, 0.1];
  const out = new Float32Array(n);
  for (let i = 0; i < n; i++) {
    seed = (seed * 1103515245 + 12345) >>> 0;
    out[i] = i % 5 === 0 ? special[(seed >>> 8) % special.length]! : ((seed / 2 ** 32) - 0.5) * 10 ** ((seed % 13) - 6);
  }
  return out;
}

/** A smooth image, which the ZIP filters make very compressible. */
function gradient(width: number, height: number): Float32Array {
  const rgb = new Float32Array(width * height * 3);
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const i = 3 * (y * width + x);
      rgb[i] = x / width;
      rgb[i + 1] = y / height;
      rgb[i + 2] = 0.25;
    }
  }
  return rgb;
}

const SIZES: [number, number][] = [[1, 1], [3, 17], [37, 5], [16, 16], [64, 33]];
const COMPRESSIONS = ['none', 'zips', 'zip'] as const;

describe('EXR round trip', () => {
  for (const compression of COMPRESSIONS) {
    it.each(SIZES)(`keeps every float bit-exact with ${compression} (%i×%i)`, (width, height) => {
      for (const rgb of [awkwardFloats(width * height * 3, width * 31 + height), gradient(width, height)]) {
        const file = encodeExr(width, height, rgb, { compression });
        const image = decodeExr(file, 'rt.exr');
        expect([image.width, image.height]).toEqual([width, height]);
        expect(Object.keys(image.channels)).toEqual(['B', 'G', 'R']);
        // toEqual compares numbers with Object.is: -0 ≠ 0 and NaN = NaN, so this is exact.
        expect(Array.from(exrToRgb(image))).toEqual(Array.from(rgb));
      }
    });
  }

  it('compresses smooth images well with ZIP', () => {
    const rgb = gradient(256, 128);
    const raw = encodeExr(256, 128, rgb, { compression: 'none' }).length;
    const zip = encodeExr(256, 128, rgb).length;
    expect(raw).toBeGreaterThan(256 * 128 * 12);
    expect(zip).toBeLessThan(raw / 4);
  });

  it('writes HALF channels on request, rounding to the nearest half', () => {
    const rgb = gradient(37, 5);
    rgb[0] = 70000; // beyond the half range
    const image = decodeExr(encodeExr(37, 5, rgb, { pixelType: 'half' }));
    const back = exrToRgb(image);
    expect(back[0]).toBe(Infinity);
    for (let i = 1; i < rgb.length; i++) expect(Math.abs(back[i]! - rgb[i]!)).toBeLessThanOrEqual(Math.abs(rgb[i]!) * 2 ** -11);
    expect(encodeExr(37, 5, rgb, { pixelType: 'half', compression: 'none' }).length).toBeLessThan(encodeExr(37, 5, rgb, { compression: 'none' }).length * 0.6);
  });

  it('writes the header a strict reader expects', () => {
    const file = encodeExr(3, 17, gradient(3, 17));
    const view = new DataView(file.buffer);
    expect(view.getUint32(0, true)).toBe(20000630);
    expect(view.getUint32(4, true)).toBe(2);
    const text = new TextDecoder('latin1').decode(file.subarray(0, 400));
    for (const attr of ['channels\0chlist', 'compression\0compression', 'dataWindow\0box2i', 'displayWindow\0box2i', 'lineOrder\0lineOrder', 'pixelAspectRatio\0float', 'screenWindowCenter\0v2f', 'screenWindowWidth\0float']) {
      expect(text).toContain(`${attr}\0`);
    }
    // chlist: B, G, R as FLOAT (2), then its terminator; ZIP is compression 3.
    const channels = text.indexOf('chlist\0') + 7 + 4;
    expect(Array.from(file.subarray(channels, channels + 19))).toEqual([66, 0, 2, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 71]);
    expect(file[text.indexOf('compression\0compression\0') + 24 + 4]).toBe(3);
    // Header end (the empty attribute name) is followed by the offset table: 2 chunks of 16 lines.
    const headerEnd = text.indexOf('screenWindowWidth\0float\0') + 24 + 4 + 4 + 1;
    expect(file[headerEnd - 1]).toBe(0);
    const first = Number(view.getBigUint64(headerEnd, true));
    const second = Number(view.getBigUint64(headerEnd + 8, true));
    expect(first).toBe(headerEnd + 16);
    expect(view.getInt32(first, true)).toBe(0); // y of the first chunk
    expect(second).toBe(first + 8 + view.getInt32(first + 4, true));
    expect(view.getInt32(second, true)).toBe(16);
  });

  it('rejects bad input to the encoder', () => {
    expectLanternError(() => encodeExr(2, 2, new Float32Array(11)), /11 floats given for 2×2/);
    expectLanternError(() => encodeExr(0, 2, new Float32Array(0)), /0×2/);
  });
});

describe('half floats', () => {
  it('round-trips every half exactly', () => {
    for (let h = 0; h < 65536; h++) {
      const f = halfToFloat(h);
      if (Number.isNaN(f)) expect(Number.isNaN(halfToFloat(floatToHalf(f)))).toBe(true);
      else expect(floatToHalf(f)).toBe(h);
    }
  });

  it('rounds to nearest even, with overflow to infinity and underflow to zero', () => {
    const cases: [number, number][] = [
      [1, 0x3c00], [-2, 0xc000], [65504, 0x7bff], [65519, 0x7bff], [65520, 0x7c00], [1e9, 0x7c00], [-0, 0x8000],
      [1 + 2 ** -11, 0x3c00], [1 + 3 * 2 ** -11, 0x3c02], [2 ** -24, 0x0001], [2 ** -25, 0], [2 ** -25 * 1.01, 1],
      [3 * 2 ** -25, 2], [2 ** -14, 0x0400], [2 ** -14 - 2 ** -25, 0x0400], [Infinity, 0x7c00], [-Infinity, 0xfc00],
    ];
    for (const [value, bits] of cases) expect(floatToHalf(value), `${value}`).toBe(bits);
    expect(floatToHalf(NaN) & 0x7c00).toBe(0x7c00);
    expect(floatToHalf(NaN) & 0x3ff).not.toBe(0);
  });
});

/** A tiny EXR assembled field by field, independent of the encoder. */
function handMadeExr(opts: {
  channels: { name: string; type: number }[];
  compression: number;
  window: [number, number, number, number];
  lineOrder?: number;
  chunks: { y: number; data: number[] }[];
}): Uint8Array {
  const bytes: number[] = [];
  const int32 = (v: number) => bytes.push(v & 255, (v >> 8) & 255, (v >> 16) & 255, (v >>> 24) & 255);
  const str = (s: string) => bytes.push(...Array.from(s, (c) => c.charCodeAt(0)), 0);
  const attr = (name: string, type: string, value: number[]) => (str(name), str(type), int32(value.length), bytes.push(...value));
  const le = (v: number) => [v & 255, (v >> 8) & 255, (v >> 16) & 255, (v >>> 24) & 255];
  int32(20000630);
  int32(2);
  attr('channels', 'chlist', [...opts.channels.flatMap((c) => [...Array.from(c.name, (ch) => ch.charCodeAt(0)), 0, ...le(c.type), 0, 0, 0, 0, ...le(1), ...le(1)]), 0]);
  attr('compression', 'compression', [opts.compression]);
  attr('dataWindow', 'box2i', opts.window.flatMap(le));
  attr('displayWindow', 'box2i', opts.window.flatMap(le));
  attr('lineOrder', 'lineOrder', [opts.lineOrder ?? 0]);
  attr('owner', 'string', Array.from('test', (c) => c.charCodeAt(0))); // an attribute the decoder must skip
  bytes.push(0);
  let offset = bytes.length + 8 * opts.chunks.length;
  const offsets: number[] = [];
  for (const c of opts.chunks) {
    offsets.push(offset);
    offset += 8 + c.data.length;
  }
  // The offset table is in increasing-y order even when the chunks are stored in another order.
  const byY = opts.chunks.map((c, i) => [c.y, offsets[i]!] as const).sort((a, b) => a[0] - b[0]);
  for (const [, o] of byY) (int32(o), int32(0));
  for (const c of opts.chunks) (int32(c.y), int32(c.data.length), bytes.push(...c.data));
  return new Uint8Array(bytes);
}

const u16 = (v: number) => [v & 255, v >> 8];
const f32 = (v: number) => Array.from(new Uint8Array(new Float32Array([v]).buffer));
const u32 = (v: number) => [v & 255, (v >> 8) & 255, (v >> 16) & 255, (v >>> 24) & 255];

describe('EXR decoding of other writers\' files', () => {
  it('reads HALF, FLOAT and UINT channels, an offset data window and decreasing line order', () => {
    // 2×2 pixels at (10,-3)–(11,-2); channels A (UINT), G (HALF), Z (FLOAT); one scanline per chunk.
    const channels = [{ name: 'A', type: 0 }, { name: 'G', type: 1 }, { name: 'Z', type: 2 }];
    const line = (a: number[], g: number[], z: number[]) => [...a.flatMap(u32), ...g.flatMap(u16), ...z.flatMap(f32)];
    const file = handMadeExr({
      channels,
      compression: 0,
      window: [10, -3, 11, -2],
      lineOrder: 1,
      chunks: [
        { y: -2, data: line([7, 4000000000], [0x7c00, 0x3555], [-1.5, 2e20]) },
        { y: -3, data: line([0, 1], [0x3c00, 0xc000], [0.5, -0]) },
      ],
    });
    const image = decodeExr(file, 'hand.exr');
    expect([image.width, image.height]).toEqual([2, 2]);
    expect(Array.from(image.channels.A!)).toEqual([0, 1, 7, 4000000000].map(Math.fround));
    expect(Array.from(image.channels.G!)).toEqual([1, -2, Infinity, 0.333251953125]);
    expect(Array.from(image.channels.Z!)).toEqual([0.5, -0, -1.5, Math.fround(2e20)]);
  });

  it('reads more HALF values, including subnormals and -0, with ZIPS compression', () => {
    // Padded with a long constant run so that zlib output is smaller than the raw bytes: otherwise
    // the chunk would (correctly) be read as stored uncompressed.
    const halves = [0x0001, 0x8000, 0x7bff, 0x0400, 0x3bff, 0xfbff, ...Array<number>(58).fill(0x3c00)];
    const raw = new Uint8Array(halves.flatMap(u16));
    // Hand-compressed exactly as the format says: filter, then zlib.
    const packed = Array.from(zlibSync(filterForCompression(raw)));
    const file = handMadeExr({ channels: [{ name: 'Y', type: 1 }], compression: 2, window: [0, 0, 63, 0], chunks: [{ y: 0, data: packed }] });
    expect(packed.length).toBeLessThan(raw.length); // the decoder must take the decompression path
    const image = decodeExr(file);
    expect(Array.from(image.channels.Y!.subarray(0, 7))).toEqual([2 ** -24, -0, 65504, 2 ** -14, 0.99951171875, -65504, 1]);
    expect(Array.from(exrToRgb(image).subarray(0, 3))).toEqual([2 ** -24, 2 ** -24, 2 ** -24]);
  });

  it('reads RLE-compressed files', () => {
    const values = [...Array<number>(20).fill(1), 0.5, 0.25, ...Array<number>(10).fill(2)];
    const raw = new Uint8Array(values.flatMap(f32));
    const filtered = filterForCompression(raw);
    // Run-length encode: runs of 3+ equal bytes as (count - 1, byte), the rest as literal runs
    // (-length, bytes...).
    const rle: number[] = [];
    let literal: number[] = [];
    const flush = () => {
      if (literal.length > 0) rle.push(256 - literal.length, ...literal);
      literal = [];
    };
    for (let i = 0; i < filtered.length; ) {
      let run = 1;
      while (i + run < filtered.length && filtered[i + run] === filtered[i] && run < 128) run++;
      if (run >= 3) {
        flush();
        rle.push(run - 1, filtered[i]!);
        i += run;
      } else {
        literal.push(filtered[i++]!);
        if (literal.length === 127) flush();
      }
    }
    flush();
    expect(rle.length).toBeLessThan(raw.length);
    const file = handMadeExr({ channels: [{ name: 'R', type: 2 }], compression: 1, window: [0, 0, 31, 0], chunks: [{ y: 0, data: rle }] });
    expect(Array.from(decodeExr(file).channels.R!)).toEqual(values);
  });
});

/**
 * Files written by the reference implementation (OpenEXR 3.5 through its Python bindings), kept as
 * base64 so the test needs no tools: channels G (FLOAT), R (HALF), U (UINT) holding, at data-window
 * pixel (x, y), G = (7x - 3y) / 8, R = x - y / 4 and U = 1000x + y, all exact in their types.
 */
const OPENEXR_FILES = {
  // 6×20 pixels, ZIP, data window origin (3, -2), DECREASING_Y line order.
  zip:
    'di8xAQIAAABjaGFubmVscwBjaGxpc3QANwAAAEcAAgAAAAAAAAABAAAAAQAAAFIAAQAAAAAAAAABAAAAAQAAAFUAAAAAAAAAAAAB' +
    'AAAAAQAAAABjb21wcmVzc2lvbgBjb21wcmVzc2lvbgABAAAAA2RhdGFXaW5kb3cAYm94MmkAEAAAAAMAAAD+////CAAAABEAAABk' +
    'aXNwbGF5V2luZG93AGJveDJpABAAAAAAAAAAAAAAAD8AAAA/AAAAbGluZU9yZGVyAGxpbmVPcmRlcgABAAAAAXBpeGVsQXNwZWN0' +
    'UmF0aW8AZmxvYXQABAAAAAAAgD9zY3JlZW5XaW5kb3dDZW50ZXIAdjJmAAgAAAAAAAAAAAAAAHNjcmVlbldpbmRvd1dpZHRoAGZs' +
    'b2F0AAQAAAAAAIA/dHlwZQBzdHJpbmcADQAAAHNjYW5saW5laW1hZ2UAIAIAAAAAAABmAQAAAAAAAA4AAACyAAAAeF5jcDigcofj' +
    'xw2NBQkBGxpAYEJBRUfCAo8dBhckXjT4bDG4IPLmg8AOj4YDBxoYGhom5le2J8733G54XvJ5Q8QKmyMKD1j+XDCY8QIo19AwKa+q' +
    'LWme1zajc1LPGlLmeOzQuSLw4YXEBgEHkN7JudWtyXO9txqflX7a4HAABu1b6+pqjuxxaWiuba/sLu0vnJyLJOvQUldXW87mhku2' +
    'vq62isEDt2xd9S8fJFkA/h90gf7///9NAgAAeF5jaGh4oJCwYEXEAwWeLw0QkDEjYIPFCYUHHD8aHA40NBhcmFBwwoKBoaGBoeHA' +
    'wfrM6YHrLY8r3uf83nDAASjGUDBhQ8ALCZBGBqa6rGlB66yOKd3j+tYg8IGBYUGCw4EZGRcMQHodnGuzpwavtT6qfJf7K9DkBQkM' +
    'DAIfGhp2eIBtbanJmRKyxuaIyh2gQwomgOw74BCwYUECyOAG1urcyaGrbQ+r3ub93DChwOBCA9AEhQcdFWC9bVV5k8JW2R1Su8X3' +
    'qWFFRMKCBwoQf4H1slfmTwxfaX9Q/Sb/R6CZHRUKDyD+AuvtqCiYELHC4YDGDaBjbmgsSAjYAPYXEAJJzvLC/sjljvs1rwu+b/gg' +
    'AHIrxF9gvV1lRX1Ry5z2aV0TetfA8ueCwYwMsL8gerlLi3ujlzrv1b4q/Bao64XEhgCIv8Cgp6SkJ2aJyx6dKyJvGmSeMDCcsAD7' +
    'C6K5t7i0O3ax627dy6KvGzRu8Hx5oADzFxD0FZV1xS1y26V3SexVg8kZiRc/OMD+SgDr7S8s74xf6L5T/6L4SyB3v+N+xwMOILin' +
    'pamp0bqhuba9sru0v3ByboPdIbjsF7ZWoKwNsqz9wX1OUPkfDG3NGLJw3b9+dTY3NaHJQnQDZf8cAVmMIQvV/bccZLEtsqzDAbju' +
    'f1Ugi7HIgv3FUA2y2A5VFiQPNpuxBmQxFlmw2Yy1IIvt0WWhuplqQRZjlQXqZq4DWeyAXdaupQ5kMRZZsHxzHchiRxyyLXUgi52w' +
    'yQLlW+pAFjsjyQIAT2nLkA==',
  // 6×4 pixels, RLE (some scanlines compressed, some stored raw), INCREASING_Y.
  rle:
    'di8xAQIAAABjaGFubmVscwBjaGxpc3QANwAAAEcAAgAAAAAAAAABAAAAAQAAAFIAAQAAAAAAAAABAAAAAQAAAFUAAAAAAAAAAAAB' +
    'AAAAAQAAAABjb21wcmVzc2lvbgBjb21wcmVzc2lvbgABAAAAAWRhdGFXaW5kb3cAYm94MmkAEAAAAAAAAAAAAAAABQAAAAMAAABk' +
    'aXNwbGF5V2luZG93AGJveDJpABAAAAAAAAAAAAAAAD8AAAA/AAAAbGluZU9yZGVyAGxpbmVPcmRlcgABAAAAAHBpeGVsQXNwZWN0' +
    'UmF0aW8AZmxvYXQABAAAAAAAgD9zY3JlZW5XaW5kb3dDZW50ZXIAdjJmAAgAAAAAAAAAAAAAAHNjcmVlbldpbmRvd1dpZHRoAGZs' +
    'b2F0AAQAAAAAAIA/dHlwZQBzdHJpbmcADQAAAHNjYW5saW5laW1hZ2UAdgEAAAAAAAC3AQAAAAAAAPsBAAAAAAAAPwIAAAAAAAAA' +
    'AAAAOQAAAPMAgIDgIGCgqFjgIAz0BoD2aJhQsDjIIOAI+AKA5b9Bv0HAQMBAwEC8hIKCgTuAg32HeYt1j3GTbQEAAAA8AAAAAADA' +
    'vgAAAD8AALA/AAAQQAAASEAAAIBAALQAOgA/gEGAQ8BEAQAAAOkDAADRBwAAuQsAAKEPAACJEwAAAgAAADwAAAAAAEC/AAAAPgAA' +
    'gD8AAPA/AAAwQAAAaEAAuAA4AD4AQQBDgEQCAAAA6gMAANIHAAC6CwAAog8AAIoTAAADAAAAPAAAAAAAkL8AAIC+AAAgPwAAwD8A' +
    'ABhAAABQQAC6ADQAPYBAgEJARAMAAADrAwAA0wcAALsLAACjDwAAixMAAA==',
};

describe('EXR files from OpenEXR itself', () => {
  it.each([['zip', 6, 20], ['rle', 6, 4]] as const)('decodes the %s file exactly', (kind, width, height) => {
    const image = decodeExr(new Uint8Array(Buffer.from(OPENEXR_FILES[kind], 'base64')), `${kind}.exr`);
    expect([image.width, image.height]).toEqual([width, height]);
    expect(Object.keys(image.channels)).toEqual(['G', 'R', 'U']);
    for (let y = 0; y < height; y++) {
      for (let x = 0; x < width; x++) {
        const i = y * width + x;
        expect(image.channels.G![i]).toBe((7 * x - 3 * y) / 8);
        expect(image.channels.R![i]).toBe(x - y / 4);
        expect(image.channels.U![i]).toBe(1000 * x + y);
      }
    }
  });
});

describe('EXR errors', () => {
  const good = () => encodeExr(3, 17, gradient(3, 17));

  it('rejects non-EXR data and unsupported features by name', () => {
    expectLanternError(() => decodeExr(new Uint8Array([1, 2, 3]), 'x.exr'), /x\.exr: not an OpenEXR file/);
    expectLanternError(() => decodeExr(new TextEncoder().encode('P6 3 3 255\n'), 'x.exr'), /not an OpenEXR file/);
    const tiled = good();
    tiled[5] = tiled[5]! | 0x02;
    expectLanternError(() => decodeExr(tiled, 't.exr'), /tiled images are not supported/);
    const multi = good();
    multi[5] = multi[5]! | 0x10;
    expectLanternError(() => decodeExr(multi), /multi-part/);
    for (const [code, name] of [[4, 'PIZ'], [5, 'PXR24'], [6, 'B44'], [8, 'DWAA'], [9, 'DWAB'], [42, 'unknown compression 42']] as const) {
      const file = good();
      const at = new TextDecoder('latin1').decode(file.subarray(0, 300)).indexOf('compression\0compression\0') + 24 + 4;
      file[at] = code;
      expectLanternError(() => decodeExr(file, 'c.exr'), new RegExp(`c\\.exr: OpenEXR compression ${name} is not supported`));
    }
  });

  it('gives a LanternError for every truncation', () => {
    for (const file of [good(), encodeExr(5, 3, awkwardFloats(45, 1), { compression: 'none' })]) {
      for (let n = 0; n < file.length; n++) expectLanternError(() => decodeExr(file.subarray(0, n), 'cut.exr'));
    }
  });

  it('gives a LanternError or a correct-size image for corrupted bytes, never a crash', () => {
    let seed = 7;
    const random = () => ((seed = (seed * 1103515245 + 12345) >>> 0) / 2 ** 32);
    const originals = [good(), encodeExr(37, 5, gradient(37, 5), { compression: 'zips' }), encodeExr(4, 4, gradient(4, 4), { compression: 'none', pixelType: 'half' })];
    for (let trial = 0; trial < 3000; trial++) {
      const file = originals[trial % originals.length]!.slice();
      for (let k = 0; k < 1 + (trial % 3); k++) file[Math.floor(random() * file.length)] = Math.floor(random() * 256);
      try {
        const image = decodeExr(file, 'fuzz.exr');
        for (const plane of Object.values(image.channels)) expect(plane.length).toBe(image.width * image.height);
      } catch (e) {
        if (!(e instanceof LanternError)) throw e;
      }
    }
  });

  it('refuses a data window far larger than the file', () => {
    const file = handMadeExr({ channels: [{ name: 'R', type: 2 }], compression: 3, window: [0, 0, 2_000_000_000, 1_000_000], chunks: [] });
    expectLanternError(() => decodeExr(file, 'big.exr'), /data window \(2000000001×1000001\) is far larger than the file/);
  });

  it('explains missing channels when converting to RGB', () => {
    const file = handMadeExr({ channels: [{ name: 'Z', type: 2 }], compression: 0, window: [0, 0, 0, 0], chunks: [{ y: 0, data: f32(1) }] });
    expectLanternError(() => exrToRgb(decodeExr(file), 'z.exr'), /z\.exr: no R, G, B \(or Y\) channels; it has Z/);
  });

  it('decodes straight to interleaved RGB as the planes and their conversion do, skipping other channels, Y repeated', () => {
    for (const file of [encodeExr(37, 5, gradient(37, 5), { pixelType: 'half' }), encodeExr(5, 3, awkwardFloats(45, 1), { compression: 'none' }), encodeExr(9, 40, gradient(9, 40), { compression: 'zips' })]) {
      const direct = decodeExrRgb(file, 'd.exr');
      expect(Array.from(direct.rgb)).toEqual(Array.from(exrToRgb(decodeExr(file))));
    }
    // OpenEXR's own file: G, R and U; no B, so no RGB.
    expectLanternError(() => decodeExrRgb(new Uint8Array(Buffer.from(OPENEXR_FILES.zip, 'base64')), 'gru.exr'), /gru\.exr: no R, G, B \(or Y\) channels; it has G, R, U/);
    const grey = handMadeExr({ channels: [{ name: 'A', type: 2 }, { name: 'Y', type: 2 }], compression: 0, window: [0, 0, 1, 0], chunks: [{ y: 0, data: [0.5, 0.25, 3, 4].flatMap(f32) }] });
    expect(Array.from(decodeExrRgb(grey).rgb)).toEqual([3, 3, 3, 4, 4, 4]);
  });
});

describe('EXR chunk compression handed out', () => {
  const [width, height] = [64, 50];
  const rgb = gradient(width, height);

  it('gives encodeExr\'s bytes when the chunks go through the same zlib, all at once', async () => {
    const handed: number[] = [];
    const file = await encodeExrAsync(width, height, rgb, {}, async (chunks) => {
      handed.push(chunks.length);
      return chunks.map((c) => zlibSync(c, { level: 4 }));
    });
    expect(handed).toEqual([Math.ceil(height / 16)]);
    expect(Buffer.from(file).equals(Buffer.from(encodeExr(width, height, rgb)))).toBe(true);
  });

  it('decodes to the same floats through another deflate, and stores a chunk raw where it does not shrink', () => {
    const other = encodeExr(width, height, rgb, {}, (filtered) => zlibSync(filtered, { level: 9 }));
    expect(Array.from(decodeExrRgb(other).rgb)).toEqual(Array.from(rgb));
    // A deflate that never shrinks anything: every chunk is then written raw, and still decodes.
    const raw = encodeExr(width, height, rgb, {}, (filtered) => new Uint8Array(filtered.length + 1));
    // The raw pixels, plus the header (under 400 bytes) and 16 bytes of table and chunk header a chunk.
    expect(raw.length - width * height * 12).toBeGreaterThan(16 * Math.ceil(height / 16));
    expect(raw.length - width * height * 12).toBeLessThan(400 + 16 * Math.ceil(height / 16));
    expect(Array.from(decodeExrRgb(raw).rgb)).toEqual(Array.from(rgb));
  });

  it('hands nothing out without compression', async () => {
    const file = await encodeExrAsync(width, height, rgb, { compression: 'none' }, () => Promise.reject(new Error('not called')));
    expect(Buffer.from(file).equals(Buffer.from(encodeExr(width, height, rgb, { compression: 'none' })))).toBe(true);
  });
});
