/** The path tracer dispatch (shaders/passes/path-trace.wgsl): adds samples to the accumulation buffer. */
import { pixelGroups, spectralConstants } from '../gpu/kernel-variants.ts';
import { reflectKernel, SceneKernels, TRACING_FEATURES, type ComputeKernel, type NamedResource } from '../gpu/kernel.ts';
import type { SceneFeatures } from '../gpu/pack/scene-pack.ts';
import type { SceneResources } from '../gpu/scene-resources.ts';
import { compileSpecialised, type SceneSpecialisation, type SpecialisedKernel } from '../gpu/specialisation.ts';
import type { GpuTimer } from '../gpu/timestamps.ts';
import type { ViewUniform } from '../gpu/view.ts';
import { LIGHT_SAMPLING, resolveSampler, SAMPLERS, type LightSampling, type Sampler } from './variants.ts';
import type { Torch } from '../scene/types.ts';
import type { Pass, PassFrame } from './pass.ts';
import { UniformParams, type UniformValues } from './uniform-params.ts';

/** shaders/scene/torch.wgsl TorchLight: surface radiance I / (π r²) gives intensity I far away. */
function torchUniform(torch: Torch | undefined): { radiance: number[]; radius: number; range: number } {
  if (!torch) return { radiance: [0, 0, 0], radius: 1, range: 1 };
  const l = torch.intensity / (Math.PI * torch.radius * torch.radius);
  return { radiance: torch.color.map((c) => c * l), radius: torch.radius, range: torch.range };
}

/** The `params` uniform of passes/path-trace for one dispatch (shared with the real-time frame kernel). */
export function pathTraceParams(d: PathTraceDispatch): UniformValues {
  return {
    tile_origin: [d.tile.x, d.tile.y],
    tile_size: [d.tile.width, d.tile.height],
    sample_index: d.sampleIndex >>> 0,
    samples: d.samples,
    max_bounces: d.maxBounces,
    seed: d.seed >>> 0,
    light_sampling: LIGHT_SAMPLING.indexOf(d.lightSampling),
    sampler: SAMPLERS.indexOf(d.sampler),
    torch: torchUniform(d.torch),
  };
}

export const PATH_TRACE_MODULE = 'passes/path-trace';
/** The progressive path tracer's entry point in PATH_TRACE_MODULE. */
export const PATH_TRACE_ENTRY = 'path_trace';
const MODULE = PATH_TRACE_MODULE;

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
  /** Where the random numbers come from (settings.sampler). */
  readonly sampler: Sampler;
  /** The torch at the camera, if any. */
  readonly torch?: Torch;
  /** Trace four wavelengths per path (the SPECTRAL variant of lib/spectrum.wgsl; prepare it first). */
  readonly spectral?: boolean;
}

/** The buffers the path tracer writes. */
export interface PathTraceTarget {
  /** vec4f per pixel: Σ radiance, Σ luminance². */
  readonly accumulation: GPUBuffer;
  /** Four u32: extension rays (lo, hi), shadow rays (lo, hi). */
  readonly rayCounters: GPUBuffer;
}

/** What one progressive dispatch is given (one band, or the whole image). */
export interface PathTracePassFrame extends PassFrame {
  readonly scene: SceneResources;
  readonly view: ViewUniform;
  readonly target: PathTraceTarget;
  readonly dispatch: PathTraceDispatch;
}

/**
 * The scene variants of a tracing entry point (shaders/passes/path-trace or an entry point that
 * imports it) with their bind groups cached per kernel and resource: each pipeline has its own
 * layouts. Group 0 is the scene, 1 the view, 2 the pass's own, keyed by one of its buffers.
 * Spectral mode is a second set of the same variants compiled with SPECTRAL (lib/spectrum.wgsl),
 * made only once something prepares it, so RGB rendering neither compiles nor runs any of it.
 * An entry point created with a sampler is compiled for it (lib/random.wgsl SAMPLER): its kernels
 * hold that sampler's code alone; useSampler compiles another's.
 */
