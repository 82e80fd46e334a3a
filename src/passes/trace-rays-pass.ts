/**
 * Closest-hit tracing of a ray buffer (shaders/passes/trace-rays.wgsl): the traversal benchmark and
 * the GPU side of the traversal-versus-oracle test.
 */
import { WORKGROUP } from '../gpu/kernel-variants.ts';
import { SceneKernels, TRAVERSAL_FEATURES, type ComputeKernel } from '../gpu/kernel.ts';
import type { SceneFeatures } from '../gpu/pack/scene-pack.ts';
import type { SceneResources } from '../gpu/scene-resources.ts';
import { reflectModule, structLayout } from '../gpu/wgsl/reflect.ts';
import { StructArray } from '../gpu/pack/struct-array.ts';
import type { Vec3 } from '../math/vec3.ts';
import type { Pass, PassFrame } from './pass.ts';
import { UniformParams } from './uniform-params.ts';

const MODULE = 'passes/trace-rays';

/** Bytes per ray and per hit record, from the WGSL structs. */
export function rayBufferStrides(): { ray: number; hit: number } {
  const { defs } = reflectModule(MODULE);
  return { ray: structLayout(defs, 'Ray').stride, hit: structLayout(defs, 'HitRecord').stride };
}

/** A ray of the ray buffer: hits count at t_min < t < t_max, in units of |direction|. */
export interface TraceRay {
  readonly origin: Vec3;
  readonly direction: Vec3;
  readonly tMin?: number;
  readonly tMax?: number;
}

/** One HitRecord: distance, source triangle (NO_TRIANGLE: a miss) and the barycentrics of v1 and v2. */
export interface TraceHit {
  readonly t: number;
  readonly triangle: number;
  readonly u: number;
  readonly v: number;
}

/** The WGSL Ray array for `rays` (as f32: what the GPU traces). */
export function packRays(rays: readonly TraceRay[]): ArrayBuffer {
  const out = new StructArray(structLayout(reflectModule(MODULE).defs, 'Ray'), rays.length);
  const origin = out.vec3('origin'), direction = out.vec3('direction'), tMin = out.f32Field('t_min'), tMax = out.f32Field('t_max');
  rays.forEach((r, i) => {
    origin(i, ...r.origin);
    direction(i, ...r.direction);
    tMin(i, r.tMin ?? 0);
    tMax(i, r.tMax ?? 3e38);
  });
  return out.bytes;
}

/** The first `count` HitRecords of a hit buffer read back. */
export function unpackHits(raw: ArrayBuffer, count: number): TraceHit[] {
  const layout = structLayout(reflectModule(MODULE).defs, 'HitRecord');
  const f32 = new Float32Array(raw), u32 = new Uint32Array(raw);
  const s = layout.strideWords, t = layout.word('t'), tri = layout.word('triangle'), u = layout.word('u'), v = layout.word('v');
  return Array.from({ length: count }, (_, i) => ({ t: f32[i * s + t]!, triangle: u32[i * s + tri]!, u: f32[i * s + u]!, v: f32[i * s + v]! }));
}

/** Workgroup grid for `count` invocations of WORKGROUP.rays threads, as rows within the dispatch limit. */
export function rayDispatchSize(count: number, maxPerDimension: number): [number, number] {
  const groups = Math.ceil(count / WORKGROUP.rays);
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

export interface TraceRaysFrame extends PassFrame {
  /** The buffers to trace (bind()). */
  readonly binding: TraceRaysBinding;
  /** The compute pass's label and timer label. */
  readonly label?: string;
}

export class TraceRaysPass implements Pass<TraceRaysFrame> {
  private constructor(
    private readonly device: GPUDevice,
    private readonly kernels: SceneKernels,
    private readonly params: UniformParams<{ ray_count: number }>,
  ) {}

  /** `first`: the features of the scene to be rendered, where known: its variants start compiling instead of a plain scene's (SceneKernels.create). */
  static async create(device: GPUDevice, first?: SceneFeatures): Promise<TraceRaysPass> {
    const kernels = await SceneKernels.create(device, { module: MODULE, entryPoint: 'trace_rays' }, TRAVERSAL_FEATURES, {}, first);
    return new TraceRaysPass(device, kernels, new UniformParams(device, MODULE));
  }

  /** Bind groups for tracing `rays` into `hits`; reuse them to trace the same buffers many times. */
  async bind(scene: SceneResources, rays: GPUBuffer, hits: GPUBuffer, count: number): Promise<TraceRaysBinding> {
    await this.kernels.prepare(scene.features);
    this.params.write({ ray_count: count });
    const kernel = this.kernels.get(scene.features);
    return { kernel, 0: kernel.bindGroup(0, scene.bindings), 2: kernel.bindGroup(2, { params: this.params.buffer, rays, hits }), count };
  }

  encode(encoder: GPUCommandEncoder, { binding, timer, label = 'trace rays' }: TraceRaysFrame): void {
    const pass = encoder.beginComputePass({ label, ...(timer ? { timestampWrites: timer.timestampWrites(label) } : {}) });
    const [x, y] = rayDispatchSize(binding.count, this.device.limits.maxComputeWorkgroupsPerDimension);
    binding.kernel.dispatch(pass, { 0: binding[0], 2: binding[2] }, x, y);
    pass.end();
  }

  destroy(): void {
    this.params.destroy();
  }
}
