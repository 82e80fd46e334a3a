/**
 * The real-time frame's path tracer (entry path_trace_frame of shaders/passes/path-trace-frame.wgsl,
 * which imports passes/path-trace): `samples` paths per pixel written, not added, as demodulated
 * radiance, plus the G-buffer. Compiled with CAPTURE_PRIMARY = 1, so the progressive kernel
 * (PathTracePass, CAPTURE_PRIMARY = 0) is untouched by the G-buffer writes.
 */
import { KernelVariants, TRAVERSAL_VARIANTS, traversalVariant, type ComputeKernel, type TraversalVariant } from '../gpu/kernel.ts';
import type { SceneResources } from '../gpu/scene-resources.ts';
import type { GpuTimer } from '../gpu/timestamps.ts';
import { cameraBasis, type ViewUniform } from '../renderer/view.ts';
import type { Camera } from '../scene/types.ts';
import { cached, PATH_TRACE_MODULE, PATH_TRACE_WORKGROUP, pathTraceParams, type PathTraceDispatch } from './path-trace-pass.ts';
import { UniformParams, type UniformValues } from './uniform-params.ts';

const MODULE = 'passes/path-trace-frame';

const FRAME_VARIANTS: Record<TraversalVariant, Record<string, number>> = {
  masked: { ...TRAVERSAL_VARIANTS.masked, CAPTURE_PRIMARY: 1 },
  opaque: { ...TRAVERSAL_VARIANTS.opaque, CAPTURE_PRIMARY: 1 },
};

/** What the frame kernel writes. */
export interface FrameTarget {
  /** vec4f per pixel: the frame's mean demodulated radiance. */
  readonly frameRadiance: GPUBuffer;
  /** GBufferTexel per pixel (shaders/denoise/gbuffer.wgsl). */
  readonly gbuffer: GPUBuffer;
}

export class PathTraceFramePass {
  private readonly sceneGroups = new WeakMap<ComputeKernel, WeakMap<SceneResources, GPUBindGroup>>();
  private readonly viewGroups = new WeakMap<ComputeKernel, WeakMap<ViewUniform, GPUBindGroup>>();
  private readonly targetGroups = new WeakMap<ComputeKernel, WeakMap<GPUBuffer, GPUBindGroup>>();

  private constructor(
    private readonly kernels: KernelVariants<TraversalVariant>,
    private readonly params: UniformParams<UniformValues>,
    private readonly frame: UniformParams<UniformValues>,
  ) {}

  static async create(device: GPUDevice): Promise<PathTraceFramePass> {
    const kernels = await KernelVariants.create(device, { module: MODULE, entryPoint: 'path_trace_frame' }, FRAME_VARIANTS);
    return new PathTraceFramePass(kernels, new UniformParams(device, PATH_TRACE_MODULE), new UniformParams(device, MODULE, 'frame'));
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
    const b = cameraBasis(previousCamera, view.width / view.height);
    this.frame.write({ previous_camera: { position: b.position, right: b.right, up: b.up, forward: b.forward } });
    const kernel = this.kernels.get(traversalVariant(scene.counts.maskedTriangles));
    const pass = encoder.beginComputePass({ label: 'path trace (frame)', ...(timer ? { timestampWrites: timer.timestampWrites('path trace (frame)') } : {}) });
    kernel.dispatch(
      pass,
      {
        0: cached(this.sceneGroups, kernel, scene, () => kernel.bindGroup(0, scene.bindings)),
        1: cached(this.viewGroups, kernel, view, () => kernel.bindGroup(1, { view: view.buffer })),
        2: cached(this.targetGroups, kernel, target.gbuffer, () =>
          kernel.bindGroup(2, { params: this.params.buffer, frame: this.frame.buffer, frame_radiance: target.frameRadiance, gbuffer: target.gbuffer }),
        ),
      },
      Math.ceil(d.tile.width / PATH_TRACE_WORKGROUP),
      Math.ceil(d.tile.height / PATH_TRACE_WORKGROUP),
    );
    pass.end();
  }

  destroy(): void {
    this.params.destroy();
    this.frame.destroy();
  }
}
