/**
 * The element table molecules are drawn from: colour, van der Waals radius and covalent radius for
 * every element from H to Kr and the heavier ones common in molecule files.
 *
 * - Colours are Jmol's CPK scheme (jmol.sourceforge.net/jscolors), sRGB hex as Jmol publishes them;
 *   `linearColor` decodes them for materials.
 * - Van der Waals radii (Å): Bondi, "van der Waals Volumes and Radii", J. Phys. Chem. 68 (1964) 441,
 *   where Bondi gives one; Mantina et al., J. Phys. Chem. A 113 (2009) 5806, for the main-group
 *   elements he lacks (Be, B, Al, Ca, Ge, Rb, Sr, Sb, Cs, Ba, Bi); Alvarez, Dalton Trans. 42 (2013)
 *   8617, for the transition metals neither covers.
 * - Covalent radii (Å): Cordero et al., "Covalent radii revisited", Dalton Trans. (2008) 2832; carbon
 *   is its sp3 value, and Mn, Fe and Co their low-spin ones.
 */
import { LanternError } from '../../errors.ts';
import type { Vec3 } from '../../math/vec3.ts';

export interface Element {
  readonly symbol: string;
  readonly number: number;
  /** Jmol colour, sRGB 0xRRGGBB. */
  readonly jmol: number;
  /** Van der Waals radius, Å. */
  readonly vdw: number;
  /** Single-bond covalent radius, Å. */
  readonly covalent: number;
}

// symbol, atomic number, Jmol colour, van der Waals radius, covalent radius.
const TABLE: readonly (readonly [string, number, number, number, number])[] = [
  ['H', 1, 0xffffff, 1.2, 0.31],
  ['He', 2, 0xd9ffff, 1.4, 0.28],
  ['Li', 3, 0xcc80ff, 1.82, 1.28],
  ['Be', 4, 0xc2ff00, 1.53, 0.96],
  ['B', 5, 0xffb5b5, 1.92, 0.84],
  ['C', 6, 0x909090, 1.7, 0.76],
  ['N', 7, 0x3050f8, 1.55, 0.71],
  ['O', 8, 0xff0d0d, 1.52, 0.66],
  ['F', 9, 0x90e050, 1.47, 0.57],
  ['Ne', 10, 0xb3e3f5, 1.54, 0.58],
  ['Na', 11, 0xab5cf2, 2.27, 1.66],
  ['Mg', 12, 0x8aff00, 1.73, 1.41],
  ['Al', 13, 0xbfa6a6, 1.84, 1.21],
  ['Si', 14, 0xf0c8a0, 2.1, 1.11],
  ['P', 15, 0xff8000, 1.8, 1.07],
  ['S', 16, 0xffff30, 1.8, 1.05],
  ['Cl', 17, 0x1ff01f, 1.75, 1.02],
  ['Ar', 18, 0x80d1e3, 1.88, 1.06],
  ['K', 19, 0x8f40d4, 2.75, 2.03],
  ['Ca', 20, 0x3dff00, 2.31, 1.76],
  ['Sc', 21, 0xe6e6e6, 2.58, 1.7],
  ['Ti', 22, 0xbfc2c7, 2.46, 1.6],
  ['V', 23, 0xa6a6ab, 2.42, 1.53],
  ['Cr', 24, 0x8a99c7, 2.45, 1.39],
  ['Mn', 25, 0x9c7ac7, 2.45, 1.39],
  ['Fe', 26, 0xe06633, 2.44, 1.32],
  ['Co', 27, 0xf090a0, 2.4, 1.26],
  ['Ni', 28, 0x50d050, 1.63, 1.24],
  ['Cu', 29, 0xc88033, 1.4, 1.32],
  ['Zn', 30, 0x7d80b0, 1.39, 1.22],
  ['Ga', 31, 0xc28f8f, 1.87, 1.22],
  ['Ge', 32, 0x668f8f, 2.11, 1.2],
  ['As', 33, 0xbd80e3, 1.85, 1.19],
  ['Se', 34, 0xffa100, 1.9, 1.2],
  ['Br', 35, 0xa62929, 1.85, 1.2],
  ['Kr', 36, 0x5cb8d1, 2.02, 1.16],
  ['Rb', 37, 0x702eb0, 3.03, 2.2],
  ['Sr', 38, 0x00ff00, 2.49, 1.95],
  ['Zr', 40, 0x94e0e0, 2.52, 1.75],
  ['Mo', 42, 0x54b5b5, 2.45, 1.54],
  ['Ru', 44, 0x248f8f, 2.46, 1.46],
  ['Rh', 45, 0x0a7d8c, 2.44, 1.42],
  ['Pd', 46, 0x006985, 1.63, 1.39],
  ['Ag', 47, 0xc0c0c0, 1.72, 1.45],
  ['Cd', 48, 0xffd98f, 1.58, 1.44],
  ['In', 49, 0xa67573, 1.93, 1.42],
  ['Sn', 50, 0x668080, 2.17, 1.39],
  ['Sb', 51, 0x9e63b5, 2.06, 1.39],
  ['Te', 52, 0xd47a00, 2.06, 1.38],
  ['I', 53, 0x940094, 1.98, 1.39],
  ['Xe', 54, 0x429eb0, 2.16, 1.4],
  ['Cs', 55, 0x57178f, 3.43, 2.44],
  ['Ba', 56, 0x00c900, 2.68, 2.15],
  ['W', 74, 0x2194d6, 2.57, 1.62],
  ['Pt', 78, 0xd0d0e0, 1.75, 1.36],
  ['Au', 79, 0xffd123, 1.66, 1.36],
  ['Hg', 80, 0xb8b8d0, 1.55, 1.32],
  ['Tl', 81, 0xa6544d, 1.96, 1.45],
  ['Pb', 82, 0x575961, 2.02, 1.46],
  ['Bi', 83, 0x9e4fb5, 2.07, 1.48],
  ['U', 92, 0x008fff, 1.86, 1.96],
];

const BY_SYMBOL: ReadonlyMap<string, Element> = new Map(TABLE.map(([symbol, number, jmol, vdw, covalent]) => [symbol, { symbol, number, jmol, vdw, covalent }]));

/** Symbols molfiles use for isotopes of hydrogen: deuterium and tritium are drawn as hydrogen. */
const ALIASES: Readonly<Record<string, string>> = { D: 'H', T: 'H' };

/** Every element in the table, by atomic number. */
export const ELEMENTS: readonly Element[] = [...BY_SYMBOL.values()];

/** The element of a symbol as molfiles write it (`C`, `Cl`; case as in the periodic table), or undefined. */
export function findElement(symbol: string): Element | undefined {
  return BY_SYMBOL.get(ALIASES[symbol] ?? symbol);
}

/** The element of a symbol, or a LanternError naming the symbol and where it was read. */
export function elementOf(symbol: string, where: string): Element {
  const element = findElement(symbol);
  if (!element) {
    throw new LanternError(
      `${where}: unknown element '${symbol}'`,
      `Lantern draws ${ELEMENTS.length} elements (H to Kr and common heavier ones); query atoms (A, Q, R#, *) and lists have no shape`,
    );
  }
  return element;
}

/** A Jmol colour as linear RGB in [0, 1] (the sRGB transfer function inverted). */
export function linearColor(element: Element): Vec3 {
  const channel = (shift: number) => {
    const c = ((element.jmol >> shift) & 0xff) / 255;
    return c <= 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055) ** 2.4;
  };
  return [channel(16), channel(8), channel(0)];
}
