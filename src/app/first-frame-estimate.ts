/**
 * What the page tells a user about the wait for the first frame. Most of that wait is compiling
 * pipelines (Dawn hands WGSL to the driver), then one frame.
 *
 * Before Play, the estimate is honest about its basis: a figure measured on this computer in an
 * earlier visit (kept in localStorage by the page) where there is one for this adapter and a
 * similar image size; otherwise a model from the adapter's kind and the image size, with figures
 * measured in this project:
 *
 * - software adapters (SwiftShader, llvmpipe: the GPU emulated on the CPU): Play to the first frame
 *   of the default page took 30–71 s on 2 cores (issue #27; most of it the real-time chain's and
 *   the path tracer's compiles), and rays run at about 1 M/s;
 * - hardware adapters: compiles took 1–3.4 s on an H200 (a weaker GPU's driver is not much faster),
 *   and the first frame itself is milliseconds.
 *
 * After Play, what is really waited for replaces the guess (remainingCompileMs): the pipelines of
 * the batch under way (gpu/pipeline-compiles.ts), each expected to take what it took on this
 * computer before (the page keeps every pipeline's compile time per adapter), or what the
 * pipelines measured so far took on average, scheduled as the device compiles them (so many at a
 * time, in order); the estimate follows each compile as it completes.
 *
 * Pure (no DOM, no GPU): the page queries the adapter (no device) and passes what it learnt.
 */
import type { CompileProgress, PipelineCompile } from '../gpu/pipeline-compiles.ts';

/** What a GPUAdapter says about itself before any device exists (GPUAdapterInfo's fields and the fallback flag). */
export interface AdapterFacts {
  readonly vendor: string;
  readonly architecture: string;
  readonly device: string;
  readonly description: string;
  readonly isFallbackAdapter: boolean;
}

/** A first frame measured on this computer: which adapter, how long from Play, at what image size. */
export interface FirstFrameRecord {
  readonly adapter: string;
  readonly ms: number;
  readonly pixels: number;
}

/** The key an adapter's measurements are kept under (the same GPU and driver give the same key). */
export const adapterKey = (a: AdapterFacts) => [a.vendor, a.architecture, a.device, a.description].filter((x) => x !== '').join(' ') || 'unknown adapter';

/** Whether the adapter runs on the CPU: the browser says so (fallback adapter), or its name is a known software rasteriser. */
export function isSoftware(a: AdapterFacts): boolean {
  return a.isFallbackAdapter || /swiftshader|llvmpipe|lavapipe|softpipe|software|basic render/i.test(adapterKey(a));
}

/**
 * Compile time of what the first frame needs, milliseconds: the default page's first frame waited
 * 30–71 s on SwiftShader with 2 cores (the runs; 41 s in this one's measurement under load),
 * 1–3.4 s on an H200.
 */
const COMPILE_MS = { software: 45_000, hardware: 2_000 } as const;
/**
 * A pipeline's compile before any has been measured on this computer, milliseconds: on SwiftShader
 * (2 cores) they took 0.3 s (small image passes) to 29 s (the hybrid recipe's GI kernel), the path
 * tracer 15 s; on an H200 0.1–3.4 s.
 */
const PIPELINE_MS = { software: 8_000, hardware: 500 } as const;
/** Rays a second (software: about 1 M/s primary on SwiftShader, 2 cores: docs/perf.md). */
const RAYS_PER_SECOND = { software: 1e6, hardware: 1e9 } as const;
/** Rays a first frame traces per pixel: a path of a few bounces with a shadow ray at each (3.1–7.5 rays/path measured). */
const RAYS_PER_PIXEL = 6;

export interface FirstFrameEstimate {
  readonly ms: number;
  /** How the figure was reached, for the user: "measured on this computer in an earlier visit", "a software GPU, …". */
  readonly basis: string;
}

/**
 * The expected milliseconds from Play to the first frame, or undefined when nothing is known about
 * the adapter (no WebGPU, or the adapter query failed). A record for the same adapter is used where
 * its image had between half and twice the pixels of this one.
 */
export function estimateFirstFrame(adapter: AdapterFacts | undefined, pixels: number, record?: FirstFrameRecord): FirstFrameEstimate | undefined {
  if (!adapter) return undefined;
  if (record && record.adapter === adapterKey(adapter) && record.pixels > 0 && pixels / record.pixels <= 2 && record.pixels / pixels <= 2) {
    return { ms: record.ms, basis: 'what it took on this computer last time' };
  }
  const kind = isSoftware(adapter) ? 'software' : 'hardware';
  return {
    ms: COMPILE_MS[kind] + frameMs(adapter, pixels),
    basis: kind === 'software' ? 'a software GPU, which runs on the CPU: shaders compile for 30 s to a minute, then about a million rays a second' : 'a hardware GPU: mostly compiling shaders',
  };
}

