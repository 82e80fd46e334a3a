/**
 * Compute kernels built from reflection: link a WGSL module, compile it (compiler messages point at
 * module and line), derive one bind group layout per group from the resources the entry point uses,
 * and create bind groups from resources given by their WGSL variable names.
 */
import { LanternError } from '../errors.ts';
import type { SceneFeatures } from './pack/scene-pack.ts';
import { featureConstants, featureKey, workgroupConstants } from './kernel-variants.ts';
import { compileComputePipeline } from './pipeline-compiles.ts';
import { reportStage, timedStage } from './stage-log.ts';
import { sourceLocation, type LinkedShader } from './wgsl/linker.ts';
import { bindingsKnown, entryPointBindings, isReflected, reflectModule, type BindingSlot, type ReflectedShader } from './wgsl/reflect.ts';

/**
 * Does the CPU part of making kernels of `module` ahead of time (linking and reflection, cached),
 * e.g. while the scene whose variant is wanted still loads; reported to the device's stage log. In a
 * bundle that is reading the reflection the build made; from sources, parsing the module's layouts.
 */
export function reflectKernel(device: GPUDevice, module: string): void {
  const t0 = performance.now();
  if (isReflected(module)) return;
  const shader = reflectModule(module);
  void shader.defs; // live: the layouts are parsed now, inside this stage
  reportStage(device, { stage: `reflect ${module}`, startMs: t0, endMs: performance.now(), detail: shader.source });
}

export type NamedResource = GPUBuffer | GPUTextureView | GPUSampler | GPUBufferBinding;

const isBuffer = (r: NamedResource): r is GPUBuffer => typeof (r as GPUBuffer).mapAsync === 'function';

/** Compiles a linked shader, throwing a LanternError that points every error at its module and line. */
export function compileShader(device: GPUDevice, linked: LinkedShader): Promise<GPUShaderModule> {
  return timedStage(device, `shader ${linked.entry}`, () => compileModule(device, linked));
}

async function compileModule(device: GPUDevice, linked: LinkedShader): Promise<GPUShaderModule> {
  const module = device.createShaderModule({ label: linked.entry, code: linked.code });
  const info = await module.getCompilationInfo();
  const errors = info.messages.filter((m) => m.type === 'error');
  if (errors.length > 0) {
    const lines = errors.map((m) => `${sourceLocation(linked, m.lineNum)}:${m.linePos}: ${m.message}`);
    throw new LanternError(`WGSL compilation of '${linked.entry}' failed:\n  ${lines.join('\n  ')}`);
  }
  return module;
}

const moduleCache = new WeakMap<GPUDevice, Map<string, Promise<GPUShaderModule>>>();

function cachedModule(device: GPUDevice, shader: ReflectedShader): Promise<GPUShaderModule> {
  let perDevice = moduleCache.get(device);
  if (!perDevice) moduleCache.set(device, (perDevice = new Map()));
  let module = perDevice.get(shader.linked.code);
  if (!module) {
    module = compileShader(device, shader.linked);
    perDevice.set(shader.linked.code, module);
  }
  return module;
}

/** Bind group layouts, one per group index up to the highest one used (unused groups are empty). */
export function createBindGroupLayouts(device: GPUDevice, label: string, slots: BindingSlot[][]): GPUBindGroupLayout[] {
  return slots.map((group, g) =>
    device.createBindGroupLayout({ label: `${label} group ${g}`, entries: group.map((s) => s.entry) }),
  );
}

/** Creates bind groups for a set of reflected binding slots from resources named as in WGSL. */
export class BindGroupFactory {
  constructor(
    protected readonly device: GPUDevice,
    readonly label: string,
    readonly layouts: readonly GPUBindGroupLayout[],
    readonly slots: readonly (readonly BindingSlot[])[],
  ) {}

  /** Names the entry point needs in `group` (the resources map may hold more). */
  namesIn(group: number): string[] {
    return (this.slots[group] ?? []).map((s) => s.name);
  }

  bindGroup(group: number, resources: Readonly<Record<string, NamedResource>>, label?: string): GPUBindGroup {
    const layout = this.layouts[group];
    if (!layout) throw new Error(`${this.label} has no bind group ${group}`);
    const entries: GPUBindGroupEntry[] = (this.slots[group] ?? []).map((slot) => {
      const r = resources[slot.name];
      if (!r) {
        throw new Error(`${this.label}: no resource named '${slot.name}' for group ${group} (given: ${Object.keys(resources).join(', ')})`);
      }
      return { binding: slot.entry.binding, resource: isBuffer(r) ? { buffer: r } : r };
    });
    return this.device.createBindGroup({ label: label ?? `${this.label} group ${group}`, layout, entries });
  }
}

