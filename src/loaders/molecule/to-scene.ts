/**
 * A molecule as analytic spheres and capsules, put in the studio (scene/studio.ts). Units are Å.
 *
 * Styles:
 * - 'ball-and-stick' (default): each atom a sphere of half its covalent radius (never less than 1.5×
 *   a bond's radius, so a hydrogen still shows past its bond), each bond capsules of BOND_RADIUS
 *   between the atom centres:
 *     single (and query bonds 5-8, which have no one order): one capsule on the axis;
 *     double: two capsules of 0.55× the radius, offset ±DOUBLE_OFFSET from the axis;
 *     triple: three of 0.45× the radius, at 0 and ±TRIPLE_OFFSET;
 *     aromatic (type 4): the textbook drawing of a delocalised ring, a full capsule on the axis plus a
 *       thin one (0.4×) over the middle 60 % of the bond, offset AROMATIC_OFFSET toward the ring
 *       (the side of the neighbour bonded aromatically, i.e. inside a convex ring);
 *     coordination (9): one capsule of 0.6×; hydrogen bond (10): one of 0.3×.
 *   The offsets lie in the plane of a neighbouring bond (of either end atom), so a double bond in a
 *   ring or a carbonyl lies in the molecule's plane, as chemists draw it; a bond with no neighbour
 *   (O=O) takes any perpendicular.
 * - 'space-filling': each atom a sphere of its van der Waals radius, no bonds.
 *
 * Materials: one glossy plastic per element present (Jmol colour), in order of first appearance, then
 * a light grey one for the bonds.
 */
import { add, cross, dot, length, normalize, scale, sub, type Vec3 } from '../../math/vec3.ts';
import { studioScene } from '../../scene/studio.ts';
import { metallicRoughness, type Material, type Mesh, type Scene } from '../../scene/types.ts';
import { linearColor, type Element } from './elements.ts';
import type { Bond, Molecule } from './molfile.ts';

export const MOLECULE_STYLES = ['ball-and-stick', 'space-filling'] as const;
export type MoleculeStyle = (typeof MOLECULE_STYLES)[number];
export const DEFAULT_MOLECULE_STYLE: MoleculeStyle = 'ball-and-stick';

/** Radius of a single bond's capsule, Å. */
export const BOND_RADIUS = 0.16;
const DOUBLE_RADIUS = 0.55 * BOND_RADIUS;
const DOUBLE_OFFSET = 0.13;
const TRIPLE_RADIUS = 0.45 * BOND_RADIUS;
const TRIPLE_OFFSET = 0.17;
const AROMATIC_RADIUS = 0.4 * BOND_RADIUS;
const AROMATIC_OFFSET = 0.3;
/** The aromatic inner line covers the bond from this fraction of its length to one minus it. */
const AROMATIC_INSET = 0.2;
const BOND_COLOR: Vec3 = [0.7, 0.7, 0.7];
/** Glossy plastic: a dielectric coat over the element colour. */
const ATOM_ROUGHNESS = 0.3;

/** The sphere radius of an atom in a style, Å. */
export function atomRadius(element: Element, style: MoleculeStyle): number {
  return style === 'space-filling' ? element.vdw : Math.max(0.5 * element.covalent, 1.5 * BOND_RADIUS);
}

/** One capsule: end points and radius, Å. */
export interface BondCapsule {
  readonly a: Vec3;
  readonly b: Vec3;
  readonly radius: number;
}

