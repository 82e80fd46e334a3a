/**
 * OpenEXR's lossless chunk compressions that Lantern handles: ZIP/ZIPS (zlib) and RLE. Both first
 * run two reversible filters over the raw bytes, which is what makes float images compress:
 * - interleave: the bytes at even offsets go to the first half, odd offsets to the second, so the
 *   slowly-varying high bytes of neighbouring samples end up next to each other;
 * - predictor: each byte becomes its difference from the previous one (+128, mod 256), turning
 *   smooth runs into runs of near-constant bytes.
 */
import { unzlibSync } from 'fflate';

/** Filters for writing: interleave, then delta-encode. */
export function filterForCompression(raw: Uint8Array): Uint8Array {
  const n = raw.length;
  const out = new Uint8Array(n);
  const half = (n + 1) >> 1;
  for (let i = 0, a = 0, b = half; i < n; i += 2) {
    out[a++] = raw[i]!;
    if (i + 1 < n) out[b++] = raw[i + 1]!;
  }
  for (let i = n - 1; i > 0; i--) out[i] = (out[i]! - out[i - 1]! + 128) & 0xff;
  return out;
}

/** Inverse of filterForCompression: delta-decode in place, then de-interleave. */
export function unfilterAfterDecompression(filtered: Uint8Array): Uint8Array {
  const n = filtered.length;
  for (let i = 1, previous = filtered[0] ?? 0; i < n; i++) previous = filtered[i] = (previous + filtered[i]! - 128) & 0xff;
  const out = new Uint8Array(n);
  const half = (n + 1) >> 1;
  // Pairs first, then the odd last byte: no test inside the loop (this runs over every byte of an image).
  for (let a = 0; a < n >> 1; a++) {
    out[2 * a] = filtered[a]!;
    out[2 * a + 1] = filtered[half + a]!;
  }
  if (n & 1) out[n - 1] = filtered[half - 1]!;
  return out;
}


/** Inflates into a buffer of exactly the expected size; returns undefined if the data does not fill it. */
export function zipDecompress(data: Uint8Array, expectedSize: number): Uint8Array | undefined {
  const out = new Uint8Array(expectedSize);
  const inflated = unzlibSync(data, { out });
  return inflated.length === expectedSize ? unfilterAfterDecompression(inflated) : undefined;
}

/**
 * OpenEXR's run-length code: a signed count byte c; c < 0 means -c literal bytes follow, c ≥ 0 means
 * the next byte repeats c + 1 times. Returns undefined on malformed or wrongly sized data.
 */
export function rleDecompress(data: Uint8Array, expectedSize: number): Uint8Array | undefined {
  const out = new Uint8Array(expectedSize);
  let i = 0, o = 0;
  while (i < data.length) {
    const c = (data[i++]! << 24) >> 24; // as signed char
    if (c < 0) {
      if (i - c > data.length || o - c > expectedSize) return undefined;
      out.set(data.subarray(i, i - c), o);
      i -= c;
      o -= c;
    } else {
      if (i >= data.length || o + c + 1 > expectedSize) return undefined;
      out.fill(data[i++]!, o, o + c + 1);
      o += c + 1;
    }
  }
  return o === expectedSize ? unfilterAfterDecompression(out) : undefined;
}
