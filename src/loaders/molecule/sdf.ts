/**
 * SD files (CTfile formats, BIOVIA 2020, "SDfile"): records separated by a `$$$$` line, each a molfile
 * (molfile.ts) followed by data items (`> <NAME>` then value lines, up to a blank line). A .mol file is
 * read the same way: one record, no separator. Data items are not drawn and are skipped. The file is
 * read a line at a time (lines.ts); the atoms and bonds of all its records together are charged to
 * the moleculeRecords limit as their counts lines ask for them.
 */
import { LanternError } from '../../errors.ts';
import { LineReader } from './lines.ts';
import { moleculeBudget, parseMolBlock, RecordLines, type Molecule } from './molfile.ts';

/** Every record of an SD file (or the one molecule of a .mol file), in order. */
export function parseSdf(input: string | Uint8Array, source: string): Molecule[] {
  const lines = new LineReader(input, source);
  const budget = moleculeBudget(source);
  const molecules: Molecule[] = [];
  for (let record = new RecordLines(lines); ; record = new RecordLines(lines)) {
    // Blank space between or after records is not one.
    if (record.hasContent()) {
      molecules.push(parseMolBlock(record, source, budget));
      record.skipRest();
    }
    if (record.endOfFile) break;
  }
  if (molecules.length === 0) throw new LanternError(`${source} holds no molecule`, 'A molfile starts with three header lines and a counts line ending in V2000 or V3000');
  return molecules;
}
