/**
 * The PLY header: the ASCII preamble that declares the body's format and, element by element, the
 * properties of each record. Everything after `end_header` is interpreted only through this.
 */
import { LanternError } from '../../errors.ts';

export type PlyFormat = 'ascii' | 'binary_little_endian' | 'binary_big_endian';

export type PlyScalarType = 'int8' | 'uint8' | 'int16' | 'uint16' | 'int32' | 'uint32' | 'float32' | 'float64';

export interface PlyScalarProperty {
  readonly kind: 'scalar';
  readonly name: string;
  readonly type: PlyScalarType;
}

export interface PlyListProperty {
  readonly kind: 'list';
  readonly name: string;
  /** Type of the leading entry count; always an integer type. */
  readonly countType: PlyScalarType;
  readonly itemType: PlyScalarType;
}

export type PlyProperty = PlyScalarProperty | PlyListProperty;

export interface PlyElement {
  readonly name: string;
  readonly count: number;
  readonly properties: readonly PlyProperty[];
}

export interface PlyHeader {
  readonly format: PlyFormat;
  readonly elements: readonly PlyElement[];
  readonly comments: readonly string[];
  /** Byte offset of the first body byte (just past the `end_header` line). */
  readonly bodyOffset: number;
}

/** Both the old C names and the sized names from the PLY spec's later revision. */
const TYPE_NAMES: Readonly<Record<string, PlyScalarType>> = {
  char: 'int8', int8: 'int8', uchar: 'uint8', uint8: 'uint8',
  short: 'int16', int16: 'int16', ushort: 'uint16', uint16: 'uint16',
  int: 'int32', int32: 'int32', uint: 'uint32', uint32: 'uint32',
  float: 'float32', float32: 'float32', double: 'float64', float64: 'float64',
};

export const SCALAR_SIZE: Readonly<Record<PlyScalarType, number>> = {
  int8: 1, uint8: 1, int16: 2, uint16: 2, int32: 4, uint32: 4, float32: 4, float64: 8,
};

export const isIntegerType = (t: PlyScalarType): boolean => t !== 'float32' && t !== 'float64';

/**
 * A real header is a few hundred bytes; long comment blocks exist, but a header over this size means we
 * are reading something that is not a PLY file and should stop looking for `end_header`.
 */
export const MAX_HEADER_BYTES = 1 << 20;

export function parsePlyHeader(bytes: Uint8Array, name: string): PlyHeader {
  const lines = splitHeaderLines(bytes, name);
  let format: PlyFormat | undefined;
  const elements: { name: string; count: number; properties: PlyProperty[] }[] = [];
  const comments: string[] = [];

  for (let i = 1; i < lines.text.length; i++) {
    const line = lines.text[i]!;
    const lineNo = i + 1;
    const words = line.trim().split(/\s+/);
    const bad = (what: string, hint?: string): never => {
      throw new LanternError(`${name}: PLY header line ${lineNo} ('${line.trim()}') ${what}`, hint);
    };
    switch (words[0]) {
      case '': // blank lines carry nothing; some writers emit them
        break;
      case 'comment':
      case 'obj_info':
        comments.push(line.trim().slice(words[0].length).trim());
        break;
      case 'format': {
        if (format) bad('repeats the format');
        const f = words[1];
        if (f !== 'ascii' && f !== 'binary_little_endian' && f !== 'binary_big_endian') {
          bad(`has unsupported format '${f ?? ''}'`, 'Lantern reads ascii, binary_little_endian and binary_big_endian');
        }
        if (words[2] !== '1.0' && words[2] !== '1') bad(`has unsupported version '${words[2] ?? ''}'`, 'Lantern reads PLY 1.0');
        format = f as PlyFormat;
        break;
      }
      case 'element': {
        const count = Number(words[2]);
        if (words.length !== 3 || !Number.isSafeInteger(count) || count < 0) bad('is not \'element <name> <count>\'');
        elements.push({ name: words[1]!, count, properties: [] });
        break;
      }
      case 'property': {
        const element = elements[elements.length - 1] ?? bad('declares a property before any element');
        element.properties.push(parseProperty(words, bad));
        break;
      }
      default:
        bad(`has an unknown keyword '${words[0]}'`);
    }
  }
  if (!format) throw new LanternError(`${name}: the PLY header has no 'format' line`);
  return { format, elements, comments, bodyOffset: lines.bodyOffset };
}

function parseProperty(words: string[], bad: (what: string, hint?: string) => never): PlyProperty {
  const type = (w: string | undefined): PlyScalarType =>
    TYPE_NAMES[w ?? ''] ?? bad(`has unknown type '${w ?? ''}'`, `known types: ${Object.keys(TYPE_NAMES).join(', ')}`);
  if (words[1] === 'list') {
    if (words.length !== 5) bad("is not 'property list <count type> <item type> <name>'");
    const countType = type(words[2]);
    if (!isIntegerType(countType)) bad('has a non-integer list count type');
    return { kind: 'list', name: words[4]!, countType, itemType: type(words[3]) };
  }
  if (words.length !== 3) bad("is not 'property <type> <name>'");
  return { kind: 'scalar', name: words[2]!, type: type(words[1]) };
}

/**
 * Splits the header into lines (accepting \n, \r\n and lone \r endings) and finds where the body
 * starts: immediately after the line terminator of `end_header`.
 */
function splitHeaderLines(bytes: Uint8Array, name: string): { text: string[]; bodyOffset: number } {
  const notPly = (): never => {
    throw new LanternError(`${name}: not a PLY file (it does not start with 'ply')`, 'check the file name and contents');
  };
  if (bytes[0] !== 0x70 || bytes[1] !== 0x6c || bytes[2] !== 0x79) notPly(); // "ply"
  const text: string[] = [];
  const limit = Math.min(bytes.length, MAX_HEADER_BYTES);
  let start = 0;
  for (let i = 0; i < limit; i++) {
    const c = bytes[i]!;
    if (c !== 0x0a && c !== 0x0d) continue;
    const line = latin1(bytes, start, i);
    text.push(line);
    // \r\n counts as one terminator; a lone \r (old Mac writers) as one too.
    const end = c === 0x0d && bytes[i + 1] === 0x0a ? i + 2 : i + 1;
    if (text.length === 1 && line.trim() !== 'ply') notPly();
    if (line.trim() === 'end_header') return { text: text.slice(0, -1), bodyOffset: end };
    start = end;
    i = end - 1;
  }
  if (text.length === 0) notPly();
  throw new LanternError(
    bytes.length > MAX_HEADER_BYTES
      ? `${name}: no 'end_header' line in the first ${MAX_HEADER_BYTES} bytes`
      : `${name}: the PLY header is truncated (no 'end_header' line)`,
  );
}

function latin1(bytes: Uint8Array, start: number, end: number): string {
  let s = '';
  for (let i = start; i < end; i++) s += String.fromCharCode(bytes[i]!);
  return s;
}
