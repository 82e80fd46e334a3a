/**
 * Start-up work on a worker thread while the main thread starts the GPU (Dawn, the tone mapper's
 * pipeline): loading and preparing the scene (read, parse, BVH, pack). Dawn for Node compiles
 * pipelines on the thread that calls it (inside its event processing), and loading is plain
 * JavaScript, so on one thread they would not overlap. (The path tracer's WGSL was parsed on a
 * second thread too, for its bindings, until the build reflected it: gpu/wgsl/precomputed.ts.)
 *
 * A worker runs this same bundle: main.ts hands over to runSceneThread when it is not the main
 * thread. Run from sources (tests), where there is no bundle to start, everything runs in-thread.
 */
import { fileURLToPath } from 'node:url';
import { statSync } from 'node:fs';
import { isMainThread, parentPort, Worker, workerData } from 'node:worker_threads';
import { LanternError } from '../errors.ts';
import type { StageSpan } from '../gpu/stage-log.ts';
import { prepareSceneAsync, type PreparedScene } from '../renderer/prepare.ts';
import { nodeBvhPool } from './bvh-workers.ts';
import type { Environment } from '../scene/environment.ts';
import { withEnvironment } from '../scene/environment-override.ts';
import type { Scene } from '../scene/types.ts';
import type { SceneOptionValues } from './options.ts';
import { BUNDLE_START_MS } from './process-clock.ts';
import { loadSceneArgument, sceneLoadOptions } from './scene-source.ts';
import { Timeline } from './timeline.ts';

export interface LoadedPrepared {
  readonly prepared: PreparedScene;
  /** Milliseconds from the start of reading to the prepared scene. */
  readonly loadMs: number;
}

type ThreadRequest = {
  readonly role: 'lantern-scene-thread';
  /** The main thread's performance.timeOrigin: the worker's spans are moved onto its clock. */
  readonly mainTimeOrigin: number;
} & { readonly task: 'scene'; readonly sceneArg: string; readonly sceneOptions: SceneOptionValues; readonly environment?: Environment };

type ThreadReply =
  | { readonly type: 'note'; readonly message: string }
  | { readonly type: 'spans'; readonly spans: readonly StageSpan[] }
  | { readonly type: 'done'; readonly result: LoadedPrepared }
  | { readonly type: 'error'; readonly message: string; readonly hint?: string; readonly user: boolean; readonly stack?: string };

/** Loads and prepares on the calling thread; `timeline` hears of each stage. */
export async function loadPrepared(sceneArg: string, note: (message: string) => void, sceneOptions: SceneOptionValues = {}, environment?: Environment, adjust?: (scene: Scene) => Scene, timeline?: Timeline): Promise<LoadedPrepared> {
  const t0 = performance.now();
  // A big mesh file: the BVH workers start (and warm up) while it is read and parsed, not after.
  if (isBigMeshFile(sceneArg)) nodeBvhPool()?.start();
  const loaded = await loadSceneArgument(sceneArg, sceneLoadOptions(sceneOptions, note), timeline);
  const lit = environment ? withEnvironment(loaded, environment) : loaded;
  const scene = adjust ? adjust(lit) : lit;
  // The BVH on every core (bvh/build-parallel.ts: the single-thread tree, sooner; small scenes stay here).
  const prepared = await prepareSceneAsync(scene, undefined, { bvhPool: nodeBvhPool() });
  const loadMs = performance.now() - t0;
  if (timeline) {
    const { flattenMs, bvhMs, packMs } = prepared.timings;
    const end = t0 + loadMs;
    timeline.add({ stage: 'prepare: flatten', startMs: end - packMs - bvhMs - flattenMs, endMs: end - packMs - bvhMs });
    timeline.add({ stage: 'prepare: BVH', startMs: end - packMs - bvhMs, endMs: end - packMs });
    timeline.add({ stage: 'prepare: pack', startMs: end - packMs, endMs: end });
  }
  return { prepared, loadMs };
}

/** Mesh files large enough that their BVH will be built on the worker pool (PARALLEL_MIN_PRIMITIVES is 100,000 primitives: a few MB). */
function isBigMeshFile(sceneArg: string): boolean {
  if (!/\.(ply|ply\.gz|glb|gltf)$/i.test(sceneArg)) return false;
  try {
    return statSync(sceneArg).size > 4_000_000;
  } catch {
    return false;
  }
}

/**
 * The bundle this code runs in, when it is one (a worker can start it), else undefined; also
 * undefined with LANTERN_START_THREADS=0 in the environment (all on one thread: a comparison, or a
 * machine with one core).
 */
export function bundlePath(): string | undefined {
  if (process.env.LANTERN_START_THREADS === '0') return undefined;
  const url = import.meta.url;
  return url.startsWith('file:') && url.endsWith('.mjs') ? fileURLToPath(url) : undefined;
}

