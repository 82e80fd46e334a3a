/**
 * The benchmark behind `lantern bench`: traversal throughput on pre-generated rays (closest hit;
 * coherent primary rays through pixel centres, stored by 8 × 8 tiles or by rows, then tinybvh's
 * diffuse rays: one per primary hit, cosine-distributed about the geometric normal) and full
 * path-tracing throughput at the current settings. GPU time comes from timestamp queries where the
 * adapter has them, else from wall-clock time around onSubmittedWorkDone (which includes submit
 * overhead: the result says which). The timing protocol is tinybvh's: the clocks warmed for at
 * least half a second, then for each figure 5 untimed launches and the median of 20 timed ones.
 */
import { GpuTimer } from '../gpu/timestamps.ts';
import { createBufferWithData, readBuffer } from '../gpu/readback.ts';
import { reflectModule, structLayout } from '../gpu/wgsl/reflect.ts';
import { BenchmarkRaysPass, type RayOrder } from '../passes/benchmark-rays-pass.ts';
import { TraceRaysPass } from '../passes/trace-rays-pass.ts';
import type { TriangleList } from '../scene/triangles.ts';
import { countHits, diffuseRaysFromHits, reorderRays, type HitWords, type RayWords } from './benchmark-rays.ts';
import type { Renderer } from './renderer.ts';
import { median } from '../math/median.ts';

export interface ThroughputFigure {
  /** Median GPU milliseconds of one pass. */
  readonly ms: number;
  readonly mraysPerSecond: number;
  /** Rays traced by one pass. */
  readonly rays: number;
  /** The fraction of them that hit something. */
  readonly hitFraction: number;
}

export interface PathTracingFigure {
  readonly maxBounces: number;
  /** Median GPU milliseconds of one sample per pixel over the whole image. */
  readonly msPerSample: number;
  readonly samplesPerSecond: number;
  /** Extension + shadow rays per second. */
  readonly mraysPerSecond: number;
  /** Extension + shadow rays per path (one sample of one pixel). */
  readonly raysPerPath: number;
}

export interface BenchmarkResult {
  readonly adapter: string;
  readonly timing: 'gpu-timestamps' | 'wall-clock';
  readonly width: number;
  readonly height: number;
  readonly rayOrder: RayOrder;
  /** Whether the diffuse rays were sorted for coherence (by direction octant and origin) before tracing. */
  readonly reordered: boolean;
  readonly warmups: number;
  readonly repeats: number;
  readonly primary: ThroughputFigure;
  readonly diffuse: ThroughputFigure;
  /** Absent when not asked for. */
  readonly pathTracing?: PathTracingFigure;
}

export interface BenchmarkOptions {
  /** The scene's primitives (the diffuse rays need their geometric normals). */
  readonly triangles: TriangleList;
  /** The scene's bounding-box diagonal (the diffuse rays' origin offset is 1e-4 of it). */
  readonly diagonal: number;
  /** Timed launches of each measurement (the median is reported); default 20. */
  readonly repeats?: number;
  /** Untimed launches before them; default 5. */
  readonly warmups?: number;
  /** How primary rays are stored, so how a workgroup's 64 rays lie on the image; default tiles. */
  readonly rayOrder?: RayOrder;
  /** Whether the diffuse rays are sorted for coherence before they are traced (untimed); default false. */
  readonly reorder?: boolean;
  /** Whether to time path tracing too; default true. */
  readonly pathTracing?: boolean;
}

/** Wall time of path tracing run before any measurement, so the GPU is at its working clocks. */
const WARM_UP_MS = 1000;

/** Times `encode` `repeats` times after `warmups` untimed runs, one submit each; returns the median in ms. */
async function timePasses(device: GPUDevice, timer: GpuTimer | undefined, warmups: number, repeats: number, encode: (encoder: GPUCommandEncoder, timer?: GpuTimer) => void): Promise<number> {
  const times: number[] = [];
  for (let i = 0; i < warmups + repeats; i++) {
    const encoder = device.createCommandEncoder({ label: 'benchmark' });
    const t0 = performance.now();
    encode(encoder, timer);
    timer?.resolve(encoder);
    device.queue.submit([encoder.finish()]);
    await device.queue.onSubmittedWorkDone();
    const wall = performance.now() - t0;
    const ms = timer ? (await timer.read()).reduce((sum, p) => sum + p.ms, 0) : wall;
    if (i >= warmups) times.push(ms);
  }
  return median(times);
}

/** Word offsets of the trace-rays module's Ray and HitRecord. */
function rayWords(): { ray: RayWords; hit: HitWords } {
  const { defs } = reflectModule('passes/trace-rays');
  const r = structLayout(defs, 'Ray'), h = structLayout(defs, 'HitRecord');
  return {
    ray: { stride: r.strideWords, origin: r.word('origin'), direction: r.word('direction'), tMin: r.word('t_min'), tMax: r.word('t_max') },
    hit: { stride: h.strideWords, t: h.word('t'), triangle: h.word('triangle') },
  };
}


