/**
 * MDL Molfiles (CTfile formats, BIOVIA 2020): the connection table of one molecule, V2000 or V3000.
 *
 *   line 1        name
 *   line 2        program, date, dimensions ("  -OEChem-07012107543D")
 *   line 3        comment
 *   line 4        counts line: aaabbb...                                      ...vvvvvv (V2000 | V3000)
 *   V2000:        atom block   xxxxx.xxxxyyyyy.yyyyzzzzz.zzzz aaa...  (columns 1-30, symbol 32-34)
 *                 bond block   111222ttt...                           (atom, atom, type)
 *                 properties   "M  CHG ...", ..., ended by "M  END"
 *   V3000:        "M  V30 BEGIN CTAB", "M  V30 COUNTS na nb ...", "M  V30 BEGIN ATOM" / index type x y z
 *                 aamap ... / "END ATOM", "BEGIN BOND" / index type atom1 atom2 ... / "END BOND",
 *                 other blocks (SGROUP, COLLECTION) skipped, "END CTAB", then "M  END"; a V30 line
 *                 ending in '-' continues on the next.
 *
 * V2000 is a fixed-column format (a counts line of 184 atoms and 192 bonds reads "184192"), so its
 * fields are cut by column. Every error names the file and the line: "caffeine.mol line 7: ...".
 */
import { Budget } from '../../budgets.ts';
import { LanternError } from '../../errors.ts';
import type { Vec3 } from '../../math/vec3.ts';
import { elementOf, type Element } from './elements.ts';
import { LineReader } from './lines.ts';

export interface Atom {
  readonly element: Element;
  /** Å. */
  readonly position: Vec3;
}

/**
 * MDL bond types: 1 single, 2 double, 3 triple, 4 aromatic, 5–8 query bonds (single or double,
 * single or aromatic, double or aromatic, any), V3000 adds 9 coordination and 10 hydrogen bond.
 */
export type BondType = 1 | 2 | 3 | 4 | 5 | 6 | 7 | 8 | 9 | 10;

export interface Bond {
  /** Indices into Molecule.atoms (0-based; the file counts from 1). */
  readonly a: number;
  readonly b: number;
  readonly type: BondType;
}

export interface Molecule {
  /** The header's first line, trimmed (may be empty). */
  readonly name: string;
  readonly version: 'V2000' | 'V3000';
  readonly atoms: readonly Atom[];
  readonly bonds: readonly Bond[];
  /** The 1-based line the molecule starts on (an SDF record's first line). */
  readonly firstLine: number;
}

/**
 * The lines of one SD record, read as they come: `next` ends (undefined) at the record's `$$$$` line
 * or at the end of the file. Blank lines before a record's first other line are counted, not kept, so
 * that a file of nothing but line breaks costs no memory.
 */
export class RecordLines {
  /** 0-based index of the record's first line. */
  readonly start: number;
  private blanks = 0;
  private held: string | undefined;
  private ended = false;
  /** Whether the record ended with the file (not at a `$$$$` line). */
  endOfFile = false;
  /** 0-based index of the line `next` returned last (start − 1 before the first). */
  index: number;

  constructor(private readonly lines: LineReader) {
    this.start = lines.index + 1;
    this.index = this.start - 1;
  }

  /** Skips leading blank lines: false when the record holds nothing else (blank space between or after records). */
  hasContent(): boolean {
    for (;;) {
      if (!this.ended) this.blanks += this.lines.skipBlankLines();
      const line = this.physical();
      if (line === undefined) return false;
      if (line.trim() !== '') {
        this.held = line;
        return true;
      }
      this.blanks++;
    }
  }

  next(): string | undefined {
    if (this.blanks > 0) {
      this.blanks--;
      this.index++;
      return '';
    }
    const line = this.held ?? this.physical();
    this.held = undefined;
    if (line !== undefined) this.index++;
    return line;
  }

  /** Reads past the rest of the record (an SD record's data items). */
  skipRest(): void {
    while (this.next() !== undefined);
  }

  private physical(): string | undefined {
    if (this.ended) return undefined;
    const line = this.lines.next();
    if (line === undefined || line.trim() === '$$$$') {
      this.ended = true;
      this.endOfFile = line === undefined;
      return undefined;
    }
    return line;
  }
}

/** The atoms and bonds one load may read (moleculeRecords, each), charged as counts lines ask for them. */
export interface MoleculeBudget {
  readonly atoms: Budget;
  readonly bonds: Budget;
}

export function moleculeBudget(source: string): MoleculeBudget {
  return { atoms: new Budget('moleculeRecords', `${source}: atoms`), bonds: new Budget('moleculeRecords', `${source}: bonds`) };
}