export interface KernelOptions {
  /** A module of src/shaders ("passes/path-trace") or an already reflected shader (tests). */
  readonly module: string | ReflectedShader;
  readonly entryPoint: string;
  /** Values of WGSL `override` constants (the workgroup sizes of lib/workgroup are added: gpu/kernel-variants.ts WORKGROUP). */
  readonly constants?: Record<string, number>;
  /** Keep the shader module for later kernels of the same code (default); specialised kernels, made once per scene, do not. */
  readonly cacheModule?: boolean;
}

export class ComputeKernel extends BindGroupFactory {
  private readonly emptyGroups = new Map<number, GPUBindGroup>();

  private constructor(
    device: GPUDevice,
    label: string,
    layouts: GPUBindGroupLayout[],
    slots: BindingSlot[][],
    readonly pipeline: GPUComputePipeline,
  ) {
    super(device, label, layouts, slots);
  }

  static async create(device: GPUDevice, options: KernelOptions): Promise<ComputeKernel> {
    const reflectStart = performance.now();
    const first = typeof options.module === 'string' && !isReflected(options.module);
    const shader = typeof options.module === 'string' ? reflectModule(options.module) : options.module;
    if (first) reportStage(device, { stage: `reflect ${shader.linked.entry}`, startMs: reflectStart, endMs: performance.now(), detail: shader.source });
    const label = `${shader.linked.entry}:${options.entryPoint}`;
    const parse = !bindingsKnown(shader, [options.entryPoint]);
    const bindingsStart = performance.now();
    const slots = entryPointBindings(shader, [options.entryPoint], GPUShaderStage.COMPUTE);
    if (parse) reportStage(device, { stage: `bindings ${label}`, startMs: bindingsStart, endMs: performance.now() });
    const module = await (options.cacheModule === false ? compileShader(device, shader.linked) : cachedModule(device, shader));
    const layouts = createBindGroupLayouts(device, label, slots);
    const layout = device.createPipelineLayout({ label, bindGroupLayouts: layouts });
    let pipeline: GPUComputePipeline;
    try {
      pipeline = await compileComputePipeline(device, { label, layout, compute: { module, entryPoint: options.entryPoint, constants: { ...workgroupConstants(shader.linked.modules), ...options.constants } } });
    } catch (e) {
      throw new LanternError(`could not create the compute pipeline ${label}: ${(e as Error).message}`, undefined, { cause: e });
    }
    return new ComputeKernel(device, label, layouts, slots, pipeline);
  }

  /** Records a dispatch. `groups` maps group index to bind group; groups with no bindings get an empty one. */
  dispatch(pass: GPUComputePassEncoder, groups: Readonly<Record<number, GPUBindGroup>>, x: number, y = 1, z = 1): void {
    this.bind(pass, groups);
    pass.dispatchWorkgroups(x, y, z);
  }

  /** Records a dispatch whose workgroup counts are three u32 at `offset` of `args` (written by an earlier dispatch). */
  dispatchIndirect(pass: GPUComputePassEncoder, groups: Readonly<Record<number, GPUBindGroup>>, args: GPUBuffer, offset: number): void {
    this.bind(pass, groups);
    pass.dispatchWorkgroupsIndirect(args, offset);
  }

  private bind(pass: GPUComputePassEncoder, groups: Readonly<Record<number, GPUBindGroup>>): void {
    pass.setPipeline(this.pipeline);
    for (let g = 0; g < this.layouts.length; g++) {
      const given = groups[g];
      if (given) pass.setBindGroup(g, given);
      else if (this.namesIn(g).length === 0) pass.setBindGroup(g, this.emptyGroup(g));
      else throw new Error(`${this.label}: bind group ${g} (${this.namesIn(g).join(', ')}) was not given`);
    }
  }

  private emptyGroup(g: number): GPUBindGroup {
    let bg = this.emptyGroups.get(g);
    if (!bg) {
      bg = this.device.createBindGroup({ label: `${this.label} empty group ${g}`, layout: this.layouts[g]!, entries: [] });
      this.emptyGroups.set(g, bg);
    }
    return bg;
  }
}

/**
 * The variants of one entry point compiled with different `override` constants, created up front so
 * that choosing one while encoding is synchronous. Keys are caller-chosen names.
 */
export class KernelVariants<K extends string> {
  private constructor(private readonly kernels: ReadonlyMap<K, ComputeKernel>) {}

