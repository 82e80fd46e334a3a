/**
 * The Wolfenstein 3D entry of the loader registry: one game's MAPHEAD, GAMEMAPS and VSWAP (`.WL1`
 * shareware, `.WL6` registered) are one file set, and its maps are the parts (`#E1L1`, or the
 * 1-based map number). Naming any one of the three is enough: the other two are its siblings, in
 * the same folder with the same extension (names matched without regard to case). A folder holding
 * them is a set too (filesInFolder). Other files of the game (AUDIOT, VGAGRAPH, …) are ignored.
 */
import { WarningCap } from '../../budgets.ts';
import { LanternError } from '../../errors.ts';
import type { FileHead, NamedBytes, OpenedScene, SceneFormat, SceneReference } from '../format.ts';
import { extensionOf, readWolfGame } from './game.ts';
import { GAMEMAPS_SIGNATURE, mapId, mapIndexOf } from './maps.ts';
import { wolfMapToScene } from './to-scene.ts';
import type { WolfGame } from './types.ts';

const EXTENSIONS = ['.wl6', '.wl1'];
const EXTENSION = /\.wl[16]$/i;
type Role = 'maphead' | 'gamemaps' | 'vswap';
const ROLE_NAMES: Record<Role, readonly string[]> = { maphead: ['MAPHEAD'], gamemaps: ['GAMEMAPS', 'MAPTEMP'], vswap: ['VSWAP'] };
const ROLES: readonly Role[] = ['maphead', 'gamemaps', 'vswap'];
const SET_HINT = 'Wolfenstein 3D maps need MAPHEAD, GAMEMAPS and VSWAP of one game, side by side (MAPHEAD.WL1, GAMEMAPS.WL1, VSWAP.WL1)';

const baseName = (path: string) => path.slice(Math.max(path.lastIndexOf('/'), path.lastIndexOf('\\')) + 1);

/** Which of the three files a name is ('MAPHEAD.WL1' → maphead), or undefined for another file. */
export function wolfRole(name: string): Role | undefined {
  const base = baseName(name);
  if (!EXTENSION.test(base)) return undefined;
  const stem = base.slice(0, base.lastIndexOf('.')).toUpperCase();
  return ROLES.find((r) => ROLE_NAMES[r].includes(stem));
}

/** A map named by id (any case) or 1-based number, as listed ('E1L1'); anything else as given. */
function normalizePart(name: string): string {
  const index = mapIndexOf(name);
  return index === undefined ? name : mapId(index);
}

/**
 * The sibling of `main` playing `role`: the main file's own spelling of the extension and the
 * name's case (`vswap.wl1` beside `maphead.wl1`), then upper case.
 */
function siblingNames(main: string, role: Role): string[] {
  const base = baseName(main);
  const ext = base.slice(base.lastIndexOf('.'));
  const lower = base === base.toLowerCase();
  const names = ROLE_NAMES[role].flatMap((stem) => [lower ? `${stem.toLowerCase()}${ext}` : `${stem}${ext}`, `${stem}${ext.toUpperCase()}`, `${stem.toLowerCase()}${ext.toLowerCase()}`]);
  return [...new Set(names)];
}

const ROLE_ORDER = (name: string) => {
  const role = wolfRole(name);
  return role ? ROLES.indexOf(role) : ROLES.length;
};

export const WOLF3D_FORMAT: SceneFormat = {
  id: 'wolf3d',
  kind: 'scene',
  description: 'Wolfenstein 3D data files',
  extensions: EXTENSIONS,
  // Only GAMEMAPS carries a signature; MAPHEAD and VSWAP are known by their extension.
  sniff: (head) => head.length >= GAMEMAPS_SIGNATURE.length && String.fromCharCode(...head.subarray(0, GAMEMAPS_SIGNATURE.length)) === GAMEMAPS_SIGNATURE,
  linkParam: 'wolf',
  stacks: true,
  example: 'folder#E1L1 or MAPHEAD.WL1+GAMEMAPS.WL1+VSWAP.WL1#E1L1',
  part: { noun: 'map', linkParam: 'map', normalize: normalizePart },
  parseReference(argument) {
    return parseWolfReference(argument);
  },
  filesInFolder(names) {
    return wolfFilesInFolder(names);
  },
  arrange: <T extends FileHead>(files: readonly T[]) => files.map((f, i) => ({ f, i })).sort((a, b) => ROLE_ORDER(a.f.name) - ROLE_ORDER(b.f.name) || a.i - b.i).map((x) => x.f),
  siblings(main) {
    const role = wolfRole(main.name);
    return role ? ROLES.filter((r) => r !== role).map((r) => siblingNames(main.name, r)[0]!) : [];
  },
  async open(set) {
    if (set.files.length === 0) throw new LanternError('no Wolfenstein 3D file was given', SET_HINT);
    const found: Partial<Record<Role, NamedBytes>> = {};
    // A whole game among the files (a dropped folder, perhaps with both .WL1 and .WL6): that one.
    const complete = wolfFilesInFolder(set.files.map((f) => f.name));
    const given = complete ? complete.map((name) => set.files.find((f) => f.name === name)!) : set.files;
    for (const file of given) {
      const role = wolfRole(file.name);
      if (!role) continue;
      const already = found[role];
      if (already) throw new LanternError(`cannot open ${already.name} and ${file.name} together: both are ${ROLE_NAMES[role][0]} files`, SET_HINT);
      found[role] = file;
    }
    const main = ROLES.map((r) => found[r]).find((f) => f !== undefined);
    if (!main) {
      throw new LanternError(`${set.files.map((f) => f.name).join(', ')}: none of them is MAPHEAD, GAMEMAPS or VSWAP`, SET_HINT);
    }
    for (const role of ROLES) {
      if (found[role]) continue;
      for (const name of siblingNames(main.name, role)) {
        const bytes = await set.resolve(name);
        if (bytes) {
          found[role] = { name, bytes };
          break;
        }
      }
      if (!found[role]) throw new LanternError(`${main.name}: ${siblingNames(main.name, role)[0]} is missing beside it`, SET_HINT);
    }
    const files = { maphead: found.maphead!, gamemaps: found.gamemaps!, vswap: found.vswap! };
    return openGame(readWolfGame(files), `${files.maphead.name} + ${files.gamemaps.name} + ${files.vswap.name}`);
  },
};

