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
}

/**
 * `output` hears of what the loader worked around (warn), of information (note: the GPU fallback,
 * how the scene is lit) and of Dawn's own lines (dawnOutput, shown with --verbose).
 */
export async function openSession(sceneArg: string, output: Pick<CliContext, 'note' | 'warn' | 'dawnOutput'>, sceneOptions: SceneOptionValues = {}, environment?: Environment, options: SessionOptions = {}): Promise<Session> {
  const { adjust, timeline, progressive = true, check } = options;
  // A damaged file is refused before the GPU starts (and before Dawn has printed anything).
  checkSceneFiles(sceneArg);
  const loading = loadPreparedInThread(sceneArg, output.warn, sceneOptions, environment, adjust, timeline);
  // Reported by the await below; the GPU's own errors wait for it (a missing file says so first).
  loading.catch(() => undefined);
  let renderer: Renderer | undefined;
  try {
    const gpu = await acquireNodeGpu({ onNote: output.note, onDawnOutput: output.dawnOutput, ...(timeline ? { onStage: timeline.add.bind(timeline) } : {}) });
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