  static async create<K extends string>(device: GPUDevice, base: Omit<KernelOptions, 'constants'>, variants: Record<K, Record<string, number>>): Promise<KernelVariants<K>> {
    const entries = await Promise.all(
      (Object.entries(variants) as [K, Record<string, number>][]).map(async ([key, constants]) => [key, await ComputeKernel.create(device, { ...base, constants })] as const),
    );
    return new KernelVariants(new Map(entries));
  }

  get(key: K): ComputeKernel {
    return this.kernels.get(key)!;
  }
}

/**
 * The variants of one entry point for the scenes it meets, compiled when a scene first needs one
 * (prepare, awaited by Renderer.setScene) so that choosing one while encoding stays synchronous.
 * `features` names the scene features the entry point's modules declare overrides for.
 */
export class SceneKernels {
  private readonly ready = new Map<string, ComputeKernel>();
  private readonly pending = new Map<string, Promise<ComputeKernel>>();
  /** The features each variant was asked for, by key (preparedFeatures). */
  private readonly asked = new Map<string, SceneFeatures>();

  constructor(
    private readonly device: GPUDevice,
    private readonly base: Omit<KernelOptions, 'constants'>,
    private readonly features: readonly (keyof SceneFeatures)[],
    private readonly extraConstants: Record<string, number> = {},
  ) {}

  /**
   * Creates the set and compiles the variant of a plain scene (diffuse, opaque, no lights but
   * emitters, a BVH shallow enough for the short stack: the Cornell box), so errors surface at once. With `first`, the features of the scene about to be
   * rendered, that variant alone starts compiling instead and the set is returned at once: the
   * scene's prepare() awaits it and reports its errors; no plain variant is compiled for nothing.
   */
  static async create(device: GPUDevice, base: Omit<KernelOptions, 'constants'>, features: readonly (keyof SceneFeatures)[], extraConstants: Record<string, number> = {}, first?: SceneFeatures): Promise<SceneKernels> {
    const kernels = new SceneKernels(device, base, features, extraConstants);
    if (first) kernels.prepare(first).catch(() => undefined); // prepare(first) again reports a failure
    else await kernels.prepare(PLAIN_SCENE);
    return kernels;
  }

  private key(f: SceneFeatures): string {
    return featureKey(this.features, f);
  }

  /** Compiles the variant `f` needs, once. */
  async prepare(f: SceneFeatures): Promise<void> {
    const key = this.key(f);
    if (this.ready.has(key)) return;
    this.asked.set(key, f);
    let pending = this.pending.get(key);
    if (!pending) {
      const constants: Record<string, number> = { ...this.extraConstants, ...featureConstants(this.features, f) };
      pending = ComputeKernel.create(this.device, { ...this.base, constants });
      this.pending.set(key, pending);
    }
    this.ready.set(key, await pending);
  }

  /** Whether the variant `f` needs is compiled. */
  has(f: SceneFeatures): boolean {
    return this.ready.has(this.key(f));
  }

  /** The features of every variant asked for so far (compiled or compiling). */
  preparedFeatures(): SceneFeatures[] {
    return [...this.asked.values()];
  }

  get(f: SceneFeatures): ComputeKernel {
    const kernel = this.ready.get(this.key(f));
    if (!kernel) throw new Error(`${this.base.entryPoint}: no pipeline compiled for scene features ${JSON.stringify(f)} (prepare() first)`);
    return kernel;
  }
}

/**
 * What a renderer told no features compiles for. Its BVH takes the short stack, as nearly every scene's
 * does (at most SHALLOW_STACK_ENTRIES deep, no moving instances: the Cornell box, the viewer's first
 * scene): with the deep stack here, a renderer made without features compiled every kernel's deep
 * variant and then the small scene's (the ReSTIR test: 8 of its 20 pipelines for nothing).
 */
export const PLAIN_SCENE: SceneFeatures = Object.freeze({ alphaMasks: false, generalMaterials: false, punctualLights: false, environment: false, analyticPrimitives: false, instances: false, staticAccel: 'bvh2', shallowStack: true });
/** The features every path-tracing entry point compiles by. */
export const TRACING_FEATURES: readonly (keyof SceneFeatures)[] = ['alphaMasks', 'generalMaterials', 'punctualLights', 'environment', 'analyticPrimitives', 'instances', 'staticAccel', 'shallowStack'];
/** The features of passes that only trace (debug views, ray buffers). */
export const TRAVERSAL_FEATURES: readonly (keyof SceneFeatures)[] = ['alphaMasks', 'analyticPrimitives', 'instances', 'staticAccel', 'shallowStack'];
