/**
 * The benchmark behind `lantern bench`: traversal throughput on pre-generated rays (closest hit;
 * coherent primary rays through pixel centres, then incoherent diffuse rays from their hits, as
 * tinybvh's speed test measures) and full path-tracing throughput at the current settings. GPU time
 * comes from timestamp queries where the adapter has them, else from wall-clock time around
 * onSubmittedWorkDone (which includes submit overhead: the result says which).
 */
import { GpuTimer } from '../gpu/timestamps.ts';
import { BenchmarkRaysPass } from '../passes/benchmark-rays-pass.ts';
import { rayBufferStrides, TraceRaysPass } from '../passes/trace-rays-pass.ts';
import type { Renderer } from './renderer.ts';

export interface ThroughputFigure {
  /** Median GPU milliseconds of one pass. */
  readonly ms: number;
  readonly mraysPerSecond: number;
}

export interface BenchmarkResult {
  readonly adapter: string;
  readonly timing: 'gpu-timestamps' | 'wall-clock';
  readonly width: number;
  readonly height: number;
  readonly primary: ThroughputFigure;
  readonly diffuse: ThroughputFigure;
  readonly pathTracing: {
    readonly maxBounces: number;
    /** Median GPU milliseconds of one sample per pixel over the whole image. */
    readonly msPerSample: number;
    readonly samplesPerSecond: number;
    /** Extension + shadow rays per second. */
    readonly mraysPerSecond: number;
    /** Extension + shadow rays per path (one sample of one pixel). */
    readonly raysPerPath: number;
  };
}

export interface BenchmarkOptions {
  /** Timed repetitions of each measurement (after one warm-up). */
  readonly repeats?: number;
}

const median = (xs: number[]): number => {
  const s = [...xs].sort((a, b) => a - b);
  const m = s.length >> 1;
  return s.length % 2 ? s[m]! : (s[m - 1]! + s[m]!) / 2;
};

/** Wall time of path tracing run before any measurement, so the GPU is at its working clocks. */
const WARM_UP_MS = 1000;

/** Times `encode` `repeats` times (after a warm-up), one submit each; returns the median in ms. */
async function timePasses(device: GPUDevice, timer: GpuTimer | undefined, repeats: number, encode: (encoder: GPUCommandEncoder, timer?: GpuTimer) => void): Promise<number> {
  const times: number[] = [];
  for (let i = 0; i <= repeats; i++) {
    const encoder = device.createCommandEncoder({ label: 'benchmark' });
    const t0 = performance.now();
    encode(encoder, timer);
    timer?.resolve(encoder);
    device.queue.submit([encoder.finish()]);
    await device.queue.onSubmittedWorkDone();
    const wall = performance.now() - t0;
    const ms = timer ? (await timer.read()).reduce((sum, p) => sum + p.ms, 0) : wall;
    if (i > 0) times.push(ms);
  }
  return median(times);
}

export async function runBenchmark(renderer: Renderer, options: BenchmarkOptions = {}): Promise<BenchmarkResult> {
  const repeats = options.repeats ?? 10;
  const { device } = renderer;
  const { resources, view } = renderer.internals();
  const width = renderer.width, height = renderer.height;
  const count = width * height;
  const timer = renderer.gpu.hasTimestamps ? new GpuTimer(device) : undefined;
  const [trace, generate] = await Promise.all([TraceRaysPass.create(device), BenchmarkRaysPass.create(device)]);
  const strides = rayBufferStrides();
  const buffer = (label: string, size: number) => device.createBuffer({ label, size, usage: GPUBufferUsage.STORAGE });
  const primaryRays = buffer('primary rays', count * strides.ray);
  const primaryHits = buffer('primary hits', count * strides.hit);
  const diffuseRays = buffer('diffuse rays', count * strides.ray);
  const diffuseHits = buffer('diffuse hits', count * strides.hit);
  try {
    // A GPU lowers its clocks while it idles (a BVH build, a pipeline compile: the specialised
    // kernel's takes seconds), and a few milliseconds of work do not bring them back: an H200
    // measured 5.5× slower right after a compile. Keep it busy for a while before timing anything.
    const warmUntil = performance.now() + WARM_UP_MS;
    for (let i = 0; i < 1000 && performance.now() < warmUntil; i++) {
      renderer.accumulate(1, [renderer.fullImage()]);
      await renderer.finish();
    }
    renderer.resetAccumulation();

    let encoder = device.createCommandEncoder({ label: 'benchmark rays' });
    generate.encodePrimary(encoder, view, width, height, primaryRays);
    device.queue.submit([encoder.finish()]);
    const primaryGroups = await trace.bind(resources, primaryRays, primaryHits, count);
    const primaryMs = await timePasses(device, timer, repeats, (e, t) => trace.encode(e, primaryGroups, t, 'primary rays'));

    encoder = device.createCommandEncoder({ label: 'benchmark rays' });
    generate.encodeDiffuse(encoder, count, primaryRays, primaryHits, diffuseRays, 1234);
    device.queue.submit([encoder.finish()]);
    const diffuseGroups = await trace.bind(resources, diffuseRays, diffuseHits, count);
    const diffuseMs = await timePasses(device, timer, repeats, (e, t) => trace.encode(e, diffuseGroups, t, 'diffuse rays'));

    // Path tracing: one sample per pixel per submit, as the interactive viewer runs it.
    renderer.resetAccumulation();
    const sampleTimes: number[] = [];
    for (let i = 0; i <= repeats; i++) {
      const t0 = performance.now();
      renderer.accumulate(1, [renderer.fullImage()], timer);
      await renderer.finish();
      const wall = performance.now() - t0;
      const ms = timer ? (await timer.read()).reduce((sum, p) => sum + p.ms, 0) : wall;
      if (i > 0) sampleTimes.push(ms);
    }
    const rays = await renderer.readRayCounts();
    const raysPerPath = (rays.extension + rays.shadow) / (renderer.sampleCount * count);
    const msPerSample = median(sampleTimes);
    renderer.resetAccumulation();

    const figure = (ms: number): ThroughputFigure => ({ ms, mraysPerSecond: count / (ms * 1e3) });
    return {
      adapter: renderer.gpu.adapterName,
      timing: timer ? 'gpu-timestamps' : 'wall-clock',
      width,
      height,
      primary: figure(primaryMs),
      diffuse: figure(diffuseMs),
      pathTracing: {
        maxBounces: renderer.settings.maxBounces,
        msPerSample,
        samplesPerSecond: (count * 1000) / msPerSample,
        mraysPerSecond: (raysPerPath * count) / (msPerSample * 1e3),
        raysPerPath,
      },
    };
  } finally {
    for (const b of [primaryRays, primaryHits, diffuseRays, diffuseHits]) b.destroy();
    trace.destroy();
    generate.destroy();
    timer?.destroy();
  }
}
