/**
 * Issue #28: one contract for every pass. A pass is made once (its static `create`, which compiles
 * its pipelines) and then records its GPU work with `encode(encoder, frame)`: everything it reads
 * and writes for that recording comes in `frame`, an object of the pass's own frame type, which
 * extends PassFrame with the pass's inputs and outputs (targets, dispatch record, bind groups,
 * label). A frame is a small object of references, built per call (per band where a recipe bands a
 * frame): nothing in it is copied by the pass.
 *
 * What a pass makes comes back one way: `encode` returns nothing. Outputs the caller owns are in
 * the frame (a target texture or buffer the pass writes); outputs the pass owns (its own texture or
 * state buffer, sized by the pass) are read-only properties of the pass, valid once `encode` has
 * recorded them: SelectionOutlinePass.output, ExposurePass.state (and ExposurePass.read() for its
 * value on the CPU).
 *
 * Besides encode and destroy a pass may have methods of its own that record nothing per frame
 * (prepare, bind, write, compileSpecialised, useSpecialised) or record a step outside its frame's
 * work (RestirPass.keepHistory, after the frame is finished).
 *
 * tests/architecture/pass-contract.test.ts checks that every *Pass class exported from src/passes
 * implements Pass and that its encode takes (encoder, frame).
 */
import type { SceneResources } from '../gpu/scene-resources.ts';
import type { GpuTimer } from '../gpu/timestamps.ts';
import type { ViewUniform } from '../gpu/view.ts';

/**
 * What any pass may be given for a frame. A pass's frame type makes required what it reads (most
 * take `view`; those that trace the scene take `scene`). The renderer's FrameContext has these
 * names too, so a recipe hands the same references on.
 */
export interface PassFrame {
  /** The scene's GPU resources (bind group 0 of the passes that trace or draw it). */
  readonly scene?: SceneResources;
  /** The view uniform (bind group 1): camera and image size. */
  readonly view?: ViewUniform;
  /** Times the pass's compute or render passes (under the labels each pass documents), where given. */
  readonly timer?: GpuTimer | undefined;
}

/** A pass: made once, then `encode` per frame (or band) with its frame type `F`. */
export interface Pass<F extends PassFrame> {
  /** Records the pass's GPU work for `frame` into `encoder`. Returns nothing: see the file's comment for where outputs are. */
  encode(encoder: GPUCommandEncoder, frame: F): void;
  /** Frees the GPU resources the pass owns (its uniforms, state and own outputs). */
  destroy(): void;
}