export async function runBenchmark(renderer: Renderer, options: BenchmarkOptions): Promise<BenchmarkResult> {
  const repeats = options.repeats ?? 20;
  const warmups = options.warmups ?? 5;
  const rayOrder = options.rayOrder ?? 'tiles';
  const { device } = renderer;
  const { scene: resources, view } = renderer.frame();
  const width = renderer.width, height = renderer.height;
  const count = width * height;
  const timer = renderer.gpu.hasTimestamps ? new GpuTimer(device) : undefined;
  // The scene's variant of the ray tracer alone (bind() would compile it beside a plain scene's).
  const [trace, generate] = await Promise.all([TraceRaysPass.create(device, resources.features), BenchmarkRaysPass.create(device)]);
  const words = rayWords();
  const buffer = (label: string, size: number) => device.createBuffer({ label, size, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC });
  const primaryRays = buffer('primary rays', count * words.ray.stride * 4);
  const primaryHits = buffer('primary hits', count * words.hit.stride * 4);
  const owned: GPUBuffer[] = [primaryRays, primaryHits];
  try {
    // A GPU lowers its clocks while it idles (a BVH build, a pipeline compile: the specialised
    // kernel's takes seconds), and a few milliseconds of work do not bring them back: an H200
    // measured 5.5× slower right after a compile. Keep it busy for a while before timing anything:
    // with path tracing, by path tracing; without (the renderer then has no path tracer compiled,
    // cli/commands/bench.ts), by tracing the primary rays.
    const warmUp = async (work: () => void) => {
      const warmUntil = performance.now() + WARM_UP_MS;
      for (let i = 0; i < 1000 && performance.now() < warmUntil; i++) {
        work();
        await renderer.finish();
      }
    };
    const pathTracing = options.pathTracing !== false;
    if (pathTracing) {
      await warmUp(() => renderer.accumulate(1));
      renderer.resetAccumulation();
    }

    const encoder = device.createCommandEncoder({ label: 'benchmark rays' });
    generate.encode(encoder, { view, width, height, rays: primaryRays, order: rayOrder });
    device.queue.submit([encoder.finish()]);
    const primaryGroups = await trace.bind(resources, primaryRays, primaryHits, count);
    if (!pathTracing) {
      await warmUp(() => {
        const e = device.createCommandEncoder({ label: 'benchmark warm-up' });
        trace.encode(e, { binding: primaryGroups, label: 'primary rays' });
        device.queue.submit([e.finish()]);
      });
    }
    const primaryMs = await timePasses(device, timer, warmups, repeats, (e, t) => trace.encode(e, { binding: primaryGroups, timer: t, label: 'primary rays' }));

    const [rayBytes, hitBytes] = await Promise.all([readBuffer(device, primaryRays), readBuffer(device, primaryHits)]);
    const made = diffuseRaysFromHits(new Float32Array(rayBytes), hitBytes, count, options.triangles, options.diagonal, words.ray, words.hit);
    const diffuse = options.reorder ? { ...made, rays: reorderRays(made.rays, made.count, words.ray) } : made;
    let diffuseMs = 0, diffuseHitFraction = 0;
    if (diffuse.count > 0) {
      const diffuseRays = createBufferWithData(device, 'diffuse rays', diffuse.rays, GPUBufferUsage.STORAGE);
      const diffuseHits = buffer('diffuse hits', diffuse.count * words.hit.stride * 4);
      owned.push(diffuseRays, diffuseHits);
      const diffuseGroups = await trace.bind(resources, diffuseRays, diffuseHits, diffuse.count);
      diffuseMs = await timePasses(device, timer, warmups, repeats, (e, t) => trace.encode(e, { binding: diffuseGroups, timer: t, label: 'diffuse rays' }));
      diffuseHitFraction = hitFraction(await readBuffer(device, diffuseHits), diffuse.count, words.hit);
    }

    const figure = (ms: number, rays: number, hits: number): ThroughputFigure => ({ ms, mraysPerSecond: ms > 0 ? rays / (ms * 1e3) : 0, rays, hitFraction: hits });
    return {
      adapter: renderer.gpu.adapterName,
      timing: timer ? 'gpu-timestamps' : 'wall-clock',
      width,
      height,
      rayOrder,
      reordered: options.reorder ?? false,
      warmups,
      repeats,
      primary: figure(primaryMs, count, diffuse.count / count),
      diffuse: figure(diffuseMs, diffuse.count, diffuseHitFraction),
      ...(pathTracing ? { pathTracing: await timePathTracing(renderer, timer, warmups, repeats) } : {}),
    };
  } finally {
    for (const b of owned) b.destroy();
    trace.destroy();
    generate.destroy();
    timer?.destroy();
  }
}

const hitFraction = (hits: ArrayBuffer, count: number, words: HitWords): number => countHits(hits, count, words) / count;

/** Path tracing: one sample per pixel per submit, as the interactive viewer runs it. */
async function timePathTracing(renderer: Renderer, timer: GpuTimer | undefined, warmups: number, repeats: number): Promise<PathTracingFigure> {
  const count = renderer.width * renderer.height;
  renderer.resetAccumulation();
  const sampleTimes: number[] = [];
  for (let i = 0; i < warmups + repeats; i++) {
    const t0 = performance.now();
    renderer.accumulate(1, undefined, timer);
    await renderer.finish();
    const wall = performance.now() - t0;
    const ms = timer ? (await timer.read()).reduce((sum, p) => sum + p.ms, 0) : wall;
    if (i >= warmups) sampleTimes.push(ms);
  }
  const rays = await renderer.readRayCounts();
  const raysPerPath = (rays.extension + rays.shadow) / (renderer.sampleCount * count);
  const msPerSample = median(sampleTimes);
  renderer.resetAccumulation();
  return {
    maxBounces: renderer.settings.maxBounces,
    msPerSample,
    samplesPerSecond: (count * 1000) / msPerSample,
    mraysPerSecond: (raysPerPath * count) / (msPerSample * 1e3),
    raysPerPath,
  };
}
