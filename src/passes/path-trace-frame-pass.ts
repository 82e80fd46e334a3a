/**
 * The real-time frame's path tracer (entries frame_gbuffer then path_trace_frame of
 * shaders/passes/path-trace-frame.wgsl, on integrator/frame and integrator/dispatch): the G-buffer of
 * the pixel centres and, once their neighbours' are written, the pixels' emission (frame_gbuffer
 * twice), then `samples` paths per pixel written, not added, as demodulated radiance. The frame
 * kernel is compiled with RESTIR (kernel-variants.ts); the progressive kernel is not.
 */
import type { SceneResources } from '../gpu/scene-resources.ts';
import type { GpuTimer } from '../gpu/timestamps.ts';
import { cameraUniform, type ViewUniform } from '../gpu/view.ts';
import type { Camera } from '../scene/types.ts';
import type { SceneFeatures } from '../gpu/pack/scene-pack.ts';
import { PATH_TRACE_MODULE, pathTraceParams, TracingKernels, type PathTraceDispatch } from './path-trace-pass.ts';
import { KERNEL_CONSTANTS } from '../gpu/kernel-variants.ts';
import type { Pass, PassFrame } from './pass.ts';
import { UniformParams, type UniformValues } from './uniform-params.ts';
import { resolveSampler, type Sampler } from './variants.ts';

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

/** What the frame path tracer is given for one tile (a band, or the whole image). */
export interface RealTimeTraceFrame extends PassFrame {
  readonly scene: SceneResources;
  readonly view: ViewUniform;
  /** The camera of the previous frame (motion vectors, previous depth). */
  readonly previousCamera: Camera;
  readonly target: FrameTarget;
  readonly dispatch: PathTraceDispatch;
  /**
   * Record one half alone: 'gbuffer' the G-buffer of the tile's pixel centres and their emission
   * (the wavefront traces the samples; with ReSTIR, the whole image's before the reservoirs),
   * 'paths' the paths over a G-buffer already recorded for the tile. Absent: both, G-buffer first.
   */
  readonly only?: 'gbuffer' | 'paths';
}

export class PathTraceFramePass implements Pass<RealTimeTraceFrame> {
  /** The emission pass's bind-group keys, one per surface-record buffer (the centres pass is keyed by the buffer itself). */
  private readonly emissionKeys = new WeakMap<GPUBuffer, object>();

  private constructor(
    /** Its kernels: the generic variants and, once the renderer specialises, the scene's own. */
    readonly kernels: TracingKernels,
    /** The G-buffer pass before it (entry frame_gbuffer): generic variants only, RGB only. */
    private readonly gbufferKernels: TracingKernels,
    private readonly params: UniformParams<UniformValues>,
    /** The G-buffer's own `params` (its tile may differ from the paths' in one submission). */
    private readonly gbufferParams: UniformParams<UniformValues>,
    /** The emission pass's `params` (the tile without the G-buffer's ring). */
    private readonly emissionParams: UniformParams<UniformValues>,
    private readonly frame: UniformParams<UniformValues>,
    /** `frame` for the G-buffer's centres (the tile whose rays count) and its emission pass (emission_pass = 1). */
    private readonly gbufferFrame: UniformParams<UniformValues>,
    private readonly emissionFrame: UniformParams<UniformValues>,
  ) {}

  /**
   * `first`: the features of the scene to be rendered, where known: its variants start compiling
   * instead of a plain scene's (SceneKernels.create). `sampler`: the one the settings ask for (default
   * the real-time chain's), so that a renderer set to another one does not compile the default's first.
   */
  static async create(device: GPUDevice, first?: SceneFeatures, sampler: Sampler = resolveSampler('auto', 'real-time')): Promise<PathTraceFramePass> {
    const [kernels, gbufferKernels] = await Promise.all([
      TracingKernels.create(device, MODULE, 'path_trace_frame', KERNEL_CONSTANTS.pathTraceFrame, first, sampler),
      TracingKernels.create(device, MODULE, 'frame_gbuffer', {}, first),
    ]);
    const params = () => new UniformParams(device, PATH_TRACE_MODULE);
    const frame = () => new UniformParams(device, MODULE, 'frame');
    return new PathTraceFramePass(kernels, gbufferKernels, params(), params(), params(), frame(), frame(), frame());
  }

