/**
 * The fuzzer's randomness and its format-blind mutations. Everything is driven by one seeded
 * generator, so a case is fully named by (target, seed, index) and can be regenerated anywhere: in
 * the test, in a worker of the long run, and from a saved reproducer's name.
 */

/** mulberry32: small, fast, and the same sequence on every platform. */
export class Rng {
  private s: number;
  constructor(seed: number) {
    this.s = seed >>> 0;
  }
  next(): number {
    let t = (this.s = (this.s + 0x6d2b79f5) >>> 0);
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  }
  /** An integer in [0, n). */
  int(n: number): number {
    return Math.floor(this.next() * n);
  }
  chance(p: number): boolean {
    return this.next() < p;
  }
  pick<T>(items: readonly T[]): T {
    return items[this.int(items.length)]!;
  }
}

/** The seed of case `index` of a run seeded `seed`: cases are independent of each other's draws. */
export function caseSeed(seed: number, index: number): number {
  return (Math.imul(seed ^ 0x9e3779b9, 0x85ebca6b) + Math.imul(index + 1, 0xc2b2ae35)) >>> 0;
}

/** Values at the edges of the integer types headers use, where off-by-one and overflow bugs live. */
export const INTERESTING = [0, 1, 2, 3, 7, 8, 15, 16, 127, 128, 255, 256, 1023, 1024, 4096, 32767, 32768, 65535, 65536, 1e6, 2 ** 24, 2 ** 31 - 1, 2 ** 31, 2 ** 32 - 1, -1, -2, -128, -32768, -(2 ** 31)];

/** An interesting value, or one near a given value (a count that is off by a little). */
export function interesting(rng: Rng, near?: number): number {
  if (near !== undefined && rng.chance(0.3)) return near + rng.pick([-2, -1, 1, 2, near, 1000]);
  return rng.chance(0.8) ? rng.pick(INTERESTING) : rng.int(2 ** 32) - 2 ** 31;
}

/** Writes `value` as a little- (or big-) endian integer of `size` bytes at `at`, if it fits in the buffer. */
export function putInt(bytes: Uint8Array, at: number, size: 1 | 2 | 4, value: number, little = true): void {
  if (at < 0 || at + size > bytes.length) return;
  const v = value >>> 0;
  for (let k = 0; k < size; k++) bytes[little ? at + k : at + size - 1 - k] = (v >>> (8 * k)) & 0xff;
}

/**
 * A format-blind mutation: flip bits, overwrite with interesting integers, truncate, insert or
 * delete a run, duplicate a block. Returns a new array.
 */
export function mutateBytes(rng: Rng, input: Uint8Array, from = 0, to = input.length): Uint8Array {
  const bytes = input.slice();
  if (bytes.length === 0) return new Uint8Array(rng.int(16));
  const span = Math.max(1, to - from);
  const at = () => from + rng.int(span);
  switch (rng.int(7)) {
    case 0: {
      for (let n = 1 + rng.int(8); n > 0; n--) {
        const i = at();
        if (i < bytes.length) bytes[i]! ^= 1 << rng.int(8);
      }
      return bytes;
    }
    case 1: {
      putInt(bytes, at(), rng.pick([1, 2, 4] as const), interesting(rng), rng.chance(0.8));
      return bytes;
    }
    case 2:
      return bytes.slice(0, at());
    case 3: {
      const i = at();
      const run = new Uint8Array(1 + rng.int(64)).map(() => (rng.chance(0.5) ? rng.int(256) : 0));
      return concat(bytes.subarray(0, i), run, bytes.subarray(i));
    }
    case 4: {
      const i = at();
      return concat(bytes.subarray(0, i), bytes.subarray(Math.min(bytes.length, i + 1 + rng.int(64))));
    }
    case 5: {
      const i = at();
      const n = 1 + rng.int(256);
      return concat(bytes.subarray(0, i + n), bytes.subarray(i, i + n), bytes.subarray(i + n));
    }
    default: {
      for (let n = 1 + rng.int(32); n > 0; n--) {
        const i = at();
        if (i < bytes.length) bytes[i] = rng.int(256);
      }
      return bytes;
    }
  }
}

export function concat(...parts: readonly Uint8Array[]): Uint8Array {
  const out = new Uint8Array(parts.reduce((n, p) => n + p.length, 0));
  let at = 0;
  for (const p of parts) {
    out.set(p, at);
    at += p.length;
  }
  return out;
}

/** Text mutations for line formats (molfiles, PLY headers): numbers bent, lines dropped, doubled or swapped. */
export function mutateLines(rng: Rng, text: string, rounds = 1 + rng.int(3)): string {
  const lines = text.split('\n');
  for (let r = 0; r < rounds && lines.length > 0; r++) {
    const i = rng.int(lines.length);
    switch (rng.int(6)) {
      case 0:
        lines.splice(i, 1);
        break;
      case 1:
        lines.splice(i, 0, lines[i]!);
        break;
      case 2: {
        const j = rng.int(lines.length);
        [lines[i], lines[j]] = [lines[j]!, lines[i]!];
        break;
      }
      case 3:
        lines[i] = lines[i]!.slice(0, rng.int(lines[i]!.length + 1));
        break;
      default: {
        // Replace one number in the line by an interesting one, a float edge, or garbage.
        const numbers = [...lines[i]!.matchAll(/-?\d+(\.\d+)?/g)];
        if (numbers.length === 0) break;
        const m = rng.pick(numbers);
        const value = rng.pick(['NaN', 'Infinity', '-Infinity', '1e308', '-1e308', '1e-320', 'x', '', String(interesting(rng, Number(m[0])))]);
        lines[i] = lines[i]!.slice(0, m.index) + value + lines[i]!.slice(m.index! + m[0].length);
      }
    }
  }
  return lines.join('\n');
}