/** The first frame's own milliseconds once its pipelines are compiled (the model's ray rate). */
export function frameMs(adapter: AdapterFacts, pixels: number): number {
  return (1000 * pixels * RAYS_PER_PIXEL) / RAYS_PER_SECOND[isSoftware(adapter) ? 'software' : 'hardware'];
}

/** Pipeline compile times measured on this computer for one adapter, milliseconds by PipelineCompile.key. */
export interface CompileTimesRecord {
  readonly adapter: string;
  readonly ms: Readonly<Record<string, number>>;
}

/** Pipelines a record remembers at most (the least recently measured go first): a few recipes' worth, a few kB. */
export const MAX_REMEMBERED_COMPILES = 200;

/**
 * `known` with the compiles of `compiles` that are done (the latest measurement of a pipeline wins,
 * and counts as the most recent), or `known` itself when none is new; at most `limit` pipelines.
 */
export function withMeasuredCompiles(known: Readonly<Record<string, number>>, compiles: readonly PipelineCompile[], limit = MAX_REMEMBERED_COMPILES): Readonly<Record<string, number>> {
  let out: Record<string, number> | undefined;
  for (const c of compiles) {
    if (c.startMs === undefined || c.endMs === undefined) continue;
    const ms = c.endMs - c.startMs;
    if (known[c.key] === ms) continue;
    out ??= { ...known };
    // Taken out and put back: the key order is the order of measurement.
    delete out[c.key];
    out[c.key] = ms;
  }
  if (!out) return known;
  const keys = Object.keys(out);
  for (const key of keys.slice(0, Math.max(0, keys.length - limit))) delete out[key];
  return out;
}

/** A compile under way longer than expected is expected to need at least this fraction of its expected time more (never "done" before it is). */
const OVERDUE_FRACTION = 0.1;

/**
 * Milliseconds until the last compile of `progress` is done, at `nowMs` (performance.now()): each
 * compile not done takes what `known` says this pipeline took before, else the mean of `known` or
 * the adapter kind's figure, whichever is longer (the small passes finish first: a mean of them
 * alone would promise the tracing kernels in a second); one under way has its elapsed time taken
 * off; queued ones start in order as one of the `progress.concurrency` slots frees (the device's queue).
 */
export function remainingCompileMs(progress: CompileProgress, nowMs: number, known: Readonly<Record<string, number>>, adapter: AdapterFacts): number {
  const values = Object.values(known);
  const prior = PIPELINE_MS[isSoftware(adapter) ? 'software' : 'hardware'];
  const fallback = Math.max(prior, values.length > 0 ? values.reduce((a, b) => a + b, 0) / values.length : 0);
  const expected = (c: PipelineCompile) => known[c.key] ?? fallback;
  const left = progress.compiles.filter((c) => c.endMs === undefined);
  const running = left.filter((c) => c.startMs !== undefined);
  const queued = left.filter((c) => c.startMs === undefined);
  // When each slot is next free, milliseconds from now: the compiles under way hold theirs.
  const slots = running.map((c) => {
    const e = expected(c);
    return Math.max(e - (nowMs - c.startMs!), OVERDUE_FRACTION * e);
  });
  const free = Math.min(progress.concurrency, running.length + queued.length) - running.length;
  for (let i = 0; i < free; i++) slots.push(0);
  let end = Math.max(0, ...slots);
  for (const c of queued) {
    const first = slots.indexOf(Math.min(...slots));
    slots[first]! += expected(c);
    end = Math.max(end, slots[first]!);
  }
  return end;
}

/** A wait as an estimate says it: one significant figure in the unit shown ("40 s", "400 ms", "3 min"). */
export function roughDuration(ms: number): string {
  const oneFigure = (x: number) => {
    const magnitude = 10 ** Math.floor(Math.log10(Math.max(x, 1)));
    return Math.max(1, Math.round(x / magnitude)) * magnitude;
  };
  const s = ms / 1000;
  return ms < 1000 ? `${oneFigure(ms)} ms` : s < 100 ? `${oneFigure(s)} s` : `${oneFigure(s / 60)} min`;
}

/** The line under the Play button: "First frame in about 40 s (a software GPU …)". */
export function describeEstimate(e: FirstFrameEstimate): string {
  return `First frame in about ${roughDuration(e.ms)} (${e.basis}).`;
}