/** Reads a whole .mol file: one molecule; anything after `M  END` is ignored (as SDF data would be). */
export function parseMolfile(input: string | Uint8Array, source: string): Molecule {
  return parseMolBlock(new RecordLines(new LineReader(input, source)), source, moleculeBudget(source));
}

/**
 * Reads the molfile at the start of `record` (an SD record without its `$$$$`), up to and including
 * its `M  END`; what follows (an SD record's data items) is left unread.
 */
export function parseMolBlock(record: RecordLines, source: string, budget: MoleculeBudget): Molecule {
  const fail = (index: number, what: string, hint?: string): never => {
    throw new LanternError(`${source} line ${index + 1}: ${what}`, hint);
  };
  const start = record.start;
  const name = (record.next() ?? '').trim();
  record.next();
  record.next();
  const counts = record.next();
  if (counts === undefined) return fail(Math.max(start, record.index), 'the molfile ends before its counts line (line 4 of a molfile: atoms, bonds, version)');
  const countsAt = record.index;
  const version = counts.slice(33, 39).trim();
  if (version === 'V3000') {
    const { atoms, bonds } = readV3000(record, source, budget, fail);
    return { name, version: 'V3000', atoms, bonds, firstLine: start + 1 };
  }
  // Very old files leave the version out; anything else is not a molfile we know.
  if (version !== 'V2000' && version !== '') fail(countsAt, `bad counts line: version '${version}' in columns 34-39 is neither V2000 nor V3000`);
  const atomCount = countField(counts.slice(0, 3), 'atom', countsAt, fail);
  const bondCount = countField(counts.slice(3, 6), 'bond', countsAt, fail);
  budget.atoms.add(atomCount, `line ${countsAt + 1}`);
  budget.bonds.add(bondCount, `line ${countsAt + 1}`);

  const atoms: Atom[] = [];
  for (let i = 0; i < atomCount; i++) {
    const line = record.next();
    const at = record.index;
    if (line === undefined) return fail(at, `the molfile ends inside the atom block (${i} of ${atomCount} atoms read)`);
    if (line.startsWith('M  END')) fail(at, `'M  END' inside the atom block: the counts line promises ${atomCount} atoms, there are ${i}`);
    if (line.length < 32 || line.slice(31, 34).trim() === '') {
      fail(at, `atom line too short (${line.trimEnd().length} characters): a V2000 atom line has x, y, z in columns 1-30 and the element symbol in columns 32-34`);
    }
    const position: Vec3 = [
      coordinate(line.slice(0, 10), 'x', at, fail),
      coordinate(line.slice(10, 20), 'y', at, fail),
      coordinate(line.slice(20, 30), 'z', at, fail),
    ];
    atoms.push({ element: elementOf(line.slice(31, 34).trim(), `${source} line ${at + 1}`), position });
  }

  const bonds: Bond[] = [];
  for (let i = 0; i < bondCount; i++) {
    const line = record.next();
    const at = record.index;
    if (line === undefined) return fail(at, `the molfile ends inside the bond block (${i} of ${bondCount} bonds read)`);
    if (line.startsWith('M  END')) fail(at, `'M  END' inside the bond block: the counts line promises ${bondCount} bonds, there are ${i}`);
    if (line.length < 9) fail(at, `bond line too short (${line.trimEnd().length} characters): a V2000 bond line has the two atoms in columns 1-6 and the type in 7-9`);
    const a = integerField(line.slice(0, 3), 'first atom', at, fail);
    const b = integerField(line.slice(3, 6), 'second atom', at, fail);
    const type = integerField(line.slice(6, 9), 'bond type', at, fail);
    if (type < 1 || type > 8) fail(at, `bond type ${type} is not a V2000 bond type (1 single, 2 double, 3 triple, 4 aromatic, 5-8 query)`);
    bonds.push(bond(a, b, type as BondType, atomCount, (what) => fail(at, what)));
  }

  for (let line = record.next(); line !== undefined; line = record.next()) {
    if (line.startsWith('M  END')) return { name, version: 'V2000', atoms, bonds, firstLine: start + 1 };
  }
  return fail(record.index, "missing 'M  END': the molfile ends without it after its bond block");
}

type Fail = (index: number, what: string, hint?: string) => never;

function countField(text: string, noun: string, at: number, fail: Fail): number {
  if (!/^\s*\d+$/.test(text)) fail(at, `bad counts line: the ${noun} count '${text.trim()}' (columns ${noun === 'atom' ? '1-3' : '4-6'}) is not a number`);
  return Number(text);
}

function integerField(text: string, what: string, at: number, fail: Fail): number {
  if (!/^\s*-?\d+\s*$/.test(text)) fail(at, `the ${what} '${text.trim()}' is not a whole number`);
  return Number(text);
}

