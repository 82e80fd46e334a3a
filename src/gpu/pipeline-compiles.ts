/**
 * Every pipeline Lantern makes is compiled here: asynchronously (create*PipelineAsync), at most
 * `concurrency` at a time per device where a front end sets a limit, counted and timed. What a front
 * end waits for is then something it can show ("compiling shaders, 3 of 7") and estimate (each
 * compile's milliseconds as it completes); the stage log (stage-log.ts) gets each compile as a span.
 *
 * Why a limit: Chromium compiles asynchronous pipelines on its GPU process's thread pool, whose
 * foreground workers are max(3, cores - 1). Compiles that occupy all of them starve the work that
 * presents the page's frames: on 2 cores, the hybrid recipe's four tracing kernels compiling side by
 * side stopped requestAnimationFrame for 33 s (no callback at all), where the same four one or two
 * at a time kept every frame coming. Dawn under Node has no such pool to share: no limit there.
 *
 * Compiles are counted in batches: a batch begins with a request made while none is pending and
 * holds every compile requested until all of them are done. A front end that waits for a scene or a
 * recipe waits for the batch under way.
 */
import { reportStage } from './stage-log.ts';
import { WORKGROUP_CONSTANTS } from './kernel-variants.ts';

/** One pipeline of a batch. Times are performance.now() milliseconds. */
export interface PipelineCompile {
  /** The pipeline's label ("passes/path-trace:path_trace"). */
  readonly label: string;
  /** What compiles alike: the label and the override constants (the key a compile time is remembered by). */
  readonly key: string;
  readonly requestedMs: number;
  /** When it left the queue and started compiling; undefined while queued. */
  readonly startMs: number | undefined;
  /** When it was ready (or failed); undefined until then. */
  readonly endMs: number | undefined;
}

/** The batch under way (or the last one, complete). */
export interface CompileProgress {
  readonly compiles: readonly PipelineCompile[];
  /** Pipelines requested in the batch, and of them done (ready or failed). */
  readonly needed: number;
  readonly done: number;
  /** Compiles that may run at a time (Infinity: no limit). */
  readonly concurrency: number;
}

export type CompileListener = (progress: CompileProgress) => void;

interface MutableCompile {
  label: string;
  key: string;
  requestedMs: number;
  startMs: number | undefined;
  endMs: number | undefined;
}

interface DeviceCompiles {
  concurrency: number;
  running: number;
  readonly queue: (() => void)[];
  batch: MutableCompile[];
  readonly listeners: Set<CompileListener>;
}

const perDevice = new WeakMap<GPUDevice, DeviceCompiles>();

function stateOf(device: GPUDevice): DeviceCompiles {
  let s = perDevice.get(device);
  if (!s) perDevice.set(device, (s = { concurrency: Infinity, running: 0, queue: [], batch: [], listeners: new Set() }));
  return s;
}

const snapshot = (s: DeviceCompiles): CompileProgress => ({
  compiles: s.batch.map((c) => ({ ...c })),
  needed: s.batch.length,
  done: s.batch.filter((c) => c.endMs !== undefined).length,
  concurrency: s.concurrency,
});

function notify(s: DeviceCompiles): void {
  if (s.listeners.size === 0) return;
  const progress = snapshot(s);
  for (const listener of s.listeners) listener(progress);
}

/** The batch of compiles under way on `device` (or its last one). */
export function compileProgress(device: GPUDevice): CompileProgress {
  return snapshot(stateOf(device));
}

/** Tells `listener` of every compile requested, started and done on `device` from now on; returns what stops it. */
export function observeCompiles(device: GPUDevice, listener: CompileListener): () => void {
  const s = stateOf(device);
  s.listeners.add(listener);
  return () => s.listeners.delete(listener);
}

/** At most `n` compiles at a time on `device` from now on (Infinity: no limit, the default). */
export function setCompileConcurrency(device: GPUDevice, n: number): void {
  if (!(n >= 1)) throw new Error(`compile concurrency must be at least 1, not ${n}`);
  const s = stateOf(device);
  s.concurrency = n;
  while (s.running < s.concurrency && s.queue.length > 0) s.queue.shift()!();
}

/**
 * Runs `create` (one create*PipelineAsync) when a slot is free, counted in the device's batch and
 * reported to the stage log as `pipeline <label>` (with `detail`, e.g. its constants).
 */
async function compile<T>(device: GPUDevice, label: string, detail: string, create: () => Promise<T>): Promise<T> {
  const s = stateOf(device);
  if (s.batch.length > 0 && s.batch.every((c) => c.endMs !== undefined)) s.batch = [];
  const entry: MutableCompile = { label, key: detail ? `${label} ${detail}` : label, requestedMs: performance.now(), startMs: undefined, endMs: undefined };
  s.batch.push(entry);
  notify(s);
  if (s.running >= s.concurrency) await new Promise<void>((resolve) => s.queue.push(resolve));
  s.running++;
  entry.startMs = performance.now();
  notify(s);
  try {
    return await create();
  } finally {
    entry.endMs = performance.now();
    s.running--;
    reportStage(device, { stage: `pipeline ${label}`, startMs: entry.startMs, endMs: entry.endMs, ...(detail ? { detail } : {}) });
    // The next compile starts before anyone hears of this one: the slot never idles.
    s.queue.shift()?.();
    notify(s);
  }
}

/** A pipeline's variant in words: its override constants, less the workgroup sizes every such kernel has. */
const constantsDetail = (constants: Record<string, GPUPipelineConstantValue> | undefined) =>
  Object.entries(constants ?? {})
    .filter(([k]) => !(k in WORKGROUP_CONSTANTS))
    .map(([k, v]) => `${k}=${v}`)
    .join(' ');

/** createComputePipelineAsync through the device's queue (see the module's comment). */
export function compileComputePipeline(device: GPUDevice, descriptor: GPUComputePipelineDescriptor & { readonly label: string }): Promise<GPUComputePipeline> {
  return compile(device, descriptor.label, constantsDetail(descriptor.compute.constants), () => device.createComputePipelineAsync(descriptor));
}

/** createRenderPipelineAsync through the device's queue (see the module's comment). */
export function compileRenderPipeline(device: GPUDevice, descriptor: GPURenderPipelineDescriptor & { readonly label: string }): Promise<GPURenderPipeline> {
  return compile(device, descriptor.label, constantsDetail(descriptor.vertex.constants), () => device.createRenderPipelineAsync(descriptor));
}
