/**
 * ReSTIR DI for the real-time frame (entries restir_initial, restir_temporal and restir_spatial of
 * shaders/restir/restir.wgsl, each a timed pass of its own): over the whole image, between the
 * G-buffer and the frame path tracer's bands, each pixel-centre surface resamples light candidates,
 * reuses the previous frame's reservoir through the motion vectors and its neighbours' reservoirs,
 * and leaves one final reservoir per pixel that the path tracer shades (shaders/integrator/path.wgsl,
 * RESTIR). The reservoir under way lives in two words of the frame scratch between the passes; the
 * frame's final reservoirs go to a buffer free until the frame's filters run (the Denoiser lends the
 * current moments), restir_lend copies them back into those two scratch words for the path tracer
 * (which has no storage binding to spare in a browser), and keepHistory copies them to the history
 * (8 bytes a pixel, the only buffer of ReSTIR's own) once the frame is finished, so a frame given up
 * leaves the history as it was.
 */
import type { SceneResources } from '../gpu/scene-resources.ts';
import { cameraUniform, type ViewUniform } from '../gpu/view.ts';
import type { SceneFeatures } from '../gpu/pack/scene-pack.ts';
import type { Camera } from '../scene/types.ts';
import { PATH_TRACE_MODULE, pathTraceParams, TracingKernels, type PathTraceDispatch } from './path-trace-pass.ts';
import type { Pass, PassFrame } from './pass.ts';
import { UniformParams, type UniformValues } from './uniform-params.ts';

const MODULE = 'restir/restir';

/** Spatial reuse: neighbours per pixel (the unbiased combination traces a shadow ray for each). */
export const RESTIR_NEIGHBOURS = 3;

/** The spatial radius in pixels: about 2.5 % of the image height (Bitterli et al. use 30 px at 1080p), at least 3. */
export function restirRadius(height: number): number {
  return Math.min(30, Math.max(3, 0.025 * height));
}

export interface RestirTarget {
  /** The frame scratch: the G-buffer's motion and previous depth are read; the reservoir under way goes to words 0 and 3. */
  readonly scratch: GPUBuffer;
  readonly surface: GPUBuffer;
  readonly previousSurface: GPUBuffer;
  /** This frame's final reservoirs (ReservoirTexel per pixel), written by the spatial pass. */
  readonly reservoirs: GPUBuffer;
  /** The last finished frame's final reservoirs, read (reprojected) by the temporal pass. */
  readonly previousReservoirs: GPUBuffer;
  readonly rayCounters: GPUBuffer;
}

export interface RestirDispatch {
  readonly trace: PathTraceDispatch;
  readonly candidates: number;
  /** Whether `reservoirs` holds the previous frame's (same size, history not reset). */
  readonly useHistory: boolean;
}

export interface RestirFrame extends PassFrame {
  readonly scene: SceneResources;
  readonly view: ViewUniform;
  /** The camera of the previous frame (reprojection of its reservoirs). */
  readonly previousCamera: Camera;
  readonly target: RestirTarget;
  readonly dispatch: RestirDispatch;
}

export class RestirPass implements Pass<RestirFrame> {
  private constructor(
    private readonly initial: TracingKernels,
    private readonly temporal: TracingKernels,
    private readonly spatial: TracingKernels,
    private readonly lend: TracingKernels,
    private readonly params: UniformParams<UniformValues>,
    private readonly restir: UniformParams<UniformValues>,
  ) {}

  /** `first`: the features of the scene to be rendered, where known: its variants start compiling instead of a plain scene's (SceneKernels.create). */
  static async create(device: GPUDevice, first?: SceneFeatures): Promise<RestirPass> {
    const [initial, temporal, spatial, lend] = await Promise.all(['restir_initial', 'restir_temporal', 'restir_spatial', 'restir_lend'].map((entry) => TracingKernels.create(device, MODULE, entry, {}, first)));
    return new RestirPass(initial!, temporal!, spatial!, lend!, new UniformParams(device, PATH_TRACE_MODULE), new UniformParams(device, MODULE, 'restir'));
  }

  async prepare(features: SceneFeatures): Promise<void> {
    await Promise.all([this.initial, this.temporal, this.spatial, this.lend].map((k) => k.prepare(features)));
  }

  /** Records the three passes over the whole image, and the final reservoirs' copy into the scratch (restir_lend). Writes the parameters now (queue.writeBuffer): submit before encoding again. */
  encode(encoder: GPUCommandEncoder, { scene, view, previousCamera, target, dispatch: d, timer }: RestirFrame): void {
    this.params.write(pathTraceParams(d.trace));
    this.restir.write({
      previous_camera: cameraUniform(previousCamera, view.width / view.height),
      candidates: d.candidates,
      use_history: d.useHistory ? 1 : 0,
      neighbours: RESTIR_NEIGHBOURS,
      radius: restirRadius(view.height),
    });
    const targets = () => ({
      params: this.params.buffer,
      restir: this.restir.buffer,
      frame_scratch: target.scratch,
      surface_records: target.surface,
      previous_surface_records: target.previousSurface,
      reservoirs: target.reservoirs,
      previous_reservoirs: target.previousReservoirs,
      ray_counters: target.rayCounters,
    });
    const tile = { x: 0, y: 0, width: view.width, height: view.height };
    this.initial.dispatch(encoder, 'restir initial', scene, view, target.surface, targets, tile, false, timer);
    this.temporal.dispatch(encoder, 'restir temporal', scene, view, target.surface, targets, tile, false, timer);
    this.spatial.dispatch(encoder, 'restir spatial', scene, view, target.surface, targets, tile, false, timer);
    this.lend.dispatch(encoder, 'restir lend', scene, view, target.surface, targets, tile, false, timer);
  }

  /** Records the copy of a finished frame's final reservoirs into the history the next frame's temporal pass reads. */
  keepHistory(encoder: GPUCommandEncoder, target: RestirTarget): void {
    encoder.copyBufferToBuffer(target.reservoirs, 0, target.previousReservoirs, 0, target.previousReservoirs.size);
  }

  destroy(): void {
    this.params.destroy();
    this.restir.destroy();
  }
}
