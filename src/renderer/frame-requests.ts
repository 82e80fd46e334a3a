/**
 * What the Renderer is asked to render (renderer/renderer.ts delegates here): progressive samples
 * (accumulate in tiles, beginAccumulate as a SplitFrame; the samples count once submitted), one frame
 * of the recipe the settings choose (beginFrame), and the trace-only frame of the benchmarks
 * (traceFrame). It owns the accounting of what was rendered last: which image present() and
 * readImage() show, and the recipe whose output that frame is.
 */
import type { GpuTimer } from '../gpu/timestamps.ts';
import type { Tile } from '../passes/path-trace-pass.ts';
import { LanternError } from '../errors.ts';
import type { FrameContext } from './frame.ts';
import type { ImageEstimate, ImageTargets } from './image.ts';
import type { FrameRecipe, RecipeFrame } from './recipes/frame-recipe.ts';
import type { ProgressiveRecipe } from './recipes/progressive.ts';
import type { RecipeSet } from './recipes/recipe-set.ts';
import { recipeFor } from './recipes/recipe.ts';
import type { SceneResidency } from './scene-residency.ts';
import type { Integrator, RenderSettings } from './settings.ts';
import { SplitFrame, type FrameHost } from './split-frame.ts';

/** What the requests read of the renderer as it is now. */
export interface RequestState {
  settings(): RenderSettings;
  /** The frame's context (Renderer.frame): throws without a scene, a size or a camera. */
  frame(timer?: GpuTimer): FrameContext;
  /** The image's targets: throws without a scene or a size. */
  targets(): ImageTargets;
}

export class FrameRequests {
  /** The recipe of the last frame (whose output present and readFrame show). */
  lastFrame?: FrameRecipe;
  /** What present() and readImage() show: the progressive estimate or the last real-time frame. */
  shown: 'accumulation' | 'frame' = 'accumulation';

  constructor(
    private readonly host: FrameHost,
    private readonly image: ImageEstimate,
    private readonly recipes: RecipeSet,
    private readonly residency: SceneResidency,
    private readonly state: RequestState,
  ) {}

  private get device(): GPUDevice {
    return this.host.device;
  }

  /** The progressive path tracer (a renderer made without it compiles it when compile() asks for a progressive render). */
  private get progressive(): ProgressiveRecipe {
    const progressive = this.recipes.progressive;
    if (!progressive) throw new Error('Renderer: compile() the progressive recipe before accumulate()');
    return progressive;
  }

  /** Renderer.accumulate: one submit per tile; the samples count at once. */
  accumulate(samples: number, tiles: readonly Tile[], timer?: GpuTimer): void {
    this.checkSamples(samples, 'dispatch');
    const progressive = this.progressive;
    const frame = this.state.frame(timer);
    tiles.forEach((tile, i) => {
      const encoder = this.device.createCommandEncoder({ label: 'path trace' });
      progressive.encode(encoder, frame, tile, this.image.nextSampleIndex, samples);
      if (timer && i === tiles.length - 1) timer.resolve(encoder);
      this.device.queue.submit([encoder.finish()]);
    });
    this.image.add(samples);
    this.shown = 'accumulation';
  }

  /** Renderer.beginAccumulate: the samples count once the last band is submitted. */
  beginAccumulate(samples: number, timer?: GpuTimer): SplitFrame {
    this.checkSamples(samples, 'dispatch');
    const work = this.progressive.begin(this.state.frame(timer), samples, this.image.nextSampleIndex);
    return this.split(work, samples, 'path trace', () => {
      this.image.add(samples);
      this.shown = 'accumulation';
    });
  }

  /** Renderer.traceFrame: the real-time recipe's path tracing alone; returns which integrator traced. */
  traceFrame(samples: number, options: { readonly sampleIndex?: number; readonly timer?: GpuTimer; readonly breakdown?: boolean }): Integrator {
    const realTime = this.recipes.realTime;
    if (!realTime) throw new Error('Renderer: compile() the real-time chain before traceFrame()');
    this.checkSamples(samples, 'frame');
    this.residency.settleBeforeFrame();
    const encoder = this.device.createCommandEncoder({ label: 'real-time frame path tracing' });
    const integrator = realTime.encodeTraceOnly(encoder, this.state.frame(options.timer), samples, options.sampleIndex ?? 0, options.breakdown ?? false);
    options.timer?.resolve(encoder);
    this.device.queue.submit([encoder.finish()]);
    return integrator;
  }

  /** Renderer.beginFrame: the recipe the settings choose, or a debug view alone (nothing traced). */
  beginFrame(samples: number, timer?: GpuTimer): SplitFrame {
    const recipe = this.frameRecipe();
    this.checkSamples(samples, 'frame', recipe === this.recipes.realTime);
    // A debug view that replaces the image is drawn by present() and readImage(): nothing to trace.
    if (!recipe) return this.split({ splittable: false, band: () => {}, finish: () => {}, abandon: () => {} }, samples, 'frame', () => {});
    this.residency.settleBeforeFrame();
    const frame = this.state.frame(timer);
    const work = recipe.begin(frame, samples);
    return this.split({ ...work, finish: (encoder) => {
      work.finish(encoder);
      timer?.resolve(encoder);
    } }, samples, recipe === this.recipes.hybrid ? 'hybrid frame' : 'real-time frame', () => {
      this.lastFrame = recipe;
      this.shown = 'frame';
      this.residency.frameDone();
    });
  }

  /** Renderer.show: the estimate, or the last frame once one was rendered. */
  show(image: 'accumulation' | 'frame'): void {
    if (image === 'frame' && !this.lastFrame?.output) throw new Error('Renderer: renderFrame() before show(\'frame\')');
    this.shown = image;
  }

  /** The recipe a frame runs now (undefined: a debug view alone), compiled. */
  private frameRecipe(): FrameRecipe | undefined {
    return this.recipes.frameRecipe(recipeFor(this.state.settings(), { frames: true }));
  }

  /** Samples must be a positive whole number, and spectral paths (where they are traced: not by the hybrid recipe) compiled. */
  private checkSamples(samples: number, per: 'dispatch' | 'frame', tracesSpectral = true): void {
    this.state.targets();
    if (!Number.isInteger(samples) || samples < 1) throw new LanternError(`samples per ${per} must be a positive whole number, not ${samples}`);
    if (tracesSpectral && this.state.settings().spectral && !this.recipes.spectral) throw new Error('Renderer: compile() before rendering with settings.spectral');
  }

  /** A SplitFrame driving a recipe's frame; `done` runs once the last band is submitted. */
  private split(work: RecipeFrame, samples: number, label: string, done: () => void): SplitFrame {
    return new SplitFrame(this.host, this.state.targets(), samples, work.splittable, { ...work, done }, label);
  }
}
