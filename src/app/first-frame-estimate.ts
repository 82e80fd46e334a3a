/**
 * What the page tells a user before Play about the wait for the first frame. Most of that wait is
 * compiling the path tracer (Dawn hands WGSL to the driver), then one frame. The estimate is honest
 * about its basis: a figure measured on this computer in an earlier visit (kept in localStorage by
 * the page) where there is one for this adapter and a similar image size; otherwise a model from
 * the adapter's kind and the image size, with figures measured in this project (docs/perf.md):
 *
 * - software adapters (SwiftShader, llvmpipe: the GPU emulated on the CPU): the Cornell box's path
 *   tracer took 15 s to compile on 2 cores, and rays run at about 1 M/s;
 * - hardware adapters: compiles took 1–3.4 s on an H200 (a weaker GPU's driver is not much faster),
 *   and the first frame itself is milliseconds.
 *
 * Pure (no DOM, no GPU): the page queries the adapter (no device) and passes what it learnt.
 */
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

/** Compile time of what the first frame needs, milliseconds (docs/perf.md: 15.2 s for the Cornell path tracer on SwiftShader; 1–3.4 s on an H200). */
const COMPILE_MS = { software: 15_000, hardware: 2_000 } as const;
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
  const ms = COMPILE_MS[kind] + (1000 * pixels * RAYS_PER_PIXEL) / RAYS_PER_SECOND[kind];
  return {
    ms,
    basis: kind === 'software' ? 'a software GPU, which runs on the CPU: shaders compile for about 15 s, then about a million rays a second' : 'a hardware GPU: mostly compiling shaders',
  };
}

/** The line under the Play button: "First frame in about 40 s (a software GPU …)". One significant figure in the unit shown: it is an estimate. */
export function describeEstimate(e: FirstFrameEstimate): string {
  const oneFigure = (x: number) => {
    const magnitude = 10 ** Math.floor(Math.log10(Math.max(x, 1)));
    return Math.max(1, Math.round(x / magnitude)) * magnitude;
  };
  const s = e.ms / 1000;
  const text = e.ms < 1000 ? `${oneFigure(e.ms)} ms` : s < 100 ? `${oneFigure(s)} s` : `${oneFigure(s / 60)} min`;
  return `First frame in about ${text} (${e.basis}).`;
}
