import { existsSync, readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../../expect-lantern-error.ts';
import { add, cross, dot, length, normalize, scale, sub, type Vec3 } from '../../math/vec3.ts';
import type { Mesh } from '../../scene/types.ts';
import { CAFFEINE_MOL } from './caffeine.ts';
import { ELEMENTS, findElement, linearColor } from './elements.ts';
import { isMoleculeHead, MOLECULE_FORMAT } from './format.ts';
import { parseMolfile } from './molfile.ts';
import { parseSdf } from './sdf.ts';
import { LineReader } from './lines.ts';
import { atomRadius, BOND_RADIUS, bondCapsules, hillFormula, moleculeMesh, moleculeScene } from './to-scene.ts';

const fixture = (name: string) => new URL(`../../../tests/fixtures/${name}`, import.meta.url);
const CAFFEINE_V3000 = readFileSync(fixture('caffeine-v3000.mol'), 'utf8');
const caffeine = () => parseMolfile(CAFFEINE_MOL, 'caffeine.mol');
const lines = CAFFEINE_MOL.split('\n');
/** The caffeine text with line `n` (1-based) replaced. */
const withLine = (n: number, text: string) => lines.map((l, i) => (i === n - 1 ? text : l)).join('\n');
const bytes = (text: string) => new TextEncoder().encode(text);
const point = (a: Float32Array, i: number): Vec3 => [a[i]!, a[i + 1]!, a[i + 2]!];

/** The distance from p to the segment a-b. */
function distanceToSegment(p: Vec3, a: Vec3, b: Vec3): number {
  const ab = sub(b, a);
  const t = Math.max(0, Math.min(1, dot(sub(p, a), ab) / dot(ab, ab)));
  return length(sub(p, add(a, scale(ab, t))));
}

describe('caffeine', () => {
  it('the fixture file and the built-in text are the same molfile', () => {
    expect(readFileSync(fixture('caffeine.mol'), 'utf8')).toBe(CAFFEINE_MOL);
  });

  it('parses 24 atoms, C8H10N4O2, and 25 bonds of which 4 double (two C=O, C=C and C=N)', () => {
    const m = caffeine();
    expect(m.name).toBe('caffeine');
    expect(m.version).toBe('V2000');
    expect(m.atoms).toHaveLength(24);
    expect(m.bonds).toHaveLength(25);
    expect(hillFormula(m)).toBe('C8H10N4O2');
    const doubles = m.bonds.filter((b) => b.type === 2).map((b) => [m.atoms[b.a]!.element.symbol, m.atoms[b.b]!.element.symbol].sort().join('='));
    expect(doubles.sort()).toEqual(['C=C', 'C=N', 'C=O', 'C=O']);
    // Atom 1 (O) at PubChem's coordinates; bond 1 joins atoms 1 and 9 (0-based 0 and 8).
    expect(m.atoms[0]!.position).toEqual([0.47, 2.5688, 0.0006]);
    expect(m.bonds[0]).toEqual({ a: 0, b: 8, type: 2 });
  });

  it('every bond is as long as the covalent radii say (within 0.15 Å): coordinates and bonds agree', () => {
    const m = caffeine();
    for (const b of m.bonds) {
      const [p, q] = [m.atoms[b.a]!, m.atoms[b.b]!];
      const d = length(sub(p.position, q.position));
      const single = p.element.covalent + q.element.covalent;
      // Double bonds are shorter than the single-bond radii add up to.
      expect(d).toBeLessThan(single + 0.15);
      expect(d).toBeGreaterThan(single - (b.type === 2 ? 0.3 : 0.15));
    }
  });

  it('the V3000 file (with a continued line) gives the same molecule and the same scene', () => {
    const v3 = parseMolfile(CAFFEINE_V3000, 'caffeine-v3000.mol');
    const v2 = caffeine();
    expect(v3.version).toBe('V3000');
    expect(v3.atoms).toEqual(v2.atoms);
    expect(v3.bonds).toEqual(v2.bonds);
    expect(moleculeScene(v3, 'ball-and-stick', 'c')).toEqual(moleculeScene(v2, 'ball-and-stick', 'c'));
  });
});

describe('molecule to spheres and capsules', () => {
  it('ball-and-stick: half covalent radii (at least 1.5 bond radii); space-filling: van der Waals radii', () => {
    const m = caffeine();
    for (const style of ['ball-and-stick', 'space-filling'] as const) {
      const { mesh } = moleculeMesh(m, style);
      expect(mesh.indices).toHaveLength(0);
      expect(mesh.spheres!.radii).toHaveLength(24);
      m.atoms.forEach((atom, i) => {
        const expected = style === 'space-filling' ? atom.element.vdw : Math.max(atom.element.covalent / 2, 1.5 * BOND_RADIUS);
        expect(mesh.spheres!.radii[i]).toBeCloseTo(expected, 6);
        expect(point(mesh.spheres!.centers, 3 * i)).toEqual(atom.position.map(Math.fround));
      });
    }
    const carbon = findElement('C')!, hydrogen = findElement('H')!;
    expect(atomRadius(carbon, 'space-filling')).toBe(1.7);
    expect(atomRadius(hydrogen, 'space-filling')).toBe(1.2);
    expect(atomRadius(carbon, 'ball-and-stick')).toBeCloseTo(0.38);
    expect(atomRadius(hydrogen, 'ball-and-stick')).toBeCloseTo(1.5 * BOND_RADIUS);
  });

  it('space-filling draws no bonds; ball-and-stick draws 21 single + 2 × 4 double = 29 capsules', () => {
    expect(moleculeMesh(caffeine(), 'space-filling').mesh.capsules).toBeUndefined();
    expect(moleculeMesh(caffeine(), 'ball-and-stick').mesh.capsules!.radii).toHaveLength(21 + 2 * 4);
  });

  it('each atom has its element colour; bonds share one grey material', () => {
    const m = caffeine();
    const { mesh, materials } = moleculeMesh(m, 'ball-and-stick');
    expect(materials.map((x) => x.name)).toEqual(['O', 'N', 'C', 'H', 'bond']);
    m.atoms.forEach((atom, i) => {
      const material = materials[mesh.spheres!.materialIds[i]!]!;
      expect(material.kind === 'metallic-roughness' && material.baseColor).toEqual(linearColor(atom.element));
    });
    expect(new Set(mesh.capsules!.materialIds)).toEqual(new Set([4]));
  });

  it('a single bond is one capsule from atom centre to atom centre', () => {
    const m = caffeine();
    const { mesh } = moleculeMesh(m, 'ball-and-stick');
    const capsules = mesh.capsules!;
    // Capsules come in bond order: bond 3 (atoms 3-8) is the first single one, after two doubles.
    const first = m.bonds.findIndex((b) => b.type === 1);
    expect(first).toBe(2);
    const bond = m.bonds[first]!;
    const k = 2 * 2; // two capsules per double bond before it
    expect(point(capsules.endpoints, 6 * k)).toEqual(m.atoms[bond.a]!.position.map(Math.fround));
    expect(point(capsules.endpoints, 6 * k + 3)).toEqual(m.atoms[bond.b]!.position.map(Math.fround));
    expect(capsules.radii[k]).toBeCloseTo(BOND_RADIUS, 6);
  });

  it('every capsule runs along its bond, and each atom touches exactly the capsules of its bonds', () => {
    const m = caffeine();
    const { mesh } = moleculeMesh(m, 'ball-and-stick');
    const e = mesh.capsules!.endpoints;
    let k = 0;
    m.bonds.forEach((bond, i) => {
      const pieces = bondCapsules(m, i);
      const [pa, pb] = [m.atoms[bond.a]!.position, m.atoms[bond.b]!.position];
      for (const piece of pieces) {
        const [a, b] = [point(e, 6 * k), point(e, 6 * k + 3)];
        expect(a).toEqual(piece.a.map(Math.fround));
        expect(b).toEqual(piece.b.map(Math.fround));
        // Parallel to the bond, and each end inside its atom's sphere.
        expect(Math.abs(dot(normalize(sub(b, a)), normalize(sub(pb, pa))))).toBeCloseTo(1, 5);
        expect(length(sub(a, pa))).toBeLessThan(atomRadius(m.atoms[bond.a]!.element, 'ball-and-stick'));
        expect(length(sub(b, pb))).toBeLessThan(atomRadius(m.atoms[bond.b]!.element, 'ball-and-stick'));
        k++;
      }
    });
    expect(k).toBe(mesh.capsules!.radii.length);
  });

  it('a double bond is two thinner capsules either side of the axis, in the plane of a neighbouring bond', () => {
    const m = caffeine();
    // Bond 14: atoms 7=8 (C=C, 0-based 6 and 7), in the planar rings (z ≈ 0).
    const index = m.bonds.findIndex((b) => b.a === 6 && b.b === 7);
    expect(m.bonds[index]!.type).toBe(2);
    const [one, two] = bondCapsules(m, index) as [ReturnType<typeof bondCapsules>[number], ReturnType<typeof bondCapsules>[number]];
    expect(bondCapsules(m, index)).toHaveLength(2);
    expect(one.radius).toBeLessThan(BOND_RADIUS);
    expect(two.radius).toBe(one.radius);
    const [pa, pb] = [m.atoms[6]!.position, m.atoms[7]!.position];
    const mid = (c: typeof one) => scale(add(c.a, c.b), 0.5);
    const axisMid = scale(add(pa, pb), 0.5);
    // Symmetric about the axis, separated by more than their diameters.
    expect(length(add(sub(mid(one), axisMid), sub(mid(two), axisMid)))).toBeCloseTo(0, 6);
    expect(length(sub(mid(one), mid(two)))).toBeGreaterThan(2 * one.radius);
    // The ring is flat in z: the offset stays in it.
    expect(Math.abs(mid(one)[2] - axisMid[2])).toBeLessThan(1e-3);
    for (const c of [one, two]) expect(distanceToSegment(c.a, pa, pb)).toBeGreaterThan(c.radius);
  });

  it('a triple bond is three capsules; an aromatic bond a full one and a short inner one toward the ring', () => {
    // Benzene drawn aromatic: a hexagon in the z = 0 plane around the origin.
    const ring = Array.from({ length: 6 }, (_, i) => `${(1.39 * Math.cos((i * Math.PI) / 3)).toFixed(4).padStart(10)}${(1.39 * Math.sin((i * Math.PI) / 3)).toFixed(4).padStart(10)}${'0.0000'.padStart(10)} C   0  0  0  0  0  0  0  0  0  0  0  0`);
    const bonds = Array.from({ length: 6 }, (_, i) => `${String(i + 1).padStart(3)}${String(((i + 1) % 6) + 1).padStart(3)}  4  0  0  0  0`);
    const benzene = parseMolfile(['benzene', '', '', '  6  6  0     0  0  0  0  0  0999 V2000', ...ring, ...bonds, 'M  END'].join('\n'), 'benzene.mol');
    for (let i = 0; i < 6; i++) {
      const [full, inner] = bondCapsules(benzene, i) as [ReturnType<typeof bondCapsules>[number], ReturnType<typeof bondCapsules>[number]];
      expect(bondCapsules(benzene, i)).toHaveLength(2);
      expect(full.radius).toBe(BOND_RADIUS);
      expect(inner.radius).toBeLessThan(BOND_RADIUS);
      expect(length(sub(inner.a, inner.b))).toBeLessThan(length(sub(full.a, full.b)));
      // The inner line is nearer the ring's centre than the bond itself.
      expect(length(scale(add(inner.a, inner.b), 0.5))).toBeLessThan(length(scale(add(full.a, full.b), 0.5)));
    }
    const acetylene = parseMolfile(
      ['ethyne', '', '', '  4  3  0     0  0  0  0  0  0999 V2000', ...[[-1.66, 'H'], [-0.6, 'C'], [0.6, 'C'], [1.66, 'H']].map(([x, s]) => `${(x as number).toFixed(4).padStart(10)}    0.0000    0.0000 ${s}   0  0  0  0  0  0  0  0  0  0  0  0`), '  1  2  1  0', '  2  3  3  0', '  3  4  1  0', 'M  END'].join('\n'),
      'ethyne.mol',
    );
    const triple = bondCapsules(acetylene, 1);
    expect(triple).toHaveLength(3);
    // A linear molecule has no neighbouring plane: the offsets still stand off the axis, apart.
    for (const c of triple.slice(1)) expect(distanceToSegment(c.a, [-0.6, 0, 0], [0.6, 0, 0])).toBeGreaterThan(c.radius);
    expect(length(cross(sub(triple[1]!.a, triple[0]!.a), [1, 0, 0]))).toBeGreaterThan(0.1);
  });

  it('the studio frames the molecule by its spheres, in Å (metersPerUnit 1e-10)', () => {
    const scene = moleculeScene(caffeine(), 'space-filling', 'caffeine.mol');
    expect(scene.metersPerUnit).toBe(1e-10);
    const mesh = scene.meshes[0] as Mesh;
    const floor = scene.meshes[1]!;
    // The floor lies at the bottom of the lowest sphere, not of the lowest atom centre.
    let lowest = Infinity;
    for (let i = 0; i < 24; i++) lowest = Math.min(lowest, mesh.spheres!.centers[3 * i + 1]! - mesh.spheres!.radii[i]!);
    expect(floor.positions[1]).toBeLessThan(lowest);
    expect(floor.positions[1]).toBeGreaterThan(lowest - 0.01);
    // Every sphere's extreme points are in front of the camera and inside the field of view.
    const { position, forward, up, vfovDegrees } = scene.camera;
    const f = normalize(forward), r = normalize(cross(f, up)), u = cross(r, f);
    const t = Math.tan((vfovDegrees * Math.PI) / 360);
    for (let i = 0; i < 24; i++) {
      for (const d of [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]] as Vec3[]) {
        const q = sub(add(point(mesh.spheres!.centers, 3 * i), scale(d, mesh.spheres!.radii[i]!)), position);
        const z = dot(q, f);
        expect(z).toBeGreaterThan(0);
        expect(Math.abs(dot(q, u))).toBeLessThanOrEqual(t * z);
        expect(Math.abs(dot(q, r))).toBeLessThanOrEqual(t * z);
      }
    }
  });
});

