/**
 * SD files (CTfile formats, BIOVIA 2020, "SDfile"): records separated by a `$$$$` line, each a molfile
 * (molfile.ts) followed by data items (`> <NAME>` then value lines, up to a blank line). A .mol file is
 * read the same way: one record, no separator. Data items are not drawn and are skipped.
 */
import { LanternError } from '../../errors.ts';
import { parseMolBlock, splitLines, type Molecule } from './molfile.ts';

/** Every record of an SD file (or the one molecule of a .mol file), in order. */
export function parseSdf(text: string, source: string): Molecule[] {
  const lines = splitLines(text);
  const molecules: Molecule[] = [];
  let start = 0;
  for (let at = 0; at <= lines.length; at++) {
    if (at < lines.length && lines[at]!.trim() !== '$$$$') continue;
    // lines[start, at) is one record; blank space between or after records is not one.
    if (lines.slice(start, at).some((l) => l.trim() !== '')) molecules.push(parseMolBlock(lines, start, at, source).molecule);
    start = at + 1;
  }
  if (molecules.length === 0) throw new LanternError(`${source} holds no molecule`, 'A molfile starts with three header lines and a counts line ending in V2000 or V3000');
  return molecules;
}
