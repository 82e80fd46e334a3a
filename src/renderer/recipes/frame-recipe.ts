/**
 * The contract between the Renderer and a recipe's frame (renderer/recipes/recipe.ts names the
 * recipes): a recipe begins a frame from a FrameContext (renderer/frame.ts) and hands back the work
 * a SplitFrame drives, a band of the tracing at a time, the passes after the tracing with the last.
 */
import type { SceneFeatures } from '../../gpu/pack/scene-pack.ts';
import type { SplitWork } from '../split-frame.ts';
import type { FrameContext } from '../frame.ts';

/** One frame of a recipe, as SplitFrame records it (what completes it is the Renderer's: SplitWork.done). */
export interface RecipeFrame extends Omit<SplitWork, 'done'> {
  /** Whether the tracing can be cut into row bands (false: one band, the whole image). */
  readonly splittable: boolean;
}

/** A recipe that renders frames (the real-time chain, the hybrid recipe, a debug view alone). */
export interface FrameRecipe {
  /** Compiles the recipe's kernels for a scene with these features (`spectral`: its spectral variants too, where it has them). */
  prepare(features: SceneFeatures, spectral?: boolean): Promise<void>;
  /** Begins a frame of `samples` paths per pixel (a recipe may trace fewer: the hybrid's one). */
  begin(frame: FrameContext, samples: number): RecipeFrame;
  /** The linear output of the last finished frame (a vec4f per pixel), once there is one. */
  readonly output: GPUBuffer | undefined;
  /** Whether present and readImage show the output as computed (a debug view of the chain: no exposure, no tone curve). */
  showsRawValues(frame: Pick<FrameContext, 'settings'>): boolean;
  /** Forgets the history: the next frame starts from its own samples alone. */
  resetHistory(): void;
  destroy(): void;
}