const NUMBER = /^\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\s*$/;

function coordinate(text: string, axis: string, at: number, fail: Fail): number {
  if (!NUMBER.test(text)) fail(at, `the ${axis} coordinate '${text.trim()}' is not a number`);
  return Number(text);
}

/** A bond between atoms numbered from 1, checked against the atom count. */
function bond(a: number, b: number, type: BondType, atomCount: number, fail: (what: string) => never): Bond {
  for (const n of [a, b]) {
    if (n < 1 || n > atomCount) fail(`bond to atom ${n}, but atoms are numbered 1 to ${atomCount}`);
  }
  if (a === b) fail(`bond from atom ${a} to itself`);
  return { a: a - 1, b: b - 1, type };
}

/** A V3000 logical line: its content after "M  V30 " (continuations joined) and where it began. */
interface V30Line {
  readonly text: string;
  readonly at: number;
}

/**
 * What is kept of one V3000 logical line. An atom's or a bond's fields come first and are short; what
 * lies past this is properties Lantern does not draw (an SGROUP's atom list may run to thousands of
 * numbers). Without a bound, a line continued over 100,000 lines was gathered whole, and re-joined
 * at each continuation (quadratic: over 60 s).
 */
export const MAX_V30_CHARACTERS = 1 << 16;

/** The V30 lines of a record, one logical line at a time, up to `M  END`; other property lines are skipped. */
class V30Lines {
  private ahead: V30Line | undefined;
  /** 0-based index of the `M  END` line, once reached. */
  endAt = -1;

  constructor(
    private readonly record: RecordLines,
    private readonly fail: Fail,
  ) {}

  peek(): V30Line | undefined {
    return (this.ahead ??= this.read());
  }

  take(): V30Line | undefined {
    const line = this.peek();
    this.ahead = undefined;
    return line;
  }

  private read(): V30Line | undefined {
    if (this.endAt >= 0) return undefined;
    for (;;) {
      const line = this.record.next();
      if (line === undefined) return this.fail(this.record.index, "missing 'M  END': the V3000 molfile ends without it");
      if (line.startsWith('M  END')) {
        this.endAt = this.record.index;
        return undefined;
      }
      if (!line.startsWith('M  V30 ')) continue; // other property lines carry nothing we draw
      const at = this.record.index;
      const first = line.slice(7).trimEnd();
      // Most lines are not continued: no pieces to gather.
      if (!first.endsWith('-')) return { text: first.slice(0, MAX_V30_CHARACTERS).trim(), at };
      const parts: string[] = [];
      let kept = 0;
      for (let piece = first; ; ) {
        const continued = piece.endsWith('-');
        const content = continued ? piece.slice(0, -1) : piece;
        if (kept < MAX_V30_CHARACTERS) {
          parts.push(content);
          kept += content.length;
        }
        if (!continued) break;
        const next = this.record.next();
        if (next === undefined || !next.startsWith('M  V30 ')) this.fail(this.record.index - (next === undefined ? 0 : 1), "a V3000 line ends in '-' but no 'M  V30' line continues it");
        piece = next!.slice(7).trimEnd();
      }
      return { text: parts.join('').slice(0, MAX_V30_CHARACTERS).trim(), at };
    }
  }
}

