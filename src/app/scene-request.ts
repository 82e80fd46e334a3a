/**
 * What the page asks the scene worker for, and the pure code that answers: built-in scenes, and
 * scenes from a file set of any format in the loader registry (a Doom WAD stack and its maps, a
 * PLY mesh). Everything here runs in a Web Worker (scene-worker.ts) so that a large level never
 * freezes the page, and in unit tests.
 */
import { LanternError } from '../errors.ts';
import { builtinScene, isBuiltinScene } from '../loaders/builtin/index.ts';
import { formatById, type NamedBytes, type OpenedScene, type ResolveSibling, type ScenePart } from '../loaders/registry.ts';
import { normalizeRelativePath } from './dropped-files.ts';
import { prepareSceneAsync, PREPARE_STAGES, type PreparedScene } from '../renderer/prepare.ts';
import type { BvhWorkerPool } from '../bvh/build-parallel.ts';
import type { Scene } from '../scene/types.ts';

export type { NamedBytes };

/** Files the page sorted with the registry (loaders/registry.ts sortFiles): one scene's set. */
export interface OpenFilesRequest {
  /** A registry id. */
  readonly format: string;
  /** The set's files in load order (a WAD stack: IWAD first). */
  readonly files: readonly NamedBytes[];
  /** Files given alongside (a glTF's .bin and textures, dropped with it), by name or relative path. */
  readonly siblings: readonly NamedBytes[];
  /** Where the main file was served from, so that siblings not given can be fetched beside it. */
  readonly baseUrl?: string;
}

export type SceneRequest =
  | { readonly kind: 'builtin'; readonly name: string }
  /** A scene of the file set last opened with `openFiles`: a map of a WAD, or the set's only scene. */
  | { readonly kind: 'part'; readonly part?: string; readonly skill?: number };

export interface FileSetSummary {
  readonly format: string;
  /** "freedoom1.wad + mymod.wad". */
  readonly description: string;
  /** What the set holds several of (maps), empty for a one-scene set. */
  readonly parts: readonly ScenePart[];
}

export interface LoadedScene {
  readonly prepared: PreparedScene;
  /** What the loader warned about (missing textures, unclosed sectors). */
  readonly warnings: readonly string[];
  readonly loadMs: number;
}

export type ProgressListener = (stage: string, fraction: number) => void;

/** Fetches a file by absolute URL, undefined when the server has none (injected: the worker fetches, tests do not). */
export type FetchFile = (url: string) => Promise<Uint8Array | undefined>;

/** Loading stages and the fraction of the work done when each begins (rough, for a progress bar). */
const LOAD_STAGE = 'building the scene';
const STAGE_FRACTIONS: Record<string, number> = { [LOAD_STAGE]: 0.05, [PREPARE_STAGES[0]]: 0.45, [PREPARE_STAGES[1]]: 0.5, [PREPARE_STAGES[2]]: 0.9 };

/** Holds the open file set between requests, so that picking another map reuses its textures. */
export class SceneRequests {
  private opened?: OpenedScene;

  /** `bvhPool`: workers for the BVH build (bvh/build-parallel.ts; the same tree), none in tests. */
  constructor(
    private readonly fetchFile: FetchFile = () => Promise.resolve(undefined),
    private readonly bvhPool: () => BvhWorkerPool | undefined = () => undefined,
  ) {}

  /** Opens a file set; throws a LanternError naming a file that is not what its format expects. */
  async openFiles(request: OpenFilesRequest): Promise<FileSetSummary> {
    const format = formatById(request.format);
    if (!format) throw new Error(`no format '${request.format}' in the registry`);
    if (request.files.length === 0) throw new LanternError('no file was given');
    const opened = await format.open({ files: request.files, resolve: siblingResolver(request, this.fetchFile) });
    if (format.part && opened.parts.length > 0 && !opened.parts.some((p) => p.loadable)) {
      throw new LanternError(`${opened.description} has no ${format.part.noun} Lantern can build`, opened.parts.map((p) => `${p.name}: ${p.note ?? 'not supported'}`).slice(0, 3).join('; '));
    }
    this.opened = opened;
    return { format: format.id, description: opened.description, parts: opened.parts };
  }

  async load(request: SceneRequest, onProgress: ProgressListener = () => {}): Promise<LoadedScene> {
    const t0 = performance.now();
    const warnings: string[] = [];
    const onWarning = (w: string) => warnings.push(w);
    onProgress(LOAD_STAGE, STAGE_FRACTIONS[LOAD_STAGE]!);
    const scene = await this.scene(request, onWarning);
    // Loaders report through onWarning or in Scene.warnings (the glTF loader's missing textures):
    // both reach the page, each once.
    for (const w of scene.warnings ?? []) if (!warnings.includes(w)) warnings.push(w);
    const prepared = await prepareSceneAsync(scene, (stage) => onProgress(stage, STAGE_FRACTIONS[stage] ?? 0), { bvhPool: this.bvhPool() });
    onProgress('done', 1);
    return { prepared, warnings, loadMs: performance.now() - t0 };
  }

  private scene(request: SceneRequest, onWarning: (w: string) => void): Promise<Scene> {
    switch (request.kind) {
      case 'builtin':
        if (!isBuiltinScene(request.name)) throw new LanternError(`unknown scene '${request.name}'`);
        return Promise.resolve(builtinScene(request.name));
      case 'part':
        if (!this.opened) throw new LanternError('no file is open', 'Open a file first');
        return this.opened.scene(request.part, { onWarning, ...(request.skill !== undefined ? { skill: request.skill } : {}) });
    }
  }
}

/**
 * A file set's siblings: those given with it (dropped or picked together) by name or by their path
 * inside a picked folder, else fetched beside the served main file, else absent.
 */
export function siblingResolver(request: Pick<OpenFilesRequest, 'siblings' | 'baseUrl'>, fetchFile: FetchFile): ResolveSibling {
  return (reference) => {
    // The page names siblings by their path relative to the main file's folder: an exact match
    // first, so that two textures of the same name in different folders are not confused; then a
    // path that ends the same way (files picked from several folders, or a loose texture).
    const relativePath = normalizeRelativePath(reference);
    const given =
      request.siblings.find((f) => normalizeRelativePath(f.name) === relativePath) ??
      request.siblings.find((f) => f.name.endsWith(`/${relativePath}`) || relativePath.endsWith(`/${f.name}`));
    if (given) return Promise.resolve(given.bytes);
    return request.baseUrl ? fetchFile(new URL(reference, request.baseUrl).href) : Promise.resolve(undefined);
  };
}

/** Every ArrayBuffer reachable from `value`, once each: the transfer list of a worker message. */
export function transferables(value: unknown, found = new Set<ArrayBuffer>()): ArrayBuffer[] {
  if (value instanceof ArrayBuffer) found.add(value);
  else if (ArrayBuffer.isView(value)) {
    if (value.buffer instanceof ArrayBuffer) found.add(value.buffer);
  } else if (Array.isArray(value)) for (const v of value) transferables(v, found);
  else if (value && typeof value === 'object') for (const v of Object.values(value)) transferables(v, found);
  return [...found];
}
