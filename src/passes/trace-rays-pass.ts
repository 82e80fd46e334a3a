/**
 * Closest-hit tracing of a ray buffer (shaders/passes/trace-rays.wgsl): the traversal benchmark and
 * the GPU side of the traversal-versus-oracle test.
 */
import { SceneKernels, TRAVERSAL_FEATURES, type ComputeKernel } from '../gpu/kernel.ts';
import type { SceneFeatures } from '../gpu/pack/scene-pack.ts';
import type { SceneResources } from '../gpu/scene-resources.ts';
import type { GpuTimer } from '../gpu/timestamps.ts';
import { reflectModule, structLayout } from '../gpu/wgsl/reflect.ts';
import { UniformParams } from './uniform-params.ts';

const MODULE = 'passes/trace-rays';
const WORKGROUP = 64;

/** Bytes per ray and per hit record, from the WGSL structs. */
export function rayBufferStrides(): { ray: number; hit: number } {
  const { defs } = reflectModule(MODULE);
  return { ray: structLayout(defs, 'Ray').stride, hit: structLayout(defs, 'HitRecord').stride };
}

/** Workgroup grid for `count` invocations of WORKGROUP threads, as rows within the dispatch limit. */
export function rayDispatchSize(count: number, maxPerDimension: number): [number, number] {
  const groups = Math.ceil(count / WORKGROUP);
  const x = Math.min(groups, maxPerDimension);
  return [x, Math.ceil(groups / x)];
}

/** What tracing one ray buffer needs: the kernel variant for the scene and its bind groups. */
export interface TraceRaysBinding {
  readonly kernel: ComputeKernel;
  readonly 0: GPUBindGroup;
  readonly 2: GPUBindGroup;
  readonly count: number;
}

export class TraceRaysPass {
  private constructor(
    private readonly device: GPUDevice,
    private readonly kernels: SceneKernels,
    private readonly params: UniformParams<{ ray_count: number }>,
  ) {}

  static async create(device: GPUDevice): Promise<TraceRaysPass> {
    const kernels = await SceneKernels.create(device, { module: MODULE, entryPoint: 'trace_rays' }, TRAVERSAL_FEATURES);
    return new TraceRaysPass(device, kernels, new UniformParams(device, MODULE));
  }

  /** Bind groups for tracing `rays` into `hits`; reuse them to trace the same buffers many times. */
  async bind(scene: SceneResources, rays: GPUBuffer, hits: GPUBuffer, count: number): Promise<TraceRaysBinding> {
    await this.kernels.prepare(scene.features);
    this.params.write({ ray_count: count });
    const kernel = this.kernels.get(scene.features);
    return { kernel, 0: kernel.bindGroup(0, scene.bindings), 2: kernel.bindGroup(2, { params: this.params.buffer, rays, hits }), count };
  }

  encode(encoder: GPUCommandEncoder, binding: TraceRaysBinding, timer?: GpuTimer, label = 'trace rays'): void {
    const pass = encoder.beginComputePass({ label, ...(timer ? { timestampWrites: timer.timestampWrites(label) } : {}) });
    const [x, y] = rayDispatchSize(binding.count, this.device.limits.maxComputeWorkgroupsPerDimension);
    binding.kernel.dispatch(pass, { 0: binding[0], 2: binding[2] }, x, y);
    pass.end();
  }

  destroy(): void {
    this.params.destroy();
  }
}
