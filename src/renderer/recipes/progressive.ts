/**
 * The progressive recipe (recipeFor's 'progressive'): paths added to the exact running estimate in
 * the image's accumulation buffer, which tone mapping divides by the sample count. Nothing is kept
 * between samples but that sum; the Renderer counts the samples and restarts the estimate.
 */
import type { SceneFeatures } from '../../gpu/pack/scene-pack.ts';
import type { GpuTimer } from '../../gpu/timestamps.ts';
import { PathTracePass, type Tile, type TracingKernels } from '../../passes/path-trace-pass.ts';
import type { Sampler } from '../../passes/variants.ts';
import { pathDispatch, type FrameContext } from '../frame.ts';
import type { RecipeFrame } from './frame-recipe.ts';

/** Timestamp slots a split accumulation leaves for the passes after its bands (tone map, present, debug). */
const TIMER_ROOM_AFTER_BANDS = 12;

export class ProgressiveRecipe {
  private constructor(private readonly pass: PathTracePass) {}

  /** `features`: those of the first scene, where known (or still loading): its variant compiles first, for `sampler` (default progressive renders' default). */
  static async create(device: GPUDevice, features?: SceneFeatures | Promise<SceneFeatures>, sampler?: Sampler): Promise<ProgressiveRecipe> {
    return new ProgressiveRecipe(await PathTracePass.create(device, features, sampler));
  }

  prepare(features: SceneFeatures, spectral = false): Promise<void> {
    return this.pass.prepare(features, spectral);
  }

  /** The path tracer's kernels (the renderer switches their sampler and specialises them). */
  get kernels(): TracingKernels {
    return this.pass.kernels;
  }

  /** Records `samples` paths per pixel over `tile`, the estimate's samples from `sampleIndex` on; with a timer, timed. */
  encode(encoder: GPUCommandEncoder, frame: FrameContext, tile: Tile, sampleIndex: number, samples: number, timer: GpuTimer | undefined = frame.timer): void {
    this.pass.encode(encoder, { scene: frame.scene, view: frame.view, target: frame.targets, dispatch: pathDispatch(frame, 'progressive', tile, sampleIndex, samples), timer });
  }

  /** `samples` paths per pixel in row bands, each band timed while the timer has room for the passes after them. */
  begin(frame: FrameContext, samples: number, sampleIndex: number): RecipeFrame {
    const timer = frame.timer;
    return {
      splittable: true,
      band: (encoder, tile) => this.encode(encoder, frame, tile, sampleIndex, samples, timer && timer.room > TIMER_ROOM_AFTER_BANDS ? timer : undefined),
      finish: (encoder) => timer?.resolve(encoder),
      abandon: () => {},
    };
  }

  destroy(): void {
    this.pass.destroy();
  }
}
