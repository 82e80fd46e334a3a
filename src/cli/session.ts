/**
 * What every GPU command starts with: load the scene, acquire a device (noting a SwiftShader
 * fallback), create the renderer and upload the scene. The scene loads on a worker thread
 * (scene-thread.ts) while this one starts the GPU and compiles the tone mapper; then the path
 * tracer is compiled for that scene alone, where the command accumulates (a progressive render);
 * what else it runs it compiles itself (Renderer.compile). Its reflection was made when the bundle
 * was built.
 */
import type { PreparedScene } from '../renderer/prepare.ts';
import type { Environment } from '../scene/environment.ts';
import { Renderer } from '../renderer/renderer.ts';
import type { Scene } from '../scene/types.ts';
import { observeStages } from '../gpu/stage-log.ts';
import { bsdfTableData } from '../gpu/pack/bsdf-tables.ts';
import type { CliContext } from './context.ts';
import { acquireNodeGpu } from './dawn.ts';
import type { SceneOptionValues } from './options.ts';
import { checkSceneFiles } from './scene-precheck.ts';
import { loadPreparedInThread } from './scene-thread.ts';
import type { Timeline } from './timeline.ts';

export interface Session {
  readonly renderer: Renderer;
  readonly prepared: PreparedScene;
  readonly loadMs: number;
}

export interface SessionOptions {
  /** Changes the loaded scene before it is prepared (bench --levels). */
  readonly adjust?: (scene: Scene) => Scene;
  /** Hears of every start-up step. */
  readonly timeline?: Timeline;
  /**
   * Whether the command accumulates (default true): the progressive path tracer then compiles as
   * soon as the scene's features are known; without, never (frame mode, a debug view alone, rays timed).
   */
  readonly progressive?: boolean;
  /**
   * What the command checks of the loaded scene and the device's limits (an image size, a lens the
   * scene's camera lacks): run before any kernel of the scene compiles, so that a mistake costs the
   * load, not a compile. A LanternError it throws is the command's error.
   */
  readonly check?: (prepared: PreparedScene, limits: GPUSupportedLimits) => void;
  /** What a process that keeps its scene (output.sessions) keeps it by: commands with one key share one load. */
  readonly sceneKey?: string;
}

/**
 * `output` hears of what the loader worked around (warn), of information (note: the GPU fallback,
 * how the scene is lit) and of Dawn's own lines (dawnOutput, shown with --verbose).
 */
export async function openSession(sceneArg: string, output: Pick<CliContext, 'note' | 'warn' | 'dawnOutput' | 'sessions'>, sceneOptions: SceneOptionValues = {}, environment?: Environment, options: SessionOptions = {}): Promise<Session> {
  const { adjust, timeline, progressive = true, check, sceneKey } = options;
  // A damaged file is refused before the GPU starts (and before Dawn has printed anything).
  checkSceneFiles(sceneArg);
  // A process that keeps its scene (session-cache.ts) loads it once for the commands that share a key.
  const cache = output.sessions;
  const keep = cache !== undefined && sceneKey !== undefined && !adjust;
  const kept = keep && cache.scene?.key === sceneKey ? cache.scene.loading : undefined;
  const loaded = kept ?? loadPreparedInThread(sceneArg, output.warn, sceneOptions, environment, adjust, timeline);
  if (keep) {
    cache.scene = { key: sceneKey, loading: loaded };
    loaded.catch(() => {
      if (cache.scene?.loading === loaded) cache.scene = undefined;
    });
  }
  // A kept scene is copied for each command: rendering moves its instances and doors, and the next
  // command starts from the scene as loaded (a structured clone: what crossed from the scene thread
  // is plain data).
  const loading = keep ? loaded.then((l) => ({ prepared: structuredClone(l.prepared), loadMs: kept ? 0 : l.loadMs })) : loaded;
  // Reported by the await below; the GPU's own errors wait for it (a missing file says so first).
  loading.catch(() => undefined);
  let renderer: Renderer | undefined;
  try {
    const acquire = () => acquireNodeGpu({ onNote: output.note, onDawnOutput: output.dawnOutput, ...(timeline ? { onStage: timeline.add.bind(timeline) } : {}) });
    const gpu = await (cache ? (cache.gpu ??= acquire()) : acquire());
    if (timeline) observeStages(gpu.device, timeline.add.bind(timeline));
    // The tone mapper compiles while the scene loads; then only the variant this scene needs
    // compiles (of the progressive path tracer, for a command that accumulates), and the scene uploads.
    const features = loading.then(({ prepared }) => {
      check?.(prepared, gpu.device.limits);
      return prepared.packed.features;
    });
    const creating = Renderer.create(gpu, { features, progressive });
    // While the threads work: the BSDF tables every scene upload binds (computed once per process).
    const t0 = performance.now();
    bsdfTableData();
    timeline?.end('BSDF tables', t0);
    renderer = await creating;
  } catch (e) {
    await loading;
    throw e;
  }
  const { prepared, loadMs } = await loading;
  // How the scene is lit when it keeps its own light (a default sky, or its emitters): information.
  // An environment given on the command line replaced it, and the note with it.
  if (prepared.scene.lightingNote) output.note(`${prepared.scene.name}: ${prepared.scene.lightingNote}`);
  await renderer.setScene(prepared);
  return { renderer, prepared, loadMs };
}
