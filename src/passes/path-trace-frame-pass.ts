/**
 * The real-time frame's path tracer (entry path_trace_frame of shaders/passes/path-trace-frame.wgsl,
 * which imports passes/path-trace): `samples` paths per pixel written, not added, as demodulated
 * radiance, plus the G-buffer. Compiled with CAPTURE_PRIMARY = 1, so the progressive kernel
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

/** What the frame kernel writes. */
export interface FrameTarget {
  /** vec4f per pixel: the frame's mean demodulated radiance. */
  readonly frameRadiance: GPUBuffer;
  /** GBufferTexel per pixel (shaders/denoise/gbuffer.wgsl). */
  readonly gbuffer: GPUBuffer;
  /** vec4f per pixel: normal and linear depth, the à-trous filter's guide. */
  readonly guide: GPUBuffer;
  /** The renderer's ray counters (as PathTraceTarget's): extension and shadow rays are added. */
  readonly rayCounters: GPUBuffer;
}

export class PathTraceFramePass {
  private constructor(
    /** Its kernels: the generic variants and, once the renderer specialises, the scene's own. */
    readonly kernels: TracingKernels,
    private readonly params: UniformParams<UniformValues>,
    private readonly frame: UniformParams<UniformValues>,
  ) {}

  static async create(device: GPUDevice): Promise<PathTraceFramePass> {
    const kernels = await TracingKernels.create(device, MODULE, 'path_trace_frame', { CAPTURE_PRIMARY: 1 });
    return new PathTraceFramePass(kernels, new UniformParams(device, PATH_TRACE_MODULE), new UniformParams(device, MODULE, 'frame'));
  }

  prepare(features: SceneFeatures, spectral = false): Promise<void> {
    return this.kernels.prepare(features, spectral);
  }

  /** Writes the parameters now (queue.writeBuffer): submit before encoding again. */
  encode(
    encoder: GPUCommandEncoder,
    scene: SceneResources,
    view: ViewUniform,
    previousCamera: Camera,
    target: FrameTarget,
    d: PathTraceDispatch,
    timer?: GpuTimer,
  ): void {
    this.params.write(pathTraceParams(d));
    this.frame.write({ previous_camera: cameraUniform(previousCamera, view.width / view.height) });
    const targets = () => ({ params: this.params.buffer, frame: this.frame.buffer, frame_radiance: target.frameRadiance, gbuffer: target.gbuffer, guide: target.guide, ray_counters: target.rayCounters });
    this.kernels.dispatch(encoder, 'path trace (frame)', scene, view, target.gbuffer, targets, d.tile, d.spectral ?? false, timer);
  }

  destroy(): void {
    this.params.destroy();
    this.frame.destroy();
  }
}
