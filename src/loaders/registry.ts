/**
 * The one list of file formats Lantern reads, and everything that recognises them: scene
 * arguments (`freedoom1.wad#E1M1`, `iwad.wad+pwad.wad#MAP01`, `mesh.ply.gz`), files picked or
 * dropped on the page, the file picker's `accept`, help texts and the one-line error for a file
 * that is no known format. Adding a format is one entry in FORMATS (its folder exports a
 * SceneFormat, format.ts). Built-in scenes are named, not files, and are listed here too so that
 * every front end describes the same choices. Pure: no DOM, no node:*.
 */
import { LanternError } from '../errors.ts';
import { builtinSceneNames } from './builtin/index.ts';
import { WAD_FORMAT } from './doom/format.ts';
import type { FileFormat, FileHead, SceneFormat, SceneReference } from './format.ts';
import { GLTF_FORMAT } from './gltf/format.ts';
import { MOLECULE_FORMAT } from './molecule/format.ts';
import { PLY_FORMAT } from './ply/format.ts';
import { WOLF3D_FORMAT } from './wolf3d/format.ts';

export type * from './format.ts';
export { NO_SIBLINGS, SNIFF_BYTES } from './format.ts';

/** Every format, in the order help texts name them. Environment maps join as `kind: 'environment'` entries. */
export const FORMATS: readonly SceneFormat[] = [WAD_FORMAT, GLTF_FORMAT, PLY_FORMAT, MOLECULE_FORMAT, WOLF3D_FORMAT];

export function formatById(id: string): SceneFormat | undefined {
  return FORMATS.find((f) => f.id === id);
}

/** The format whose extension the name ends with (case-insensitive), or undefined. */
export function formatByName<F extends FileFormat>(name: string, formats: readonly F[] = FORMATS as unknown as readonly F[]): F | undefined {
  const lower = name.toLowerCase();
  return formats.find((f) => f.extensions.some((e) => lower.endsWith(e)));
}

/**
 * The format of a file: its content first, because a mesh saved as `level.wad` or a WAD
 * downloaded as `file.bin` should still open; the extension only when no format claims the bytes,
 * so that a truncated `.wad` gets the WAD reader's precise complaint instead of "unknown format".
 */
export function identify<F extends FileFormat>(file: FileHead, formats: readonly F[] = FORMATS as unknown as readonly F[]): F | undefined {
  return formats.find((f) => f.sniff(file.head)) ?? formatByName(file.name, formats);
}

/** "Doom WADs (.wad) and PLY meshes (.ply.gz, .ply)": what Lantern reads, for hints and help. */
export function describeFormats(formats: readonly FileFormat[] = FORMATS): string {
  const each = formats.map((f) => `${f.description} (${f.extensions.join(', ')})`);
  return each.length <= 1 ? each.join('') : `${each.slice(0, -1).join(', ')} and ${each.at(-1)}`;
}

/** The error for a file that is no known format: one line naming the formats Lantern reads. */
export function unknownFormat(names: readonly string[]): LanternError {
  return new LanternError(`cannot open ${names.map((n) => `'${n}'`).join(', ')}: not a format Lantern reads`, `Lantern reads ${describeFormats()}`);
}

/** The file picker's `accept`: every format's extensions and its siblings' (browsers match the last dot). */
export function acceptedExtensions(formats: readonly FileFormat[] = FORMATS): string {
  const all = formats.flatMap((f) => [...f.extensions, ...(f.siblingExtensions ?? [])]).map((e) => e.slice(e.lastIndexOf('.')));
  return [...new Set(all)].join(',');
}

/** The scene-argument help: built-ins, then each format with its argument shape. */
export function describeSceneArguments(aliases: readonly string[] = []): string {
  const shapes = FORMATS.map((f) => {
    const how = [...f.extensions, ...(f.stacks ? ["'+' joins files"] : []), ...(f.part ? [`'#${f.part.noun}' picks one`] : [])].join(', ');
    return `${f.description} (${how}${f.example ? `: ${f.example}` : ''})`;
  });
  return `a built-in scene (${builtinSceneNames().join(', ')})${aliases.map((a) => `, '${a}'`).join('')}, or a file: ${shapes.join(', ')}`;
}

/**
 * Splits a scene argument into file paths and a part: the first format whose shape it has
 * (`a.wad+b.wad#E1M1`) decides; anything else is one path, whose format is found from its bytes.
 */
export function parseSceneReference(argument: string): SceneReference & { readonly format?: SceneFormat } {
  for (const format of FORMATS) {
    const reference = format.parseReference?.(argument);
    if (reference) return { ...reference, format };
  }
  return { paths: [argument] };
}

/** The first format that finds a set of its files among a folder's names, and those names in load order; undefined for none. */
export function formatOfFolder(names: readonly string[]): { format: SceneFormat; names: readonly string[] } | undefined {
  for (const format of FORMATS) {
    const found = format.filesInFolder?.(names);
    if (found) return { format, names: found };
  }
  return undefined;
}

/** The formats of the files named together, checked to make one set; the set's files in load order. */
export function formatOfSet<T extends FileHead>(files: readonly T[]): { format: SceneFormat; files: T[] } {
  const formats = files.map((f) => identify(f, FORMATS));
  const unknown = files.filter((_, i) => !formats[i]);
  if (unknown.length > 0) throw unknownFormat(unknown.map((f) => f.name));
  const format = formats[0];
  if (!format) throw new LanternError('no file was given');
  const otherAt = formats.findIndex((f) => f !== format);
  if (otherAt >= 0) {
    throw new LanternError(`cannot open ${files[0]!.name} and ${files[otherAt]!.name} as one scene: they are ${format.description} and ${formats[otherAt]!.description}`, 'Open one scene at a time');
  }
  if (files.length > 1 && !format.stacks) throw new LanternError(`cannot open ${files.map((f) => f.name).join(', ')} together: ${format.description} are one file each`, 'Open one at a time');
  return { format, files: format.arrange ? format.arrange(files) : [...files] };
}

/**
 * Sorts files picked or dropped together (a WAD stack, a glTF folder with its .bin and textures)
 * into the scene's main files and the siblings they may refer to. Files no format claims are
 * siblings as long as some file is a scene; if none is, the error lists what Lantern reads.
 * A mix of scene formats is refused rather than guessed at.
 */
export function sortFiles<T extends FileHead>(files: readonly T[]): { format: SceneFormat; main: T[]; siblings: T[] } {
  const mains = files.filter((f) => identify(f));
  if (mains.length === 0) throw unknownFormat(files.map((f) => f.name));
  const { format, files: main } = formatOfSet(mains);
  return { format, main, siblings: files.filter((f) => !mains.includes(f)) };
}