describe('SD files', () => {
  const aspirinLike = ['water', '  Lantern', '', '  3  2  0     0  0  0  0  0  0999 V2000', '    0.0000    0.0000    0.0000 O   0  0', '    0.9572    0.0000    0.0000 H   0  0', '   -0.2400    0.9266    0.0000 H   0  0', '  1  2  1  0', '  1  3  1  0', 'M  END', '> <SOURCE>', 'by hand', ''].join('\n');
  const twoRecords = `${CAFFEINE_MOL}> <PUBCHEM_COMPOUND_CID>\n2519\n\n$$$$\n${aspirinLike}$$$$\n`;

  it('reads every record, data items skipped', () => {
    const molecules = parseSdf(twoRecords, 'two.sdf');
    expect(molecules.map((m) => [m.name, m.atoms.length, m.bonds.length, hillFormula(m)])).toEqual([
      ['caffeine', 24, 25, 'C8H10N4O2'],
      ['water', 3, 2, 'H2O'],
    ]);
    expect(molecules[1]!.firstLine).toBe(lines.length - 1 + 4 + 1);
  });

  it('each record is a part in each style, selectable by title or number', async () => {
    const opened = await MOLECULE_FORMAT.open({ files: [{ name: 'two.sdf', bytes: bytes(twoRecords) }], resolve: () => Promise.resolve(undefined) });
    expect(opened.parts.map((p) => p.name)).toEqual(['caffeine', 'caffeine:space-filling', 'water', 'water:space-filling']);
    expect(opened.partNamed!('2')).toBe('water');
    expect(opened.partNamed!('2:space-filling')).toBe('water:space-filling');
    expect(opened.partNamed!('water:ball-and-stick')).toBe('water');
    expect(opened.partNamed!('3')).toBeUndefined();
    const water = await opened.scene('water:space-filling');
    expect(water.name).toBe('two.sdf#water:space-filling');
    expect(water.meshes[0]!.spheres!.radii).toEqual(new Float32Array([1.52, 1.2, 1.2]));
    expect(water.meshes[0]!.capsules).toBeUndefined();
    const first = await opened.scene();
    expect(first.meshes[0]!.spheres!.radii).toHaveLength(24);
    await expect(opened.scene('coffee')).rejects.toThrow(/two\.sdf has no model 'coffee'/);
    const inventory = opened.inventory!();
    expect(inventory.lines.join('\n')).toMatch(/caffeine\s+C8H10N4O2\s+24 atoms\s+25 bonds \(21 single, 4 double\)/);
    expect(inventory.lines.join('\n')).toMatch(/water\s+H2O\s+3 atoms\s+2 bonds/);
  });

  it('a .mol file has the two styles as its parts', async () => {
    const opened = await MOLECULE_FORMAT.open({ files: [{ name: 'caffeine.mol', bytes: bytes(CAFFEINE_MOL) }], resolve: () => Promise.resolve(undefined) });
    expect(opened.parts.map((p) => p.name)).toEqual(['ball-and-stick', 'space-filling']);
    expect(opened.partNamed!('caffeine:space-filling')).toBe('space-filling');
    expect(opened.partNamed!('1')).toBe('ball-and-stick');
    const scene = await opened.scene('space-filling');
    expect(scene.meshes[0]!.spheres!.radii[0]).toBeCloseTo(1.52, 6);
  });

  it('is recognised by its counts line, V2000 or V3000, whatever the name; and `#` picks a part', () => {
    expect(isMoleculeHead(bytes(CAFFEINE_MOL))).toBe(true);
    expect(isMoleculeHead(bytes(CAFFEINE_V3000))).toBe(true);
    expect(isMoleculeHead(bytes(CAFFEINE_MOL.replace('V2000', 'V4000')))).toBe(false);
    expect(isMoleculeHead(bytes('ply\nformat ascii 1.0\n'))).toBe(false);
    expect(MOLECULE_FORMAT.parseReference!('a/caffeine.mol#space-filling')).toEqual({ paths: ['a/caffeine.mol'], part: 'space-filling' });
    expect(MOLECULE_FORMAT.parseReference!('drugs.SDF#2')).toEqual({ paths: ['drugs.SDF'], part: '2' });
    expect(MOLECULE_FORMAT.parseReference!('caffeine.mol')).toEqual({ paths: ['caffeine.mol'] });
    expect(MOLECULE_FORMAT.parseReference!('mesh.ply#x')).toBeUndefined();
  });
});