  async prepare(features: SceneFeatures, spectral = false): Promise<void> {
    await Promise.all([this.kernels.prepare(features, spectral), this.gbufferKernels.prepare(features)]);
  }

  /**
   * The G-buffer then the paths of the dispatch's tile (or the half `only` names). Writes the
   * parameters now (queue.writeBuffer): submit before encoding again.
   */
  encode(encoder: GPUCommandEncoder, f: RealTimeTraceFrame): void {
    // The G-buffer first: the path kernel then reads the centre's id and filtered emission.
    if (f.only !== 'paths') this.encodeGbuffer(encoder, f.scene, f.view, f.previousCamera, f.target, f.dispatch, f.timer);
    if (f.only !== 'gbuffer') this.encodePaths(encoder, f.scene, f.view, f.previousCamera, f.target, f.dispatch, f.timer);
  }

  /**
   * The G-buffer of d.tile's pixel centres alone (with ReSTIR: the whole image, which the reservoir
   * passes read before any band's paths), then its pixels' emission. It has its own parameters, so
   * that it and a band's paths (another tile) can go in one submission. The centres are traced over
   * the tile and one pixel around it (within the image): the emission pass looks at each pixel's
   * neighbours, which must be this frame's wherever the frame is cut into bands, so that a banded
   * frame equals a whole one.
   */
  private encodeGbuffer(encoder: GPUCommandEncoder, scene: SceneResources, view: ViewUniform, previousCamera: Camera, target: FrameTarget, d: PathTraceDispatch, timer?: GpuTimer): void {
    const t = d.tile;
    const x0 = Math.max(t.x - 1, 0), y0 = Math.max(t.y - 1, 0);
    const ring = { x: x0, y: y0, width: Math.min(t.x + t.width + 1, view.width) - x0, height: Math.min(t.y + t.height + 1, view.height) - y0 };
    this.gbufferParams.write(pathTraceParams({ ...d, tile: ring }));
    this.emissionParams.write(pathTraceParams(d));
    const frame = this.frameValues(view, previousCamera, target);
    this.gbufferFrame.write({ ...frame, emission_pass: 0, core_min: [t.x, t.y], core_max: [t.x + t.width, t.y + t.height] });
    this.emissionFrame.write({ ...frame, emission_pass: 1 });
    this.gbufferKernels.dispatch(encoder, 'frame G-buffer', scene, view, target.surface, () => this.bindings(target, this.gbufferParams, this.gbufferFrame), ring, false, timer);
    // Its own bind group (other parameters, same target): keyed by a token of the target's surface records.
    let key = this.emissionKeys.get(target.surface);
    if (!key) this.emissionKeys.set(target.surface, (key = {}));
    this.gbufferKernels.dispatch(encoder, 'frame emission', scene, view, key, () => this.bindings(target, this.emissionParams, this.emissionFrame), t, false, timer);
  }

  /** The paths of d.tile alone, over a G-buffer already recorded for it. */
  private encodePaths(encoder: GPUCommandEncoder, scene: SceneResources, view: ViewUniform, previousCamera: Camera, target: FrameTarget, d: PathTraceDispatch, timer?: GpuTimer): void {
    this.params.write(pathTraceParams(d));
    this.frame.write(this.frameValues(view, previousCamera, target));
    this.kernels.dispatch(encoder, 'path trace (frame)', scene, view, target.surface, () => this.bindings(target, this.params, this.frame), d.tile, d.spectral ?? false, timer);
  }

  private frameValues(view: ViewUniform, previousCamera: Camera, target: FrameTarget): UniformValues {
    return { previous_camera: cameraUniform(previousCamera, view.width / view.height), restir: target.restir ? 1 : 0 };
  }

  private bindings(target: FrameTarget, params: UniformParams<UniformValues>, frame: UniformParams<UniformValues>): Record<string, GPUBuffer> {
    return { params: params.buffer, frame: frame.buffer, frame_scratch: target.scratch, surface_records: target.surface, frame_records: target.frameRecords, ray_counters: target.rayCounters };
  }

  destroy(): void {
    for (const u of [this.params, this.gbufferParams, this.emissionParams, this.frame, this.gbufferFrame, this.emissionFrame]) u.destroy();
  }
}