/** The capsules that draw one bond (see the file header). */
export function bondCapsules(molecule: Molecule, bondIndex: number): BondCapsule[] {
  const bond = molecule.bonds[bondIndex]!;
  const a = molecule.atoms[bond.a]!.position;
  const b = molecule.atoms[bond.b]!.position;
  let sideOnce: Vec3 | undefined;
  const side = () => (sideOnce ??= sideDirection(molecule, bondIndex));
  const shifted = (offset: number, radius: number, inset = 0): BondCapsule => {
    const d = scale(side(), offset);
    const ab = sub(b, a);
    return { a: add(add(a, scale(ab, inset)), d), b: add(sub(b, scale(ab, inset)), d), radius };
  };
  switch (bond.type) {
    case 2:
      return [shifted(DOUBLE_OFFSET, DOUBLE_RADIUS), shifted(-DOUBLE_OFFSET, DOUBLE_RADIUS)];
    case 3:
      return [{ a, b, radius: TRIPLE_RADIUS }, shifted(TRIPLE_OFFSET, TRIPLE_RADIUS), shifted(-TRIPLE_OFFSET, TRIPLE_RADIUS)];
    case 4:
      return [{ a, b, radius: BOND_RADIUS }, shifted(AROMATIC_OFFSET, AROMATIC_RADIUS, AROMATIC_INSET)];
    case 9:
      return [{ a, b, radius: 0.6 * BOND_RADIUS }];
    case 10:
      return [{ a, b, radius: 0.3 * BOND_RADIUS }];
    default:
      return [{ a, b, radius: BOND_RADIUS }];
  }
}

/**
 * How many of an atom's bonds are looked at for a neighbour: no real atom has more than a dozen or
 * so. Without a bound, 20,000 double bonds on one atom took each bond past all the others (over 60 s).
 */
const NEIGHBOURS_LOOKED_AT = 16;

/** Each atom's bonds, in file order: bonds[offsets[i] .. offsets[i + 1]) are atom i's. */
interface AtomBonds {
  readonly offsets: Uint32Array;
  readonly bonds: Uint32Array;
}

const atomBondsOf = new WeakMap<Molecule, AtomBonds>();

function atomBonds(molecule: Molecule): AtomBonds {
  let found = atomBondsOf.get(molecule);
  if (found) return found;
  const offsets = new Uint32Array(molecule.atoms.length + 1);
  for (const b of molecule.bonds) {
    offsets[b.a + 1]!++;
    offsets[b.b + 1]!++;
  }
  for (let i = 0; i < molecule.atoms.length; i++) offsets[i + 1]! += offsets[i]!;
  const next = offsets.slice(0, -1);
  const bonds = new Uint32Array(2 * molecule.bonds.length);
  molecule.bonds.forEach((b, i) => {
    bonds[next[b.a]!++] = i;
    bonds[next[b.b]!++] = i;
  });
  atomBondsOf.set(molecule, (found = { offsets, bonds }));
  return found;
}

/**
 * A unit vector perpendicular to the bond, in the plane of a neighbouring bond and pointing toward
 * that neighbour. An aromatic bond prefers a neighbour bonded aromatically (the next atom of its ring,
 * so the direction points into the ring); any bond takes a neighbour of its first atom before one of
 * its second, each atom's in file order.
 */
function sideDirection(molecule: Molecule, bondIndex: number): Vec3 {
  const bond = molecule.bonds[bondIndex]!;
  const pa = molecule.atoms[bond.a]!.position;
  const pb = molecule.atoms[bond.b]!.position;
  // Two bonded atoms at one place (a damaged file; the fuzzer found it) give the bond no direction,
  // and any side will do.
  if (!(length(sub(pb, pa)) > 0)) return [1, 0, 0];
  const axis = normalize(sub(pb, pa));
  const { offsets, bonds } = atomBonds(molecule);
  // Aromatic neighbours first for an aromatic bond; for any other, every neighbour in one pass.
  for (const aromatic of bond.type === 4 ? [true, false] : [undefined]) {
    for (const pivot of [bond.a, bond.b]) {
      const end = Math.min(offsets[pivot + 1]!, offsets[pivot]! + NEIGHBOURS_LOOKED_AT);
      for (let k = offsets[pivot]!; k < end; k++) {
        const o = molecule.bonds[bonds[k]!]!;
        if (bonds[k] === bondIndex || (aromatic !== undefined && (o.type === 4) !== aromatic)) continue;
        // A second bond between the same two atoms was looked at from the first.
        if (pivot === bond.b && touches(o, bond.a)) continue;
        const other = o.a === pivot ? o.b : o.a;
        const w = sub(molecule.atoms[other]!.position, molecule.atoms[pivot]!.position);
        const perpendicular = sub(w, scale(axis, dot(w, axis)));
        if (length(perpendicular) > 1e-3 * length(w)) return normalize(perpendicular);
      }
    }
  }
  // No neighbour off the bond's line: any perpendicular, from the world axis least along the bond.
  const least: Vec3 = Math.abs(axis[0]) < 0.6 ? [1, 0, 0] : Math.abs(axis[1]) < 0.6 ? [0, 1, 0] : [0, 0, 1];
  const side = cross(axis, least);
  // Coordinates near the float range (1e308, found by the fuzzer) can still cancel to nothing.
  return length(side) > 0 ? normalize(side) : [1, 0, 0];
}