describe('bad files: one line naming the line', () => {
  const parse = (text: string) => () => parseMolfile(text, 'bad.mol');
  it('a bad counts line', () => {
    expectLanternError(parse(withLine(4, ' 2x 25  0     0  0  0  0  0  0999 V2000')), /^bad\.mol line 4: bad counts line: the atom count '2x'/);
    expectLanternError(parse(withLine(4, ' 24 25  0     0  0  0  0  0  0999 V2001')), /^bad\.mol line 4: bad counts line: version 'V2001'/);
    expectLanternError(parse('caffeine\n\n'), /^bad\.mol line \d: the molfile ends before its counts line/);
  });
  it('an atom line too short', () => {
    expectLanternError(parse(withLine(7, '   -0.9686   -1.3125')), /^bad\.mol line 7: atom line too short/);
  });
  it('a non-numeric coordinate', () => {
    expectLanternError(parse(withLine(6, '   -3.1271   -0.44x6   -0.0003 O   0  0  0  0  0  0  0  0  0  0  0  0')), /^bad\.mol line 6: the y coordinate '-0\.44x6' is not a number/);
  });
  it('an unknown element', () => {
    expectLanternError(parse(withLine(5, '    0.4700    2.5688    0.0006 Qq  0  0  0  0  0  0  0  0  0  0  0  0')), /^bad\.mol line 5: unknown element 'Qq'/);
  });
  it('a bond to atom 0 or past the count', () => {
    expectLanternError(parse(withLine(29, '  0  9  2  0  0  0  0')), /^bad\.mol line 29: bond to atom 0, but atoms are numbered 1 to 24/);
    expectLanternError(parse(withLine(53, ' 14 25  1  0  0  0  0')), /^bad\.mol line 53: bond to atom 25, but atoms are numbered 1 to 24/);
    expectLanternError(parse(withLine(30, '  2 10  0  0  0  0  0')), /^bad\.mol line 30: bond type 0 is not a V2000 bond type/);
  });
  it("a missing 'M  END'", () => {
    expectLanternError(parse(lines.filter((l) => l !== 'M  END').join('\n')), /^bad\.mol line 53: missing 'M {2}END'/);
  });
  it('a counts line promising more bonds than there are', () => {
    expectLanternError(parse(withLine(4, ' 24 26  0     0  0  0  0  0  0999 V2000')), /^bad\.mol line 54: 'M {2}END' inside the bond block: the counts line promises 26 bonds, there are 25/);
  });
  it('a truncated bond block', () => {
    expectLanternError(parse(lines.slice(0, 40).join('\n')), /^bad\.mol line 40: the molfile ends inside the bond block \(12 of 25 bonds read\)/);
  });
  it('V3000: a bond to a missing atom, a bad coordinate, a wrong count, no M  END', () => {
    const v3 = CAFFEINE_V3000.split('\n');
    const v3with = (n: number, text: string) => v3.map((l, i) => (i === n - 1 ? text : l)).join('\n');
    const parse3 = (text: string) => () => parseMolfile(text, 'bad3.mol');
    const bondLine = v3.findIndex((l) => l === 'M  V30 BEGIN BOND') + 2;
    expectLanternError(parse3(v3with(bondLine, 'M  V30 1 2 1 99')), new RegExp(`^bad3\\.mol line ${bondLine}: bond to atom 99, which the atom block does not have`));
    expectLanternError(parse3(v3with(10, 'M  V30 3 N -0.9686 abc 0.0000 0')), /^bad3\.mol line 10: the y coordinate 'abc' is not a number/);
    expectLanternError(parse3(v3with(10, 'M  V30 3 Xx -0.9686 -1.3125 0.0000 0')), /^bad3\.mol line 10: unknown element 'Xx'/);
    // Refused at the first atom past the count (the block is not read to its end first).
    // The 24th atom's line: after BEGIN ATOM (line 7), 24 atoms of which the first is continued.
    const atom24 = 7 + 24 + 1;
    expectLanternError(parse3(v3with(6, 'M  V30 COUNTS 23 25 0 0 0')), new RegExp(`^bad3\\.mol line ${atom24}: the atom block has more atoms than the 23 COUNTS says`));
    expectLanternError(parse3(v3with(6, 'M  V30 COUNTS 25 25 0 0 0')), /the atom block has 24 atoms but COUNTS says 25/);
    expectLanternError(parse3(v3.filter((l) => l !== 'M  END').join('\n')), /^bad3\.mol line \d+: missing 'M {2}END'/);
  });
  it('an SD record names its line in the whole file', () => {
    const text = `${CAFFEINE_MOL}$$$$\n${withLine(5, '    0.4700    2.5688    0.0006 Qq  0  0')}$$$$\n`;
    expectLanternError(() => parseSdf(text, 'two.sdf'), new RegExp(`^two\\.sdf line ${lines.length - 1 + 1 + 5}: unknown element 'Qq'`));
  });
});

