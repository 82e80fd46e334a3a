import { encode } from 'fast-png';
import { zlibSync } from 'fflate';
import { deflateSync } from 'node:zlib';
import { describe, expect, it } from 'vitest';
import { LanternError } from '../errors.ts';
import { decodePng, encodePng } from './png.ts';

function randomBytes(n: number, seed: number): Uint8Array {
  const out = new Uint8Array(n);
  for (let i = 0; i < n; i++) out[i] = (seed = (seed * 1103515245 + 12345) >>> 0) >>> 24;
  return out;
}

/** A PNG assembled chunk by chunk, independent of fast-png's encoder; rows are already packed. */
function handMadePng(width: number, height: number, colourType: number, depth: number, rows: number[][], extra: Record<string, number[]> = {}): Uint8Array {
  const chunks: number[] = [];
  const be32 = (v: number) => [(v >>> 24) & 255, (v >>> 16) & 255, (v >>> 8) & 255, v & 255];
  const chunk = (type: string, data: number[]) => {
    const body = [...Array.from(type, (c) => c.charCodeAt(0)), ...data];
    chunks.push(...be32(data.length), ...body, ...be32(crc32(body)));
  };
  chunk('IHDR', [...be32(width), ...be32(height), depth, colourType, 0, 0, 0]);
  for (const [type, data] of Object.entries(extra)) chunk(type, data);
  chunk('IDAT', Array.from(zlibSync(new Uint8Array(rows.flatMap((r) => [0, ...r]))))); // filter type 0 per row
  chunk('IEND', []);
  return new Uint8Array([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, ...chunks]);
}

function crc32(bytes: number[]): number {
  let c = 0xffffffff;
  for (const b of bytes) {
    c ^= b;
    for (let k = 0; k < 8; k++) c = c & 1 ? (c >>> 1) ^ 0xedb88320 : c >>> 1;
  }
  return (c ^ 0xffffffff) >>> 0;
}

describe('PNG', () => {
  it.each([[1, 1], [7, 3], [3, 17], [64, 9]])('round-trips 8-bit RGBA exactly (%i×%i)', (width, height) => {
    const rgba = randomBytes(width * height * 4, width * 100 + height);
    const file = encodePng(width, height, rgba);
    expect(Array.from(file.subarray(0, 8))).toEqual([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]);
    const image = decodePng(file);
    expect([image.width, image.height]).toEqual([width, height]);
    expect(image.data).toEqual(rgba);
  });

  it('round-trips through any zlib (Node\'s native one, as the CLI passes), with valid CRCs', () => {
    const rgba = randomBytes(33 * 7 * 4, 3);
    for (const level of [0, 1, 6]) {
      const image = decodePng(encodePng(33, 7, rgba, (raw) => deflateSync(raw, { level })));
      expect(image.data).toEqual(rgba);
    }
  });

  it('filters rows by their left neighbours: a horizontal ramp compresses to a fraction of its pixels', () => {
    const width = 128, height = 16;
    const rgba = new Uint8Array(width * height * 4);
    for (let i = 0; i < width * height; i++) rgba.set([2 * (i % width), (3 * i) % 256, 255 - (i % width), 255], 4 * i);
    const file = encodePng(width, height, rgba);
    expect(decodePng(file).data).toEqual(rgba);
    expect(file.length).toBeLessThan(rgba.length / 50);
  });

  it('converts grey, grey+alpha, RGB and 16-bit images to 8-bit RGBA', () => {
    const grey = decodePng(encode({ width: 2, height: 1, data: new Uint8Array([0, 200]), channels: 1, depth: 8 }));
    expect(Array.from(grey.data)).toEqual([0, 0, 0, 255, 200, 200, 200, 255]);
    const greyAlpha = decodePng(encode({ width: 1, height: 1, data: new Uint8Array([50, 60]), channels: 2, depth: 8 }));
    expect(Array.from(greyAlpha.data)).toEqual([50, 50, 50, 60]);
    const rgb = decodePng(encode({ width: 1, height: 1, data: new Uint8Array([1, 2, 3]), channels: 3, depth: 8 }));
    expect(Array.from(rgb.data)).toEqual([1, 2, 3, 255]);
    const deep = decodePng(encode({ width: 1, height: 1, data: new Uint16Array([65535, 0, 32896, 257]), channels: 4, depth: 16 }));
    expect(Array.from(deep.data)).toEqual([255, 0, 128, 1]);
  });

  it('expands palette images with tRNS alpha, and packed low-bit-depth samples', () => {
    // 2-bit palette, 5 pixels (two bytes per row, padded); entries 0 and 2 translucent, 1 and 3 opaque.
    const palette = [[255, 0, 0], [0, 255, 0], [0, 0, 255], [9, 9, 9]];
    const indexed = handMadePng(5, 1, 3, 2, [[0b00011011, 0b10000000]], { PLTE: palette.flat(), tRNS: [10, 255, 30] });
    expect(Array.from(decodePng(indexed).data)).toEqual([255, 0, 0, 10, 0, 255, 0, 255, 0, 0, 255, 30, 9, 9, 9, 255, 0, 0, 255, 30]);
    // 1-bit grey, 2 rows of 3 pixels.
    const bits = handMadePng(3, 2, 0, 1, [[0b10100000], [0b01000000]]);
    expect(Array.from(decodePng(bits).data.filter((_, i) => i % 4 === 0))).toEqual([255, 0, 255, 0, 255, 0]);
  });

  it('rejects bad input with LanternError', () => {
    expect(() => decodePng(new Uint8Array([1, 2, 3, 4]), 'junk.png')).toThrow(LanternError);
    expect(() => decodePng(new Uint8Array([1, 2, 3, 4]), 'junk.png')).toThrow(/junk\.png: not a readable PNG/);
    const truncated = encodePng(4, 4, randomBytes(64, 1)).subarray(0, 40);
    expect(() => decodePng(truncated)).toThrow(LanternError);
    const corrupted = encodePng(4, 4, randomBytes(64, 1));
    corrupted[corrupted.length - 20] = corrupted[corrupted.length - 20]! ^ 0x55; // inside the image data: the CRC no longer matches
    expect(() => decodePng(corrupted)).toThrow(LanternError);
    expect(() => encodePng(2, 2, new Uint8Array(15))).toThrow(/15 bytes given for 2×2/);
    expect(() => encodePng(0, 1, new Uint8Array(0))).toThrow(LanternError);
  });
});