function readV3000(record: RecordLines, source: string, budget: MoleculeBudget, fail: Fail): { atoms: Atom[]; bonds: Bond[] } {
  const v30 = new V30Lines(record, fail);
  const expect = (keyword: string): V30Line => {
    const line = v30.take();
    if (!line) return fail(v30.endAt, `missing 'M  V30 ${keyword}' before 'M  END'`);
    if (line.text.toUpperCase() !== keyword && !line.text.toUpperCase().startsWith(`${keyword} `)) fail(line.at, `expected 'M  V30 ${keyword}', found 'M  V30 ${line.text}'`);
    return line;
  };

  expect('BEGIN CTAB');
  const countsLine = expect('COUNTS');
  const countTokens = tokens(countsLine.text).slice(1);
  const atomCount = countTokens[0] !== undefined && /^\d+$/.test(countTokens[0]) ? Number(countTokens[0]) : fail(countsLine.at, `bad COUNTS line: the atom count '${countTokens[0] ?? ''}' is not a number`);
  const bondCount = countTokens[1] !== undefined && /^\d+$/.test(countTokens[1]) ? Number(countTokens[1]) : fail(countsLine.at, `bad COUNTS line: the bond count '${countTokens[1] ?? ''}' is not a number`);
  // Charged before the blocks are read; the blocks may then hold no more than COUNTS says.
  budget.atoms.add(atomCount, `line ${countsLine.at + 1}`);
  budget.bonds.add(bondCount, `line ${countsLine.at + 1}`);

  const atoms: Atom[] = [];
  const atomById = new Map<number, number>();
  const bonds: Bond[] = [];
  let sawAtoms = false;
  let sawBonds = false;
  for (;;) {
    const line = v30.peek();
    if (!line) return fail(v30.endAt, "missing 'M  V30 END CTAB' before 'M  END'");
    const upper = line.text.toUpperCase();
    if (upper === 'END CTAB') {
      v30.take();
      break;
    }
    if (upper === 'BEGIN ATOM') {
      v30.take();
      sawAtoms = true;
      for (let line = v30.peek(); line && line.text.toUpperCase() !== 'END ATOM'; line = v30.peek()) {
        v30.take();
        if (atoms.length === atomCount) fail(line.at, `the atom block has more atoms than the ${atomCount} COUNTS says`);
        const [id, symbol, x, y, z] = tokens(line.text);
        if (id === undefined || !/^\d+$/.test(id) || Number(id) < 1) fail(line.at, `atom index '${id ?? ''}' is not a positive whole number`);
        if (z === undefined) fail(line.at, 'atom line too short: a V3000 atom line is "index type x y z aamap"');
        const position: Vec3 = [coordinate(x!, 'x', line.at, fail), coordinate(y!, 'y', line.at, fail), coordinate(z, 'z', line.at, fail)];
        if (atomById.has(Number(id))) fail(line.at, `atom index ${id} appears twice`);
        atomById.set(Number(id), atoms.length);
        atoms.push({ element: elementOf(unquote(symbol!), `${source} line ${line.at + 1}`), position });
      }
      expect('END ATOM');
      if (atoms.length !== atomCount) fail(line.at, `the atom block has ${atoms.length} atoms but COUNTS says ${atomCount}`);
      continue;
    }
    if (upper === 'BEGIN BOND') {
      v30.take();
      sawBonds = true;
      for (let line = v30.peek(); line && line.text.toUpperCase() !== 'END BOND'; line = v30.peek()) {
        v30.take();
        if (bonds.length === bondCount) fail(line.at, `the bond block has more bonds than the ${bondCount} COUNTS says`);
        const [, typeText, aText, bText] = tokens(line.text);
        if (bText === undefined) fail(line.at, 'bond line too short: a V3000 bond line is "index type atom1 atom2"');
        const type = integerField(typeText!, 'bond type', line.at, fail);
        if (type < 1 || type > 10) fail(line.at, `bond type ${type} is not a V3000 bond type (1 single, 2 double, 3 triple, 4 aromatic, 5-8 query, 9 coordination, 10 hydrogen)`);
        const ends = [aText!, bText].map((t) => {
          const n = integerField(t, 'bond atom', line.at, fail);
          const index = atomById.get(n);
          return index === undefined ? fail(line.at, `bond to atom ${n}, which the atom block does not have`) : index;
        }) as [number, number];
        if (ends[0] === ends[1]) fail(line.at, `bond from atom ${aText} to itself`);
        bonds.push({ a: ends[0], b: ends[1], type: type as BondType });
      }
      expect('END BOND');
      if (bonds.length !== bondCount) fail(line.at, `the bond block has ${bonds.length} bonds but COUNTS says ${bondCount}`);
      continue;
    }
    if (upper.startsWith('BEGIN ')) {
      // SGROUP, COLLECTION, OBJ3D, ...: nothing to draw; skip to the matching END.
      const end = `END ${upper.slice(6)}`;
      v30.take();
      // Lengths first: the block may run to millions of lines, and most are not its end.
      for (let line = v30.peek(); line && !(line.text.length === end.length && line.text.toUpperCase() === end); line = v30.peek()) v30.take();
      expect(end);
      continue;
    }
    v30.take(); // a line outside any block (LINKNODE, ...): nothing to draw
  }
  if (!sawAtoms && atomCount > 0) fail(countsLine.at, `COUNTS says ${atomCount} atoms but there is no atom block`);
  if (!sawBonds && bondCount > 0) fail(countsLine.at, `COUNTS says ${bondCount} bonds but there is no bond block`);
  // What follows END CTAB up to M  END carries nothing we draw.
  while (v30.take());
  return { atoms, bonds };
}

/** Whitespace-separated fields; a field in double quotes may hold spaces ("" is a quote). */
function tokens(text: string): string[] {
  const out: string[] = [];
  const re = /"((?:[^"]|"")*)"|(\S+)/g;
  for (let m = re.exec(text); m; m = re.exec(text)) out.push(m[1] !== undefined ? `"${m[1]}"` : m[2]!);
  return out;
}

function unquote(field: string): string {
  return field.startsWith('"') && field.endsWith('"') ? field.slice(1, -1).replaceAll('""', '"') : field;
}