export class TracingKernels {
  /** The variant sets by mode (RGB or spectral) and sampler. */
  private readonly sets = new Map<string, SceneKernels>();
  private readonly sceneGroups = new WeakMap<ComputeKernel, WeakMap<SceneResources, GPUBindGroup>>();
  private readonly viewGroups = new WeakMap<ComputeKernel, WeakMap<ViewUniform, GPUBindGroup>>();
  private readonly targetGroups = new WeakMap<ComputeKernel, WeakMap<object, GPUBindGroup>>();

  /** The kernel specialised to one uploaded scene, used instead of the generic variants while set. */
  private active?: { readonly scene: SceneResources; readonly kernel: ComputeKernel };
  /** The sampler before the last useSampler: its kernels trace until the new ones are compiled. */
  private previousSampler?: Sampler;

  private constructor(
    private readonly device: GPUDevice,
    kernels: SceneKernels,
    private readonly base: { readonly module: string; readonly entryPoint: string },
    private readonly extraConstants: Record<string, number>,
    private samplerValue: Sampler | undefined,
  ) {
    this.sets.set(setKey(false, samplerValue), kernels);
  }

  /**
   * `first`: the features of the scene to compile for at once (SceneKernels.create; default a plain
   * scene's). `sampler`: compile for that sampler (the entry point draws its streams by sampler_seed);
   * without it, each stream chooses at run time.
   */
  static async create(device: GPUDevice, module: string, entryPoint: string, extraConstants: Record<string, number> = {}, first?: SceneFeatures, sampler?: Sampler): Promise<TracingKernels> {
    const base = { module, entryPoint };
    const kernels = await SceneKernels.create(device, base, TRACING_FEATURES, withSampler(extraConstants, sampler), first);
    return new TracingKernels(device, kernels, base, extraConstants, sampler);
  }

  /** The sampler these kernels are compiled for (undefined: chosen per stream). */
  get sampler(): Sampler | undefined {
    return this.samplerValue;
  }

  /**
   * Compiles the variants ready so far for `sampler` and traces with them from now on; until they
   * are ready, dispatches run the previous sampler's (an unbiased estimate too, but not the one
   * asked for: await this before rendering for that sampler's alone).
   */
  async useSampler(sampler: Sampler): Promise<void> {
    if (this.samplerValue === undefined) throw new Error(`${this.base.entryPoint}: created without a sampler, it cannot switch samplers`);
    if (sampler === this.samplerValue) return;
    const ready = [false, true].flatMap((spectral) => (this.sets.get(setKey(spectral, this.samplerValue))?.preparedFeatures() ?? []).map((f) => ({ f, spectral })));
    this.previousSampler = this.samplerValue;
    this.samplerValue = sampler;
    await Promise.all(ready.map(({ f, spectral }) => this.variants(spectral).prepare(f)));
  }

  /** Compiles this entry point specialised to a frozen scene (gpu/specialisation.ts), asynchronously; it is not used until useSpecialised. */
  compileSpecialised(s: SceneSpecialisation): Promise<SpecialisedKernel> {
    return compileSpecialised(this.device, this.base, s, withSampler(this.extraConstants, this.samplerValue));
  }

  /** Dispatches over `scene` use `kernel` from now on; undefined goes back to the generic variants. */
  useSpecialised(active?: { readonly scene: SceneResources; readonly kernel: ComputeKernel }): void {
    this.active = active;
  }

  /** Whether dispatches over `scene` run a specialised kernel. */
  isSpecialised(scene: SceneResources): boolean {
    return this.active?.scene === scene;
  }

  /** Compiles the variant a scene with these features needs (Renderer.setScene awaits it), in RGB or spectral mode. */
  prepare(features: SceneFeatures, spectral = false): Promise<void> {
    return this.variants(spectral).prepare(features);
  }

  private variants(spectral: boolean, sampler = this.samplerValue): SceneKernels {
    const key = setKey(spectral, sampler);
    let set = this.sets.get(key);
    if (!set) this.sets.set(key, (set = new SceneKernels(this.device, this.base, TRACING_FEATURES, withSampler({ ...this.extraConstants, ...spectralConstants(spectral) }, sampler))));
    return set;
  }

  /** The generic kernel for these features: the current sampler's, or while it compiles the previous one's. */
  private generic(features: SceneFeatures, spectral: boolean): ComputeKernel {
    const fallback = this.previousSampler !== undefined ? this.sets.get(setKey(spectral, this.previousSampler)) : undefined;
    const current = this.variants(spectral);
    return !current.has(features) && fallback?.has(features) ? fallback.get(features) : current.get(features);
  }

