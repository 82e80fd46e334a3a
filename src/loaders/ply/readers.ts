/**
 * Sequential value readers over a PLY body, one per encoding, behind one interface so the element
 * loops in ply.ts are written once. Both are hot (the ASCII dragon is 33 MB, ~5 million values), so
 * they work on raw bytes: no string splitting, no per-value allocation.
 */
import { SCALAR_SIZE, type PlyListProperty, type PlyScalarType } from './header.ts';

/** Thrown when the body ends before a value; the element loop turns it into a LanternError with context. */
export class PlyEndOfData extends Error {}

/** Thrown for an ASCII token that is not a number; `detail` says which and where. */
export class PlyBadValue extends Error {
  constructor(readonly detail: string) {
    super(detail);
  }
}

export interface ValueReader {
  /** Next value of the given type, as a JS number. */
  read(type: PlyScalarType): number;
  /** Skips `n` values of the given type. */
  skip(type: PlyScalarType, n: number): void;
  /** Bytes left; every value takes at least one, which bounds any count read from the file. */
  readonly remaining: number;
  pos: number;
}

/** A list's entry count: a non-negative integer whatever the declared count type. */
export function readListCount(reader: ValueReader, p: PlyListProperty): number {
  const n = reader.read(p.countType);
  if (!Number.isInteger(n) || n < 0) throw new PlyBadValue(`list '${p.name}' has an invalid entry count ${n}`);
  // Checked here so that no caller sizes a buffer from a count the data cannot back.
  if (n > reader.remaining) throw new PlyEndOfData();
  return n;
}

/** One binary value; small enough that V8 inlines it and folds the switch in monomorphic loops. */
export function getScalar(view: DataView, offset: number, type: PlyScalarType, little: boolean): number {
  switch (type) {
    case 'int8': return view.getInt8(offset);
    case 'uint8': return view.getUint8(offset);
    case 'int16': return view.getInt16(offset, little);
    case 'uint16': return view.getUint16(offset, little);
    case 'int32': return view.getInt32(offset, little);
    case 'uint32': return view.getUint32(offset, little);
    case 'float32': return view.getFloat32(offset, little);
    case 'float64': return view.getFloat64(offset, little);
  }
}

export class BinaryReader implements ValueReader {
  readonly view: DataView;

  constructor(
    bytes: Uint8Array,
    public pos: number,
    readonly little: boolean,
  ) {
    this.view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  }

  get remaining(): number {
    return this.view.byteLength - this.pos;
  }

  read(type: PlyScalarType): number {
    const p = this.pos;
    const size = SCALAR_SIZE[type];
    if (p + size > this.view.byteLength) throw new PlyEndOfData();
    this.pos = p + size;
    return getScalar(this.view, p, type, this.little);
  }

  skip(type: PlyScalarType, n: number): void {
    const end = this.pos + n * SCALAR_SIZE[type];
    if (end > this.view.byteLength) throw new PlyEndOfData();
    this.pos = end;
  }
}

/** Exact powers of ten: with them, mantissa (≤ 15 digits) ÷ or × 10^k is one correctly rounded operation. */
const POW10 = Array.from({ length: 23 }, (_, k) => Number(`1e${k}`));

const isSpace = (c: number): boolean => c <= 0x20; // space, tab, \r, \n, and other control bytes

export class AsciiReader implements ValueReader {
  constructor(
    private readonly bytes: Uint8Array,
    public pos: number,
  ) {}

  get remaining(): number {
    return this.bytes.length - this.pos;
  }

  /** ASCII values are text whatever the declared type; integer-ness is checked where it matters. */
  read(_type: PlyScalarType): number {
    const b = this.bytes, n = b.length;
    let p = this.pos;
    while (p < n && isSpace(b[p]!)) p++;
    if (p >= n) throw new PlyEndOfData();
    const start = p;
    let c = b[p]!;
    const negative = c === 0x2d;
    if (c === 0x2d || c === 0x2b) c = b[++p] ?? 0;
    // Clinger's fast path: accumulate up to 15 significant digits exactly, then scale once.
    let mantissa = 0, significant = 0, exponent = 0, digits = 0;
    while (c >= 0x30 && c <= 0x39) {
      mantissa = mantissa * 10 + (c - 0x30);
      if (mantissa !== 0) significant++;
      digits++;
      c = b[++p] ?? 0;
    }
    if (c === 0x2e) {
      c = b[++p] ?? 0;
      while (c >= 0x30 && c <= 0x39) {
        mantissa = mantissa * 10 + (c - 0x30);
        if (mantissa !== 0) significant++;
        digits++;
        exponent--;
        c = b[++p] ?? 0;
      }
    }
    if (digits > 0 && (c === 0x65 || c === 0x45)) {
      c = b[++p] ?? 0;
      const expNegative = c === 0x2d;
      if (c === 0x2d || c === 0x2b) c = b[++p] ?? 0;
      let e = 0, expDigits = 0;
      while (c >= 0x30 && c <= 0x39) {
        if (e < 100_000) e = e * 10 + (c - 0x30);
        expDigits++;
        c = b[++p] ?? 0;
      }
      if (expDigits === 0) return this.slowToken(start);
      exponent += expNegative ? -e : e;
    }
    if (digits === 0 || (p < n && !isSpace(c)) || significant > 15 || exponent < -22 || exponent > 22) {
      return this.slowToken(start);
    }
    this.pos = p;
    const value = exponent < 0 ? mantissa / POW10[-exponent]! : mantissa * POW10[exponent]!;
    return negative ? -value : value;
  }

  skip(_type: PlyScalarType, count: number): void {
    const b = this.bytes, n = b.length;
    let p = this.pos;
    for (let i = 0; i < count; i++) {
      while (p < n && isSpace(b[p]!)) p++;
      if (p >= n) throw new PlyEndOfData();
      while (p < n && !isSpace(b[p]!)) p++;
    }
    this.pos = p;
  }

  /** 1-based line number of a byte offset, for error messages only (it rescans the body). */
  lineAt(offset: number): number {
    let line = 1;
    for (let i = 0; i < offset && i < this.bytes.length; i++) if (this.bytes[i] === 0x0a) line++;
    return line;
  }

  /** Long mantissas, big exponents, nan/inf and garbage: let the engine's exact parser decide. */
  private slowToken(start: number): number {
    const b = this.bytes;
    let p = start;
    while (p < b.length && !isSpace(b[p]!)) p++;
    let token = '';
    for (let i = start; i < p && i - start < 400; i++) token += String.fromCharCode(b[i]!);
    // A token this long is no number a writer would produce; refuse it rather than parse a prefix.
    const value = p - start >= 400 ? NaN : Number(token);
    if (Number.isNaN(value) && !/^[+-]?nan$/i.test(token)) {
      if (/^[+-]?inf(inity)?$/i.test(token)) {
        this.pos = p;
        return token.startsWith('-') ? -Infinity : Infinity;
      }
      const shown = token.length > 40 ? `${token.slice(0, 40)}…` : token;
      throw new PlyBadValue(`line ${this.lineAt(start)}: '${shown}' is not a number`);
    }
    this.pos = p;
    return value;
  }
}
