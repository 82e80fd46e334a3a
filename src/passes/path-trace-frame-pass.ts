/**
 * The real-time frame's path tracer (entries frame_gbuffer then path_trace_frame of
 * shaders/passes/path-trace-frame.wgsl, which imports passes/path-trace): the G-buffer of the pixel
 * centres, then `samples` paths per pixel written, not added, as demodulated radiance. Compiled with CAPTURE_PRIMARY = 1, so the progressive kernel
 * (PathTracePass, CAPTURE_PRIMARY = 0) is untouched by the G-buffer writes.
 */
import type { SceneResources } from '../gpu/scene-resources.ts';
import type { GpuTimer } from '../gpu/timestamps.ts';
import { cameraUniform, type ViewUniform } from '../gpu/view.ts';
import type { Camera } from '../scene/types.ts';
import type { SceneFeatures } from '../gpu/pack/scene-pack.ts';
import { PATH_TRACE_MODULE, pathTraceParams, TracingKernels, type PathTraceDispatch } from './path-trace-pass.ts';
import { UniformParams, type UniformValues } from './uniform-params.ts';

const MODULE = 'passes/path-trace-frame';

/** What the frame kernel writes (the records of shaders/denoise/gbuffer.wgsl). */
export interface FrameTarget {
  /** Four words per pixel (FRAME_*): demodulated radiance (rgb9e5), motion, depth seen from the previous camera. */
  readonly scratch: GPUBuffer;
  /** SurfaceTexel per pixel: the pixel-centre surface (normal, linear depth, id). */
  readonly surface: GPUBuffer;
  /** FrameTexel per pixel: mean albedo and kept first-hit emission of the samples. */
  readonly frameRecords: GPUBuffer;
  /** The renderer's ray counters (as PathTraceTarget's): extension and shadow rays are added. */
  readonly rayCounters: GPUBuffer;
  /** Whether the first bounce takes its direct light from the frame's final reservoirs, lent in the scratch (RestirPass). */
  readonly restir: boolean;
}

export class PathTraceFramePass {
  private constructor(
    /** Its kernels: the generic variants and, once the renderer specialises, the scene's own. */
    readonly kernels: TracingKernels,
    /** The G-buffer pass before it (entry frame_gbuffer): generic variants only, RGB only. */
    private readonly gbufferKernels: TracingKernels,
    private readonly params: UniformParams<UniformValues>,
    /** The G-buffer's own `params` (its tile may differ from the paths' in one submission). */
    private readonly gbufferParams: UniformParams<UniformValues>,
    private readonly frame: UniformParams<UniformValues>,
  ) {}

  static async create(device: GPUDevice): Promise<PathTraceFramePass> {
    const [kernels, gbufferKernels] = await Promise.all([
      TracingKernels.create(device, MODULE, 'path_trace_frame', { CAPTURE_PRIMARY: 1, RESTIR: 1 }),
      TracingKernels.create(device, MODULE, 'frame_gbuffer', { CAPTURE_PRIMARY: 1 }),
    ]);
    return new PathTraceFramePass(kernels, gbufferKernels, new UniformParams(device, PATH_TRACE_MODULE), new UniformParams(device, PATH_TRACE_MODULE), new UniformParams(device, MODULE, 'frame'));
  }

  async prepare(features: SceneFeatures, spectral = false): Promise<void> {
    await Promise.all([this.kernels.prepare(features, spectral), this.gbufferKernels.prepare(features)]);
  }

  /**
   * The G-buffer then the paths of d.tile. Writes the parameters now (queue.writeBuffer): submit
   * before encoding again. `gbufferOnly`: the G-buffer pass alone (the wavefront traces the samples).
   */
  encode(encoder: GPUCommandEncoder, scene: SceneResources, view: ViewUniform, previousCamera: Camera, target: FrameTarget, d: PathTraceDispatch, timer?: GpuTimer, gbufferOnly = false): void {
    // The G-buffer first: the path kernel then reads the centre's id and filtered emission.
    this.encodeGbuffer(encoder, scene, view, previousCamera, target, d, timer);
    if (!gbufferOnly) this.encodePaths(encoder, scene, view, previousCamera, target, d, timer);
  }

  /**
   * The G-buffer of d.tile's pixel centres alone (with ReSTIR: the whole image, which the reservoir
   * passes read before any band's paths). It has its own parameters, so that it and a band's paths
   * (another tile) can go in one submission.
   */
  encodeGbuffer(encoder: GPUCommandEncoder, scene: SceneResources, view: ViewUniform, previousCamera: Camera, target: FrameTarget, d: PathTraceDispatch, timer?: GpuTimer): void {
    this.gbufferParams.write(pathTraceParams(d));
    this.writeFrame(view, previousCamera, target);
    this.gbufferKernels.dispatch(encoder, 'frame G-buffer', scene, view, target.surface, () => this.bindings(target, this.gbufferParams), d.tile, false, timer);
  }

  /** The paths of d.tile alone, over a G-buffer already recorded for it. */
  encodePaths(encoder: GPUCommandEncoder, scene: SceneResources, view: ViewUniform, previousCamera: Camera, target: FrameTarget, d: PathTraceDispatch, timer?: GpuTimer): void {
    this.params.write(pathTraceParams(d));
    this.writeFrame(view, previousCamera, target);
    this.kernels.dispatch(encoder, 'path trace (frame)', scene, view, target.surface, () => this.bindings(target, this.params), d.tile, d.spectral ?? false, timer);
  }

  private writeFrame(view: ViewUniform, previousCamera: Camera, target: FrameTarget): void {
    this.frame.write({ previous_camera: cameraUniform(previousCamera, view.width / view.height), restir: target.restir ? 1 : 0 });
  }

  private bindings(target: FrameTarget, params: UniformParams<UniformValues>): Record<string, GPUBuffer> {
    return { params: params.buffer, frame: this.frame.buffer, frame_scratch: target.scratch, surface_records: target.surface, frame_records: target.frameRecords, ray_counters: target.rayCounters };
  }

  destroy(): void {
    this.params.destroy();
    this.gbufferParams.destroy();
    this.frame.destroy();
  }
}
