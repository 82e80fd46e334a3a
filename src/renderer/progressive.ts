/**
 * A long render as a sequence of short submits (see DispatchPlanner), with progress reports. Used by
 * `lantern render` and by tests that need many samples.
 */
import type { Renderer } from './renderer.ts';
import { DEFAULT_PLANNER_OPTIONS, DispatchPlanner, type DispatchPlannerOptions } from './dispatch-planner.ts';

export interface ProgressiveOptions {
  /** Samples per pixel to add. */
  readonly spp: number;
  readonly onProgress?: (samplesDone: number, samplesTotal: number) => void;
  readonly planner?: DispatchPlannerOptions;
  /**
   * Samples per dispatch, fixed (only the bands adapt to timing): the accumulation's float sums then
   * group the same way on every run and machine, and equal a farm's chunks of this size merged.
   */
  readonly samplesPerDispatch?: number;
}

export async function renderProgressive(renderer: Renderer, options: ProgressiveOptions): Promise<{ seconds: number }> {
  // The kernels the settings ask for (another sampler compiles after a change): every sample theirs.
  await renderer.accelSettled();
  const plan = options.planner ?? DEFAULT_PLANNER_OPTIONS;
  const planner = new DispatchPlanner(renderer.width, renderer.height, options.samplesPerDispatch !== undefined ? { ...plan, fixedSamples: options.samplesPerDispatch } : plan);
  const start = performance.now();
  let done = 0;
  while (done < options.spp) {
    const { samples, tiles } = planner.next(options.spp - done);
    const t0 = performance.now();
    renderer.accumulate(samples, tiles);
    await renderer.finish();
    planner.observe((performance.now() - t0) / tiles.length);
    done += samples;
    options.onProgress?.(done, options.spp);
  }
  return { seconds: (performance.now() - start) / 1000 };
}
