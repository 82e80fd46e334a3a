/**
 * What the page asks the scene worker for, and the pure code that answers: built-in scenes, Doom
 * maps from a stack of WAD files (IWAD first, PWADs after), PLY meshes. Everything here runs in a
 * Web Worker (scene-worker.ts) so that a large level never freezes the page, and in unit tests.
 */
import { LanternError } from '../errors.ts';
import { builtinScene, isBuiltinScene } from '../loaders/builtin/index.ts';
import { loadDoomMap } from '../loaders/doom/load.ts';
import { DoomGraphics } from '../loaders/doom/textures.ts';
import { readWad, WadStack, type MapFormat } from '../loaders/doom/wad.ts';
import { loadPly } from '../loaders/ply/ply.ts';
import { prepareScene, PREPARE_STAGES, type PreparedScene } from '../renderer/prepare.ts';
import type { Scene } from '../scene/types.ts';

export interface NamedBytes {
  readonly name: string;
  readonly bytes: Uint8Array;
}

export type SceneRequest =
  | { readonly kind: 'builtin'; readonly name: string }
  /** A map of the WAD stack last opened with `openWads`. */
  | { readonly kind: 'doom-map'; readonly map: string }
  | { readonly kind: 'ply'; readonly file: NamedBytes };

export interface WadSummary {
  /** "freedoom1.wad + mymod.wad". */
  readonly description: string;
  readonly maps: readonly { readonly name: string; readonly format: MapFormat }[];
}

export interface LoadedScene {
  readonly prepared: PreparedScene;
  /** What the loader warned about (missing textures, unclosed sectors). */
  readonly warnings: readonly string[];
  readonly loadMs: number;
}

export type ProgressListener = (stage: string, fraction: number) => void;

/** Loading stages and the fraction of the work done when each begins (rough, for a progress bar). */
const LOAD_STAGE = 'building the scene';
const STAGE_FRACTIONS: Record<string, number> = { [LOAD_STAGE]: 0.05, [PREPARE_STAGES[0]]: 0.45, [PREPARE_STAGES[1]]: 0.5, [PREPARE_STAGES[2]]: 0.9 };

/** Holds the open WAD stack between requests, so that picking another map reuses its textures. */
export class SceneRequests {
  private stack?: WadStack;
  private graphics?: DoomGraphics;

  /** Reads a stack of WAD files (IWAD first); throws a LanternError naming a file that is not a WAD. */
  openWads(files: readonly NamedBytes[]): WadSummary {
    if (files.length === 0) throw new LanternError('no WAD file was given');
    const stack = new WadStack(files.map((f) => readWad(f.bytes, f.name)));
    const maps = stack.maps().map((m) => ({ name: m.name, format: m.format }));
    if (maps.length === 0) throw new LanternError(`${stack.describe()} has no maps`, 'Open an IWAD (such as freedoom1.wad) or a PWAD that contains maps');
    this.stack = stack;
    this.graphics = undefined;
    return { description: stack.describe(), maps };
  }

  load(request: SceneRequest, onProgress: ProgressListener = () => {}): LoadedScene {
    const t0 = performance.now();
    const warnings: string[] = [];
    const onWarning = (w: string) => warnings.push(w);
    onProgress(LOAD_STAGE, STAGE_FRACTIONS[LOAD_STAGE]!);
    const scene = this.scene(request, onWarning);
    const prepared = prepareScene(scene, (stage) => onProgress(stage, STAGE_FRACTIONS[stage] ?? 0));
    onProgress('done', 1);
    return { prepared, warnings, loadMs: performance.now() - t0 };
  }

  private scene(request: SceneRequest, onWarning: (w: string) => void): Scene {
    switch (request.kind) {
      case 'builtin':
        if (!isBuiltinScene(request.name)) throw new LanternError(`unknown scene '${request.name}'`);
        return builtinScene(request.name);
      case 'ply':
        return loadPly(request.file.bytes, request.file.name, { onWarning });
      case 'doom-map': {
        if (!this.stack) throw new LanternError('no WAD is open', 'Open a WAD file first');
        this.graphics ??= new DoomGraphics(this.stack, { onWarning });
        const loaded = loadDoomMap(this.stack, request.map, { onWarning, graphics: this.graphics });
        if (loaded.failures.length > 0) onWarning(`${loaded.failures.length} sector(s) of ${loaded.map.name} could not be triangulated`);
        return loaded.scene;
      }
    }
  }
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
