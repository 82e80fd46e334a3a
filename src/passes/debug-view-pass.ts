/**
 * The tracing half of the debug views (shaders/passes/debug-view.wgsl): one pixel-centre primary ray
 * per pixel through the counting variant of the BVH traversal, raw values out.
 */
import { KERNEL_CONSTANTS, pixelGroups } from '../gpu/kernel-variants.ts';
import { SceneKernels, TRAVERSAL_FEATURES } from '../gpu/kernel.ts';
import type { SceneFeatures } from '../gpu/pack/scene-pack.ts';
import type { SceneResources } from '../gpu/scene-resources.ts';
import { DEBUG_VIEWS, type DebugView } from './variants.ts';
import type { ViewUniform } from '../gpu/view.ts';
import type { Pass, PassFrame } from './pass.ts';
import { UniformParams } from './uniform-params.ts';

const MODULE = 'passes/debug-view';

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

export interface DebugViewFrame extends PassFrame {
  readonly scene: SceneResources;
  readonly view: ViewUniform;
  readonly target: DebugViewTarget;
  readonly debugView: DebugView;
}

export class DebugViewPass implements Pass<DebugViewFrame> {
  private constructor(
    private readonly kernels: SceneKernels,
    private readonly params: UniformParams<{ view_kind: number }>,
  ) {}

  /** `first`: the features of the scene to be rendered, where known: its variants start compiling instead of a plain scene's (SceneKernels.create). */
  static async create(device: GPUDevice, first?: SceneFeatures): Promise<DebugViewPass> {
    // The traversal with scene/bvh.wgsl's work counters compiled in; variants by alpha tests only.
    const kernels = await SceneKernels.create(device, { module: MODULE, entryPoint: 'debug_view' }, TRAVERSAL_FEATURES, KERNEL_CONSTANTS.debugView, first);
    return new DebugViewPass(kernels, new UniformParams(device, MODULE));
  }

  prepare(features: SceneFeatures): Promise<void> {
    return this.kernels.prepare(features);
  }

  /** Writes the parameters now (queue.writeBuffer): submit before encoding again. */
  encode(encoder: GPUCommandEncoder, { scene, view, target, debugView, timer }: DebugViewFrame): void {
    this.params.write({ view_kind: DEBUG_VIEWS.indexOf(debugView) });
    const kernel = this.kernels.get(scene.features);
    encoder.clearBuffer(target.range);
    const pass = encoder.beginComputePass({ label: 'debug view', ...(timer ? { timestampWrites: timer.timestampWrites('debug view') } : {}) });
    kernel.dispatch(
      pass,
      {
        0: kernel.bindGroup(0, scene.bindings),
        1: kernel.bindGroup(1, { view: view.buffer }),
        2: kernel.bindGroup(2, { params: this.params.buffer, node_depths: target.nodeDepths, debug_values: target.values, debug_range: target.range }),
      },
      ...pixelGroups(target.width, target.height),
    );
    pass.end();
  }

  destroy(): void {
    this.params.destroy();
  }
}
