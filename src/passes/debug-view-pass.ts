/**
 * The tracing half of the debug views (shaders/passes/debug-view.wgsl): one pixel-centre primary ray
 * per pixel through the counting variant of the BVH traversal, raw values out.
 */
import { KernelVariants, TRAVERSAL_VARIANTS, traversalVariant, type TraversalVariant } from '../gpu/kernel.ts';
import type { SceneResources } from '../gpu/scene-resources.ts';
import type { GpuTimer } from '../gpu/timestamps.ts';
import { DEBUG_VIEWS, type DebugView } from './variants.ts';
import type { ViewUniform } from '../gpu/view.ts';
import { UniformParams } from './uniform-params.ts';

const MODULE = 'passes/debug-view';
/** Must match @workgroup_size of debug_view. */
const WORKGROUP = 8;

/** The traversal variants with scene/bvh.wgsl's work counters compiled in. */
const COUNTING_VARIANTS: Record<TraversalVariant, Record<string, number>> = {
  masked: { ...TRAVERSAL_VARIANTS.masked, BVH_COUNT_WORK: 1 },
  opaque: { ...TRAVERSAL_VARIANTS.opaque, BVH_COUNT_WORK: 1 },
};

export interface DebugViewTarget {
  readonly width: number;
  readonly height: number;
  /** Depth of every BVH node (u32 each). */
  readonly nodeDepths: GPUBuffer;
  /** vec4f per pixel. */
  readonly values: GPUBuffer;
  /** Two u32: the image's maximum of the view's scalar, and spare. Cleared here. */
  readonly range: GPUBuffer;
}

export class DebugViewPass {
  private constructor(
    private readonly kernels: KernelVariants<TraversalVariant>,
    private readonly params: UniformParams<{ view_kind: number }>,
  ) {}

  static async create(device: GPUDevice): Promise<DebugViewPass> {
    const kernels = await KernelVariants.create(device, { module: MODULE, entryPoint: 'debug_view' }, COUNTING_VARIANTS);
    return new DebugViewPass(kernels, new UniformParams(device, MODULE));
  }

  /** Writes the parameters now (queue.writeBuffer): submit before encoding again. */
  encode(encoder: GPUCommandEncoder, scene: SceneResources, view: ViewUniform, target: DebugViewTarget, debugView: DebugView, timer?: GpuTimer): void {
    this.params.write({ view_kind: DEBUG_VIEWS.indexOf(debugView) });
    const kernel = this.kernels.get(traversalVariant(scene.counts.maskedTriangles));
    encoder.clearBuffer(target.range);
    const pass = encoder.beginComputePass({ label: 'debug view', ...(timer ? { timestampWrites: timer.timestampWrites('debug view') } : {}) });
    kernel.dispatch(
      pass,
      {
        0: kernel.bindGroup(0, scene.bindings),
        1: kernel.bindGroup(1, { view: view.buffer }),
        2: kernel.bindGroup(2, { params: this.params.buffer, node_depths: target.nodeDepths, debug_values: target.values, debug_range: target.range }),
      },
      Math.ceil(target.width / WORKGROUP),
      Math.ceil(target.height / WORKGROUP),
    );
    pass.end();
  }

  destroy(): void {
    this.params.destroy();
  }
}
