/** The path tracer dispatch (shaders/passes/path-trace.wgsl): adds samples to the accumulation buffer. */
import { ComputeKernel } from '../gpu/kernel.ts';
import type { SceneResources } from '../gpu/scene-resources.ts';
import type { GpuTimer } from '../gpu/timestamps.ts';
import type { ViewUniform } from '../renderer/view.ts';
import { LIGHT_SAMPLING, type LightSampling } from '../renderer/settings.ts';
import type { Torch } from '../scene/types.ts';
import { UniformParams, type UniformValues } from './uniform-params.ts';

/** shaders/scene/torch.wgsl TorchLight: surface radiance I / (π r²) gives intensity I far away. */
function torchUniform(torch: Torch | undefined): { radiance: number[]; radius: number; range: number } {
  if (!torch) return { radiance: [0, 0, 0], radius: 1, range: 1 };
  const l = torch.intensity / (Math.PI * torch.radius * torch.radius);
  return { radiance: torch.color.map((c) => c * l), radius: torch.radius, range: torch.range };
}

const MODULE = 'passes/path-trace';
/** Must match @workgroup_size of path_trace. */
const WORKGROUP = 8;

export interface Tile {
  readonly x: number;
  readonly y: number;
  readonly width: number;
  readonly height: number;
}

export interface PathTraceDispatch {
  readonly tile: Tile;
  /** Index of the first sample of this dispatch (seeds the random streams). */
  readonly sampleIndex: number;
  readonly samples: number;
  readonly maxBounces: number;
  readonly seed: number;
  readonly lightSampling: LightSampling;
  /** The torch at the camera, if any. */
  readonly torch?: Torch;
}

/** The buffers the path tracer writes. */
export interface PathTraceTarget {
  /** vec4f per pixel: Σ radiance, Σ luminance². */
  readonly accumulation: GPUBuffer;
  /** Four u32: extension rays (lo, hi), shadow rays (lo, hi). */
  readonly rayCounters: GPUBuffer;
}

export class PathTracePass {
  private readonly sceneGroups = new WeakMap<SceneResources, GPUBindGroup>();
  private readonly viewGroups = new WeakMap<ViewUniform, GPUBindGroup>();
  private readonly targetGroups = new WeakMap<GPUBuffer, GPUBindGroup>();

  private constructor(
    private readonly kernel: ComputeKernel,
    private readonly params: UniformParams<UniformValues>,
  ) {}

  static async create(device: GPUDevice): Promise<PathTracePass> {
    const kernel = await ComputeKernel.create(device, { module: MODULE, entryPoint: 'path_trace' });
    return new PathTracePass(kernel, new UniformParams(device, MODULE));
  }

  /** Writes the parameters now (queue.writeBuffer): submit before encoding the next dispatch. */
  encode(encoder: GPUCommandEncoder, scene: SceneResources, view: ViewUniform, target: PathTraceTarget, d: PathTraceDispatch, timer?: GpuTimer): void {
    this.params.write({
      tile_origin: [d.tile.x, d.tile.y],
      tile_size: [d.tile.width, d.tile.height],
      sample_index: d.sampleIndex >>> 0,
      samples: d.samples,
      max_bounces: d.maxBounces,
      seed: d.seed >>> 0,
      light_sampling: LIGHT_SAMPLING.indexOf(d.lightSampling),
      torch: torchUniform(d.torch),
    });
    const pass = encoder.beginComputePass({ label: 'path trace', ...(timer ? { timestampWrites: timer.timestampWrites('path trace') } : {}) });
    this.kernel.dispatch(
      pass,
      { 0: this.sceneGroup(scene), 1: this.viewGroup(view), 2: this.targetGroup(target) },
      Math.ceil(d.tile.width / WORKGROUP),
      Math.ceil(d.tile.height / WORKGROUP),
    );
    pass.end();
  }

  destroy(): void {
    this.params.destroy();
  }

  private sceneGroup(scene: SceneResources): GPUBindGroup {
    let g = this.sceneGroups.get(scene);
    if (!g) this.sceneGroups.set(scene, (g = this.kernel.bindGroup(0, scene.bindings)));
    return g;
  }

  private viewGroup(view: ViewUniform): GPUBindGroup {
    let g = this.viewGroups.get(view);
    if (!g) this.viewGroups.set(view, (g = this.kernel.bindGroup(1, { view: view.buffer })));
    return g;
  }

  private targetGroup(target: PathTraceTarget): GPUBindGroup {
    let g = this.targetGroups.get(target.accumulation);
    if (!g) {
      g = this.kernel.bindGroup(2, { params: this.params.buffer, accumulation: target.accumulation, ray_counters: target.rayCounters });
      this.targetGroups.set(target.accumulation, g);
    }
    return g;
  }
}