  /** Records one dispatch over `tile` as a compute pass named `label`; group 2 is made once per `targetKey` from `targets`. */
  dispatch(encoder: GPUCommandEncoder, label: string, scene: SceneResources, view: ViewUniform, targetKey: object, targets: () => Record<string, NamedResource>, tile: Tile, spectral: boolean, timer?: GpuTimer): void {
    // Specialised kernels are compiled in RGB: spectral dispatches use the generic spectral variants.
    const kernel = !spectral && this.active?.scene === scene ? this.active.kernel : this.generic(scene.features, spectral);
    const pass = encoder.beginComputePass({ label, ...(timer ? { timestampWrites: timer.timestampWrites(label) } : {}) });
    kernel.dispatch(
      pass,
      {
        0: cached(this.sceneGroups, kernel, scene, () => kernel.bindGroup(0, scene.bindings)),
        1: cached(this.viewGroups, kernel, view, () => kernel.bindGroup(1, { view: view.buffer })),
        2: cached(this.targetGroups, kernel, targetKey, () => kernel.bindGroup(2, targets())),
      },
      ...pixelGroups(tile.width, tile.height),
    );
    pass.end();
  }
}

const setKey = (spectral: boolean, sampler: Sampler | undefined) => `${spectral ? 'spectral' : 'rgb'}/${sampler ?? 'per-stream'}`;

/** The constants with lib/random.wgsl's SAMPLER set for `sampler` (none without one). */
function withSampler(constants: Record<string, number>, sampler: Sampler | undefined): Record<string, number> {
  return sampler === undefined ? constants : { ...constants, SAMPLER: SAMPLERS.indexOf(sampler) };
}

export class PathTracePass implements Pass<PathTracePassFrame> {
  private constructor(
    /** Its kernels: the generic variants and, once the renderer specialises, the scene's own. */
    readonly kernels: TracingKernels,
    private readonly params: UniformParams<UniformValues>,
  ) {}

  /**
   * `first`: the features of the scene about to be rendered, if known (its variant is compiled instead
   * of a plain scene's), or a promise of them: the module is reflected while it is pending. `sampler`:
   * the one to compile for (default the one progressive renders use by default).
   */
  static async create(device: GPUDevice, first?: SceneFeatures | Promise<SceneFeatures>, sampler: Sampler = resolveSampler('auto', 'progressive')): Promise<PathTracePass> {
    reflectKernel(device, MODULE);
    const params = new UniformParams(device, MODULE);
    try {
      // The renderer switches the sampler later if the settings ask for another.
      return new PathTracePass(await TracingKernels.create(device, MODULE, PATH_TRACE_ENTRY, {}, await first, sampler), params);
    } catch (e) {
      params.destroy();
      throw e;
    }
  }

  prepare(features: SceneFeatures, spectral = false): Promise<void> {
    return this.kernels.prepare(features, spectral);
  }

  /** Writes the parameters now (queue.writeBuffer): submit before encoding the next dispatch. */
  encode(encoder: GPUCommandEncoder, { scene, view, target, dispatch: d, timer }: PathTracePassFrame): void {
    this.params.write(pathTraceParams(d));
    const targets = () => ({ params: this.params.buffer, accumulation: target.accumulation, ray_counters: target.rayCounters });
    this.kernels.dispatch(encoder, d.spectral ? 'path trace (spectral)' : 'path trace', scene, view, target.accumulation, targets, d.tile, d.spectral ?? false, timer);
  }

  destroy(): void {
    this.params.destroy();
  }
}

/** A bind group cached per kernel and resource (both weakly held). */
export function cached<K extends object>(cache: WeakMap<ComputeKernel, WeakMap<K, GPUBindGroup>>, kernel: ComputeKernel, key: K, make: () => GPUBindGroup): GPUBindGroup {
  let perKernel = cache.get(kernel);
  if (!perKernel) cache.set(kernel, (perKernel = new WeakMap()));
  let group = perKernel.get(key);
  if (!group) perKernel.set(key, (group = make()));
  return group;
}