/**
 * loadPrepared on a worker thread of this bundle, or in-thread where there is no bundle to start
 * (run from sources) or the scene needs a function (`adjust`, which cannot cross threads). An
 * environment map's pixels are transferred to the thread: `environment` is not usable after the call.
 */
export function loadPreparedInThread(sceneArg: string, note: (message: string) => void, sceneOptions: SceneOptionValues = {}, environment?: Environment, adjust?: (scene: Scene) => Scene, timeline?: Timeline): Promise<LoadedPrepared> {
  const bundle = bundlePath();
  if (!bundle || adjust) return loadPrepared(sceneArg, note, sceneOptions, environment, adjust, timeline);
  // The environment map's pixels move to the thread rather than being copied (an 8K map is 384 MB):
  // the caller hands the environment over and does not use it again.
  return runInThread<LoadedPrepared>(bundle, { task: 'scene', sceneArg, sceneOptions, ...(environment ? { environment } : {}) }, 'scene thread', note, timeline, environment ? [...buffersOf(environment)] : []);
}

type TaskRequest = ThreadRequest extends infer R ? (R extends ThreadRequest ? Omit<R, 'role' | 'mainTimeOrigin'> : never) : never;

function runInThread<T>(bundle: string, task: TaskRequest, name: string, note: (message: string) => void, timeline?: Timeline, transferList: ArrayBuffer[] = []): Promise<T> {
  const request = { ...task, role: 'lantern-scene-thread', mainTimeOrigin: performance.timeOrigin } as ThreadRequest;
  const spawned = performance.now();
  const worker = new Worker(bundle, { workerData: request, transferList });
  return new Promise<T>((resolve, reject) => {
    let settled = false;
    const settle = (f: () => void) => {
      if (settled) return;
      settled = true;
      worker.unref();
      f();
    };
    worker.on('message', (reply: ThreadReply) => {
      if (reply.type === 'note') note(reply.message);
      else if (reply.type === 'spans') for (const span of reply.spans) timeline?.add(span);
      else if (reply.type === 'done') {
        timeline?.end(`${name}: result received`, spawned);
        settle(() => resolve(reply.result as T));
      } else {
        const error = reply.user ? new LanternError(reply.message, reply.hint) : new Error(reply.message);
        if (reply.stack) error.stack = reply.stack;
        settle(() => reject(error));
      }
    });
    worker.on('error', (e) => settle(() => reject(e)));
    worker.on('exit', (code) => settle(() => reject(new Error(`the ${name} stopped (exit code ${code}) before it was done`))));
  });
}

/** Whether this thread is a worker started here (a scene task). */
export function isSceneThread(): boolean {
  return !isMainThread && (workerData as Partial<ThreadRequest> | undefined)?.role === 'lantern-scene-thread';
}

/** Every ArrayBuffer reachable from `value`, once each: the worker's result moves without a copy. */
function buffersOf(value: unknown, found = new Set<ArrayBuffer>()): Set<ArrayBuffer> {
  if (value instanceof ArrayBuffer) found.add(value);
  else if (ArrayBuffer.isView(value)) {
    if (value.buffer instanceof ArrayBuffer) found.add(value.buffer);
  } else if (Array.isArray(value)) for (const v of value) buffersOf(v, found);
  else if (value && typeof value === 'object') for (const v of Object.values(value)) buffersOf(v, found);
  return found;
}

/** The worker's side: do the task, post the result (its buffers transferred), and end. */
export async function runSceneThread(): Promise<void> {
  const port = parentPort!;
  const request = workerData as ThreadRequest;
  // This thread's clock starts with the thread: its spans move onto the main thread's.
  const shift = performance.timeOrigin - request.mainTimeOrigin;
  const name = 'scene thread';
  const timeline = new Timeline();
  timeline.add({ stage: `${name}: start + bundle`, startMs: 0, endMs: BUNDLE_START_MS });
  const post = (reply: ThreadReply, transfer: ArrayBuffer[] = []) => port.postMessage(reply, transfer);
  try {
    const result = await loadPrepared(request.sceneArg, (message) => post({ type: 'note', message }), request.sceneOptions, request.environment, undefined, timeline);
    post({ type: 'spans', spans: timeline.spans.map((s) => ({ ...s, startMs: s.startMs + shift, endMs: s.endMs + shift })) });
    post({ type: 'done', result }, [...buffersOf(result)]);
  } catch (e) {
    const user = e instanceof LanternError;
    post({ type: 'error', message: (e as Error)?.message ?? String(e), ...(user && e.hint ? { hint: e.hint } : {}), user, ...(e instanceof Error && e.stack ? { stack: e.stack } : {}) });
  }
}