describe('element table', () => {
  it('has every element from H to Kr, with radii and colours in range', () => {
    for (let z = 1; z <= 36; z++) expect(ELEMENTS.some((e) => e.number === z)).toBe(true);
    for (const e of ELEMENTS) {
      expect(e.vdw).toBeGreaterThan(1);
      expect(e.vdw).toBeLessThan(3.6);
      expect(e.covalent).toBeGreaterThan(0.25);
      expect(e.covalent).toBeLessThan(e.vdw + 0.5);
      for (const c of linearColor(e)) expect(c >= 0 && c <= 1).toBe(true);
    }
    // Jmol's white hydrogen and #FF0D0D oxygen, decoded to linear.
    expect(linearColor(findElement('H')!)).toEqual([1, 1, 1]);
    expect(linearColor(findElement('O')!)[0]).toBe(1);
    expect(linearColor(findElement('O')!)[1]).toBeCloseTo(0.004025, 5);
    expect(findElement('D')).toBe(findElement('H'));
    expect(findElement('c')).toBeUndefined();
  });
  it('the caffeine fixture is present where the CLI tests expect it', () => {
    expect(existsSync(fixture('caffeine.mol'))).toBe(true);
  });
});

describe('the line reader', () => {
  const all = (input: string | Uint8Array) => {
    const reader = new LineReader(input, 'x');
    const out: string[] = [];
    for (let l = reader.next(); l !== undefined; l = reader.next()) out.push(l);
    return out;
  };
  it('splits as split(/\\r\\n|\\r|\\n/) does, a final line ending starting no line', () => {
    for (const text of ['a\r\nb\rc\nd', 'a\n\n', '\r\r\n\n', '', 'x']) {
      const expected = text.split(/\r\n|\r|\n/);
      if (expected.at(-1) === '') expected.pop();
      expect(all(text)).toEqual(expected);
      expect(all(bytes(text))).toEqual(expected);
    }
  });
  it('skips blank lines as next() would read them, counting them, across slices and line endings', () => {
    const slice = 1 << 22;
    for (const text of [' \t\r\n\n  \r\rcontent\nmore', `${'\n'.repeat(slice - 1)}\r\n  \nx`, `${'\n'.repeat(slice - 3)}        \nx y\n`, '\n\n\n', '\u00a0\nx']) {
      for (const input of [text, bytes(text)]) {
        const reader = new LineReader(input, 'x');
        const skipped = reader.skipBlankLines();
        const rest = all(input).slice(skipped);
        expect(all(input).slice(0, skipped).every((l) => l.trim() === '')).toBe(true);
        expect(reader.index).toBe(skipped - 1);
        const after: string[] = [];
        for (let l = reader.next(); l !== undefined; l = reader.next()) after.push(l);
        expect(after).toEqual(rest);
      }
    }
  });
  it('names the right line after a run of blank lines (the record starts after the $$$$ of line 1001: its counts line is 1005)', () => {
    expectLanternError(() => parseSdf(bytes(`${'\n'.repeat(1000)}$$$$\n\n\n\n\n  x`), 'b.sdf'), /^b\.sdf line 1005: bad counts line/);
    expectLanternError(() => parseSdf(bytes(`\n\n${' '.repeat(3 << 20)}\nx`), 'w.sdf'), /^w\.sdf line 3: a line longer than 1,048,576 characters/);
  });
  it('reads bytes in slices: a \\r\\n split between two slices is one line ending, a character split between them is one character', () => {
    // The slices are 4 MiB: put '\r' at the last byte of the first and '\n' at the first of the next,
    // and a two-byte 'é' astride the second boundary.
    const slice = 1 << 22;
    const row = `${'a'.repeat(99)}\n`;
    const rows = (n: number) => row.repeat(Math.floor(n / 100));
    const first = rows(slice - 1000);
    const pad = 'p'.repeat(slice - 1 - first.length);
    // '\r' is byte slice − 1, '\n' byte slice; 'é' (2 bytes) starts at byte 2 slice − 1.
    const second = rows(slice - 1000);
    const text = `${first}${pad}\r\n${second}${'q'.repeat(2 * slice - 1 - (slice + 1 + second.length))}é\nlast`;
    expect(new TextEncoder().encode(text.slice(0, text.indexOf('é'))).length).toBe(2 * slice - 1);
    const lines = all(bytes(text));
    expect(lines).toEqual(text.split(/\r\n|\r|\n/));
    expect(lines.filter((l) => l.startsWith('p') || l.startsWith('q') || l === 'last').map((l) => l.length)).toEqual([pad.length, 2 * slice - 1 - (slice + 1 + second.length) + 1, 4]);
  });
});