const touches = (bond: Bond, atom: number) => bond.a === atom || bond.b === atom;

/** The molecule as one mesh of spheres (and capsules), with its materials numbered from `firstMaterial`. */
export function moleculeMesh(molecule: Molecule, style: MoleculeStyle = DEFAULT_MOLECULE_STYLE, firstMaterial = 0): { mesh: Mesh; materials: Material[] } {
  const materials: Material[] = [];
  const materialOf = new Map<string, number>();
  const centers = new Float32Array(molecule.atoms.length * 3);
  const radii = new Float32Array(molecule.atoms.length);
  const sphereMaterials = new Uint32Array(molecule.atoms.length);
  molecule.atoms.forEach((atom, i) => {
    let m = materialOf.get(atom.element.symbol);
    if (m === undefined) {
      m = firstMaterial + materials.length;
      materialOf.set(atom.element.symbol, m);
      materials.push(metallicRoughness(atom.element.symbol, { baseColor: linearColor(atom.element), metallic: 0, roughness: ATOM_ROUGHNESS }));
    }
    centers.set(atom.position, 3 * i);
    radii[i] = atomRadius(atom.element, style);
    sphereMaterials[i] = m;
  });

  const capsules = style === 'space-filling' ? [] : molecule.bonds.flatMap((_, i) => bondCapsules(molecule, i));
  const mesh: Mesh = {
    name: molecule.name || 'molecule',
    positions: new Float32Array(0),
    indices: new Uint32Array(0),
    materialIds: new Uint32Array(0),
    spheres: { centers, radii, materialIds: sphereMaterials },
    ...(capsules.length > 0 ? { capsules: capsuleSet(capsules, firstMaterial + materials.length) } : {}),
  };
  if (capsules.length > 0) materials.push(metallicRoughness('bond', { baseColor: BOND_COLOR, metallic: 0, roughness: ATOM_ROUGHNESS }));
  return { mesh, materials };
}

function capsuleSet(capsules: readonly BondCapsule[], material: number) {
  const endpoints = new Float32Array(capsules.length * 6);
  capsules.forEach((c, i) => endpoints.set([...c.a, ...c.b], 6 * i));
  return { endpoints, radii: new Float32Array(capsules.map((c) => c.radius)), materialIds: new Uint32Array(capsules.length).fill(material) };
}

/** The molecule in the studio, framed by its atoms' spheres. `name` names the scene (the file, or the record). */
export function moleculeScene(molecule: Molecule, style: MoleculeStyle, name: string): Scene {
  const { mesh, materials } = moleculeMesh(molecule, style);
  return { ...studioScene(name, [mesh], materials), metersPerUnit: 1e-10 };
}

/**
 * The Hill formula of the atoms drawn (explicit atoms only: a file that leaves hydrogens implicit
 * gives fewer H): C first, then H, then the rest alphabetically; without carbon, all alphabetically.
 */
export function hillFormula(molecule: Molecule): string {
  const counts = new Map<string, number>();
  for (const atom of molecule.atoms) counts.set(atom.element.symbol, (counts.get(atom.element.symbol) ?? 0) + 1);
  const symbols = [...counts.keys()].sort();
  const order = counts.has('C') ? ['C', ...(counts.has('H') ? ['H'] : []), ...symbols.filter((s) => s !== 'C' && s !== 'H')] : symbols;
  return order.map((s) => `${s}${counts.get(s) === 1 ? '' : counts.get(s)}`).join('');
}