/**
 * `a/MAPHEAD.WL1+a/GAMEMAPS.WL1+a/VSWAP.WL1#E1L2`, `a/VSWAP.WL1#3` or `a/MAPHEAD.WL1`: paths that
 * all end in .WL1 or .WL6, then an optional `#map`. A folder (`a#E1L1`) is the CLI's to see
 * (filesInFolder): nothing in the string says it is one.
 */
export function parseWolfReference(argument: string): SceneReference | undefined {
  const hash = argument.lastIndexOf('#');
  const [path, fragment] = EXTENSION.test(argument) || hash < 0 ? [argument, undefined] : [argument.slice(0, hash), argument.slice(hash + 1)];
  const paths = path.split('+');
  if (!paths.every((p) => EXTENSION.test(p))) return undefined;
  if (fragment === undefined || fragment === '') return { paths };
  if (mapIndexOf(fragment) === undefined) {
    throw new LanternError(`'${argument}': '${fragment}' is not a map`, 'Name a Wolfenstein 3D map as E1L1 (episode 1, level 1) or by its number from 1');
  }
  return { paths, part: normalizePart(fragment) };
}

/** The files of a set in a folder's listing (MAPHEAD, GAMEMAPS, VSWAP of one extension), or undefined when there is none. */
export function wolfFilesInFolder(names: readonly string[]): string[] | undefined {
  const byExtension = new Map<string, Partial<Record<Role, string>>>();
  for (const name of names) {
    const role = wolfRole(name);
    if (!role) continue;
    const ext = extensionOf(name);
    const set = byExtension.get(ext) ?? {};
    set[role] ??= name;
    byExtension.set(ext, set);
  }
  // The registered game before the shareware where a folder has both.
  for (const ext of ['WL6', 'WL1']) {
    const set = byExtension.get(ext);
    if (set && ROLES.every((r) => set[r])) return ROLES.map((r) => set[r]!);
  }
  return undefined;
}

function openGame(game: WolfGame, description: string): OpenedScene {
  return {
    description,
    parts: game.maps.map((m) => ({ name: m.id, loadable: true })),
    partNamed(name) {
      const index = mapIndexOf(name);
      return game.maps.find((m) => m.index === index)?.id;
    },
    async scene(part, options = {}) {
      const map = game.map(part ?? game.maps[0]!.id);
      if (!options.onWarning) return wolfMapToScene(game, map, options);
      // Capped per kind, as Doom's and glTF's: a map whose every tile is a second player start printed 32,040 lines.
      const cap = new WarningCap(options.onWarning);
      try {
        return wolfMapToScene(game, map, { ...options, onWarning: cap.warn });
      } finally {
        cap.finish();
      }
    },
    inventory() {
      const rows = game.maps.map((info) => {
        try {
          return { ...info, ...countTiles(game.map(info.id)) };
        } catch (e) {
          // Each map answers for itself, as in the Doom listing: a bug on one map is that map's line.
          return { ...info, error: e instanceof LanternError ? e.message : `internal error: ${e instanceof Error ? e.message : String(e)}` };
        }
      });
      const lines = [
        `Wolfenstein 3D (.${game.extension}): ${rows.length} maps, ${game.graphics.wallCount} wall pages, ${game.graphics.spriteCount} sprites`,
        '  map    title               size    walls  doors  statics',
        ...rows.map((r) =>
          'error' in r
            ? `  ${r.id.padEnd(6)} ${r.error}`
            : `  ${r.id.padEnd(6)} ${r.title.padEnd(18)} ${`${r.width}×${r.height}`.padStart(5)}  ${String(r.walls).padStart(6)} ${String(r.doors).padStart(6)} ${String(r.statics).padStart(8)}`,
        ),
      ];
      return { lines, json: { extension: game.extension, wallPages: game.graphics.wallCount, sprites: game.graphics.spriteCount, maps: rows } };
    },
  };
}

/** Counts of a map's wall tiles (plane 0 codes 1–63), doors (90–101) and static objects (plane 1 codes 23–74). */
export function countTiles(map: { readonly planes: readonly [Uint16Array, Uint16Array, Uint16Array] }): { walls: number; doors: number; statics: number } {
  let walls = 0;
  let doors = 0;
  let statics = 0;
  for (const code of map.planes[0]) {
    if (code >= 1 && code <= 63) walls++;
    else if (code >= 90 && code <= 101) doors++;
  }
  for (const code of map.planes[1]) if (code >= 23 && code <= 74) statics++;
  return { walls, doors, statics };
}
