/**
 * What a file format is to Lantern: how it is recognised (extensions, magic bytes), how several
 * files form one set (a WAD stack, a glTF with its buffers and textures), and how the set becomes a
 * Scene. Every format implements this in its own folder (doom/format.ts, ply/format.ts); the list
 * of formats is registry.ts. Pure: loaders see bytes and a resolver, never paths, fetch or the DOM.
 */
import type { LightTable } from './doom/light-table.ts';
import type { Scene } from '../scene/types.ts';

/** A file as the user named it (messages say this name) and its contents. */
export interface NamedBytes {
  readonly name: string;
  readonly bytes: Uint8Array;
}

/**
 * Finds a file that the main file refers to by a path relative to it ('/'-separated, as a glTF
 * `uri`), or undefined when there is none: the loader decides whether that is fatal (a missing
 * texture is not). Asynchronous because the page may have to fetch it.
 */
export type ResolveSibling = (relativePath: string) => Promise<Uint8Array | undefined>;

/** The load input: the files the user named, in the format's order, plus their siblings. */
export interface FileSet {
  /** One file for most formats; a WAD stack holds the IWAD first, then PWADs in load order. */
  readonly files: readonly NamedBytes[];
  readonly resolve: ResolveSibling;
}

export const NO_SIBLINGS: ResolveSibling = () => Promise.resolve(undefined);

export interface LoadOptions {
  readonly onWarning?: (message: string) => void;
  /** Doom only: light table overrides (doom/light-table.ts). */
  readonly lightTable?: Partial<LightTable>;
  /** Doom: the skill level (1–5, default 3) whose things appear (doom/thing-types.ts); Wolfenstein 3D: whose actors appear (1–4, 5 counts as 4, default 3). */
  readonly skill?: number;
}

/** A file named for recognition: its name and its first bytes (SNIFF_BYTES of them suffice). */
export interface FileHead {
  readonly name: string;
  readonly head: Uint8Array;
}

/** How many leading bytes `sniff` needs; readers may pass the whole file. */
export const SNIFF_BYTES = 1024;

/** Fields every kind of file format has: scenes today, environment maps (.hdr, .exr) next. */
export interface FileFormat {
  /** Stable id: links and messages between the page and its worker name formats by it. */
  readonly id: string;
  readonly kind: 'scene' | 'environment';
  /** For people, in the plural: "Doom WADs". */
  readonly description: string;
  /** Lower-case, with the dot, longest first: ['.ply.gz', '.ply']. */
  readonly extensions: readonly string[];
  /** Extensions of the files a main file refers to (glTF: .bin, .png, .jpg): a file picker must accept them too. */
  readonly siblingExtensions?: readonly string[];
  /** True when the first bytes are this format's; content beats the extension. */
  sniff(head: Uint8Array): boolean;
  /** The page's URL parameter naming a served file of this format (`wad=`, `ply=`). */
  readonly linkParam: string;
  /** Several named files make one set (joined by '+' in a scene argument, repeated link parameters). */
  readonly stacks: boolean;
  /** A scene argument of this format's own shape, for help texts: 'iwad.wad+pwad.wad#MAP01'. */
  readonly example?: string;
  /** What one file holds several of, selected by `#name` in a scene argument (Doom: 'map'), and its link parameter. */
  readonly part?: {
    readonly noun: string;
    readonly linkParam: string;
    /** The canonical spelling of a part name from a link (Doom map names are upper case). */
    normalize?(name: string): string;
  };
  /**
   * Splits a scene argument that names files of this format (`iwad.wad+pwad.wad#MAP01`) into paths
   * and the part, or undefined when the argument is not of this format's shape. Formats without it
   * take a plain path. May throw a LanternError for a malformed argument of its shape.
   */
  parseReference?(argument: string): SceneReference | undefined;
  /**
   * The names, among a folder's, of the files that make one set of this format (Wolfenstein 3D:
   * MAPHEAD, GAMEMAPS and VSWAP), or undefined when the folder holds none: a folder named as a
   * scene argument, or dropped on the page, opens as that set. Formats without it are never folders.
   */
  filesInFolder?(names: readonly string[]): readonly string[] | undefined;
  /** The files of one set in load order (Doom: IWADs before PWADs); the given order otherwise. */
  arrange?<T extends FileHead>(files: readonly T[]): T[];
}

export interface SceneReference {
  readonly paths: readonly string[];
  readonly part?: string;
}

export interface SceneFormat extends FileFormat {
  readonly kind: 'scene';
  /** Reads the set; what can go wrong with the files themselves is thrown here, as a LanternError. */
  open(set: FileSet, options?: LoadOptions): Promise<OpenedScene>;
  /**
   * Paths, relative to the main file, of the siblings it refers to: `lantern view` serves these and
   * nothing else beside it. Formats without siblings leave it out.
   */
  siblings?(main: NamedBytes): readonly string[];
  /**
   * Checks a main file's own structure from its size and the few byte ranges it reads, without
   * reading the file whole (a truncated or damaged container), so that a front end can refuse it
   * before slow work starts: the CLI does, before the GPU starts. Throws a LanternError; open() and
   * the scene's load find the same again. Formats without it are checked when they are read.
   */
  checkFile?(name: string, size: number, read: (offset: number, length: number) => Uint8Array): void;
}

export interface ScenePart {
  readonly name: string;
  /** False for parts Lantern cannot build (a Hexen-format map); `note` says why. */
  readonly loadable: boolean;
  readonly note?: string;
}

/** An opened file set: what it holds, and its scenes on demand (a WAD keeps its textures between maps). */
export interface OpenedScene {
  /** "freedoom1.wad + mymod.wad". */
  readonly description: string;
  /** The parts to choose from, in order; empty when the set is one scene. */
  readonly parts: readonly ScenePart[];
  /**
   * The listed part another spelling names (an SD file's record by its number or title), or undefined
   * when none does. Without it, a part is named exactly as listed.
   */
  partNamed?(name: string): string | undefined;
  /** The scene of `part`, or of the first loadable part (or the only scene) when undefined. */
  scene(part?: string, options?: LoadOptions): Promise<Scene>;
  /** A listing of the parts with their counts, for `lantern info` (text lines and JSON); `options.skill` for Doom's things. */
  inventory?(options?: LoadOptions): { readonly lines: readonly string[]; readonly json: unknown };
}
