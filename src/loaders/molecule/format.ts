/**
 * The molecule entry of the loader registry: MDL molfiles (.mol, V2000 and V3000) and SD files (.sdf,
 * .sd: several molfiles separated by `$$$$`), recognised by the counts line (line 4, ending in V2000
 * or V3000 in columns 34-39).
 *
 * What `#` picks (a part, noun 'model'): a record and a style. For a file of one molecule the parts
 * are the styles, `caffeine.mol#ball-and-stick` (the default) and `caffeine.mol#space-filling`; for an
 * SD file of several they are `<record>` (ball-and-stick) and `<record>:space-filling`, where a
 * record is named by its title line (or by its number, when the title is empty, a number or shared
 * with another record). `partNamed` also takes a record's number, its title and an explicit
 * `:ball-and-stick`, so `drugs.sdf#2` and `drugs.sdf#aspirin:space-filling` both work. The page's
 * link parameter is `model=`, and its picker lists the parts.
 */
import { LanternError } from '../../errors.ts';
import type { OpenedScene, SceneFormat, ScenePart } from '../format.ts';
import type { Molecule } from './molfile.ts';
import { parseSdf } from './sdf.ts';
import { DEFAULT_MOLECULE_STYLE, hillFormula, MOLECULE_STYLES, moleculeScene, type MoleculeStyle } from './to-scene.ts';

const EXTENSION = /\.(mol|sdf|sd)$/i;

/** True when line 4 of the head is a molfile counts line. */
export function isMoleculeHead(head: Uint8Array): boolean {
  // Latin-1 decoding: a byte per character, so columns are bytes whatever the encoding.
  const text = String.fromCharCode(...head.subarray(0, 4096));
  const counts = text.split(/\r\n|\r|\n/)[3];
  if (counts === undefined || !/^[ \d]{6}/.test(counts)) return false;
  const version = counts.slice(33, 39).trim();
  return (version === 'V2000' || version === 'V3000') && counts.slice(39).trim() === '';
}

export const MOLECULE_FORMAT: SceneFormat = {
  id: 'molfile',
  kind: 'scene',
  description: 'MDL molecules',
  extensions: ['.mol', '.sdf', '.sd'],
  sniff: isMoleculeHead,
  linkParam: 'mol',
  stacks: false,
  example: 'caffeine.mol#space-filling',
  part: { noun: 'model', linkParam: 'model' },
  parseReference(argument) {
    // A '#' inside a path that itself ends in the extension is not a fragment.
    if (EXTENSION.test(argument)) return { paths: [argument] };
    const hash = argument.lastIndexOf('#');
    if (hash < 0 || !EXTENSION.test(argument.slice(0, hash))) return undefined;
    const part = argument.slice(hash + 1);
    return { paths: [argument.slice(0, hash)], ...(part ? { part } : {}) };
  },
  // async so that a bad file rejects the promise instead of throwing before there is one.
  async open(set) {
    // One file by construction (stacks: false).
    const file = set.files[0]!;
    const molecules = parseSdf(file.bytes, file.name);
    return openMolecules(file.name, molecules);
  },
};

interface Model {
  readonly record: number;
  readonly style: MoleculeStyle;
}

/** The parts of a file of molecules and their scenes (exported for the built-in caffeine scene and tests). */
export function openMolecules(fileName: string, molecules: readonly Molecule[]): OpenedScene {
  const single = molecules.length === 1;
  const labels = recordLabels(molecules);
  const nameOf = ({ record, style }: Model) => (single ? style : style === DEFAULT_MOLECULE_STYLE ? labels[record]! : `${labels[record]}:${style}`);
  const models: Model[] = molecules.flatMap((_, record) => MOLECULE_STYLES.map((style) => ({ record, style })));
  const parts: ScenePart[] = models.map((m) => ({ name: nameOf(m), loadable: true }));

  const find = (selector: string): Model | undefined => {
    if ((MOLECULE_STYLES as readonly string[]).includes(selector)) return { record: 0, style: selector as MoleculeStyle };
    const suffix = MOLECULE_STYLES.find((s) => selector.endsWith(`:${s}`));
    const style = suffix ?? DEFAULT_MOLECULE_STYLE;
    const recordSelector = suffix ? selector.slice(0, -suffix.length - 1) : selector;
    let record = labels.indexOf(recordSelector);
    if (record < 0) record = molecules.findIndex((m) => m.name !== '' && m.name === recordSelector);
    if (record < 0 && /^\d+$/.test(recordSelector) && Number(recordSelector) >= 1 && Number(recordSelector) <= molecules.length) record = Number(recordSelector) - 1;
    return record < 0 ? undefined : { record, style };
  };

  return {
    description: fileName,
    parts,
    partNamed: (selector) => {
      const model = find(selector);
      return model ? nameOf(model) : undefined;
    },
    async scene(part) {
      const model = part === undefined ? models[0]! : find(part);
      if (!model) throw new LanternError(`${fileName} has no model '${part}'`, `Its models are: ${parts.slice(0, 12).map((p) => p.name).join(', ')}${parts.length > 12 ? ', ...' : ''}`);
      const name = part === undefined ? fileName : `${fileName}#${nameOf(model)}`;
      return moleculeScene(molecules[model.record]!, model.style, name);
    },
    inventory() {
      const rows = molecules.map((m, i) => ({
        index: i + 1,
        name: m.name,
        part: labels[i]!,
        version: m.version,
        atoms: m.atoms.length,
        bonds: m.bonds.length,
        bondOrders: bondOrders(m),
        formula: hillFormula(m),
      }));
      const orders = (o: Record<string, number>) => Object.entries(o).map(([k, n]) => `${n} ${k}`).join(', ');
      const lines = [
        `${fileName}: ${molecules.length === 1 ? '1 molecule' : `${molecules.length} molecules`}; styles ${MOLECULE_STYLES.join(', ')} (pick with #${single ? 'style' : 'record:style'})`,
        ...rows.map((r) => `  ${String(r.index).padStart(3)}  ${(r.name || '(no name)').padEnd(20)} ${r.formula.padEnd(14)} ${String(r.atoms).padStart(5)} atoms ${String(r.bonds).padStart(5)} bonds (${orders(r.bondOrders)}), ${r.version}`),
      ];
      return { lines, json: { file: fileName, styles: MOLECULE_STYLES, molecules: rows } };
    },
  };
}

/**
 * How each record is named in a part: its title, unless the title is empty, all digits (it would
 * read as a record number), contains ':' or '#', or is shared with another record; then its number.
 */
function recordLabels(molecules: readonly Molecule[]): string[] {
  const count = new Map<string, number>();
  for (const m of molecules) count.set(m.name, (count.get(m.name) ?? 0) + 1);
  return molecules.map((m, i) => (m.name === '' || /^\d+$/.test(m.name) || /[:#]/.test(m.name) || count.get(m.name)! > 1 ? String(i + 1) : m.name));
}

const ORDER_NAMES: Record<number, string> = { 1: 'single', 2: 'double', 3: 'triple', 4: 'aromatic', 9: 'coordination', 10: 'hydrogen' };

function bondOrders(molecule: Molecule): Record<string, number> {
  const counts = new Map<string, number>();
  for (const b of molecule.bonds) {
    const name = ORDER_NAMES[b.type] ?? 'query';
    counts.set(name, (counts.get(name) ?? 0) + 1);
  }
  // In the order of the names (single, double, ...), whatever order the file lists bonds in.
  return Object.fromEntries([...Object.values(ORDER_NAMES), 'query'].filter((n) => counts.has(n)).map((n) => [n, counts.get(n)!]));
}
