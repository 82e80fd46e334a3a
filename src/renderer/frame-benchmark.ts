/**
 * The real-time frame's benchmark (`lantern bench --real-time`): frames of the current recipe at a
 * still camera, rendered back to back with nothing read back but their timestamps, so that the GPU
 * stays busy as it does in the viewer. `render --frames` reads back and encodes every frame, and a
 * GPU left idle between frames lowers its clocks: the H200 then runs at 345 MHz instead of 1980 and
 * every pass takes about five times longer (docs/perf.md, 2026-11-24). Reported per pass and per
 * frame: the median over the timed frames of GPU milliseconds, and the denoising chain's sum.
 */
import { GpuTimer } from '../gpu/timestamps.ts';
import { isDenoiseChainPass } from '../passes/denoise-passes.ts';
import type { Renderer } from './renderer.ts';
import { median } from '../math/median.ts';

export interface FrameBenchmarkOptions {
  /** Samples per pixel in each frame. */
  readonly spp: number;
  /** Frames timed (the medians are over them). */
  readonly frames: number;
  /** Frames rendered first and thrown away; at least `warmupSeconds` of them. */
  readonly warmups: number;
  readonly warmupSeconds: number;
}

export interface FrameBenchmarkResult {
  readonly frames: number;
  readonly sppPerFrame: number;
  /** Median GPU milliseconds of each pass, by its label (empty without timestamp queries). */
  readonly passMs: Readonly<Record<string, number>>;
  /** Median over the frames of the denoising chain's GPU time (temporal, à-trous, output); absent where no such pass ran or nothing is timed. */
  readonly chainMs?: number;
  /** Median over the frames of all passes' GPU time; absent without timestamp queries. */
  readonly frameMs?: number;
  /** Frames per second by the wall clock over the timed frames (CPU work and submission included). */
  readonly framesPerSecond: number;
}

/** Times frames of the renderer's recipe (Renderer.compile with frames asked for, first) at its current camera and settings. */
export async function benchmarkFrames(renderer: Renderer, o: FrameBenchmarkOptions): Promise<FrameBenchmarkResult> {
  const timer = renderer.gpu.hasTimestamps ? new GpuTimer(renderer.device) : undefined;
  try {
    for (let f = 0, until = performance.now() + o.warmupSeconds * 1000; f < o.warmups || performance.now() < until; f++) {
      renderer.renderFrame(o.spp);
      await renderer.finish();
    }
    const passes = new Map<string, number[]>();
    const chain: number[] = [];
    const totals: number[] = [];
    const start = performance.now();
    for (let f = 0; f < o.frames; f++) {
      renderer.renderFrame(o.spp, timer);
      if (!timer) continue;
      let frame = 0, denoise = 0, denoised = false;
      for (const { name, ms } of await timer.read()) {
        passes.set(name, [...(passes.get(name) ?? []), ms]);
        frame += ms;
        if (isDenoiseChainPass(name)) {
          denoise += ms;
          denoised = true;
        }
      }
      totals.push(frame);
      if (denoised) chain.push(denoise);
    }
    await renderer.finish();
    const seconds = (performance.now() - start) / 1000;
    return {
      frames: o.frames,
      sppPerFrame: o.spp,
      passMs: Object.fromEntries([...passes].map(([name, ms]) => [name, median(ms)])),
      ...(chain.length > 0 ? { chainMs: median(chain) } : {}),
      ...(totals.length > 0 ? { frameMs: median(totals) } : {}),
      framesPerSecond: o.frames / seconds,
    };
  } finally {
    timer?.destroy();
  }
}
