/**
 * Compute kernels built from reflection: link a WGSL module, compile it (compiler messages point at
 * module and line), derive one bind group layout per group from the resources the entry point uses,
 * and create bind groups from resources given by their WGSL variable names.
 */
import { LanternError } from '../errors.ts';
import { sourceLocation, type LinkedShader } from './wgsl/linker.ts';
import { entryPointBindings, reflectModule, type BindingSlot, type ReflectedShader } from './wgsl/reflect.ts';

export type NamedResource = GPUBuffer | GPUTextureView | GPUSampler | GPUBufferBinding;

const isBuffer = (r: NamedResource): r is GPUBuffer => typeof (r as GPUBuffer).mapAsync === 'function';

/** Compiles a linked shader, throwing a LanternError that points every error at its module and line. */
export async function compileShader(device: GPUDevice, linked: LinkedShader): Promise<GPUShaderModule> {
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
  /** Values of WGSL `override` constants. */
  readonly constants?: Record<string, number>;
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
    const shader = typeof options.module === 'string' ? reflectModule(options.module) : options.module;
    const label = `${shader.linked.entry}:${options.entryPoint}`;
    const slots = entryPointBindings(shader, [options.entryPoint], GPUShaderStage.COMPUTE);
    const module = await cachedModule(device, shader);
    const layouts = createBindGroupLayouts(device, label, slots);
    const layout = device.createPipelineLayout({ label, bindGroupLayouts: layouts });
    let pipeline: GPUComputePipeline;
    try {
      pipeline = await device.createComputePipelineAsync({
        label,
        layout,
        compute: { module, entryPoint: options.entryPoint, ...(options.constants ? { constants: options.constants } : {}) },
      });
    } catch (e) {
      throw new LanternError(`could not create the compute pipeline ${label}: ${(e as Error).message}`, undefined, { cause: e });
    }
    return new ComputeKernel(device, label, layouts, slots, pipeline);
  }

  /** Records a dispatch. `groups` maps group index to bind group; groups with no bindings get an empty one. */
  dispatch(pass: GPUComputePassEncoder, groups: Readonly<Record<number, GPUBindGroup>>, x: number, y = 1, z = 1): void {
    pass.setPipeline(this.pipeline);
    for (let g = 0; g < this.layouts.length; g++) {
      const given = groups[g];
      if (given) pass.setBindGroup(g, given);
      else if (this.namesIn(g).length === 0) pass.setBindGroup(g, this.emptyGroup(g));
      else throw new Error(`${this.label}: bind group ${g} (${this.namesIn(g).join(', ')}) was not given`);
    }
    pass.dispatchWorkgroups(x, y, z);
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

/** The traversal variant a scene needs: alpha masks compiled in only where it has masked triangles. */
export type TraversalVariant = 'masked' | 'opaque';
export const TRAVERSAL_VARIANTS: Record<TraversalVariant, Record<string, number>> = {
  masked: { SCENE_HAS_ALPHA_MASKS: 1 },
  opaque: { SCENE_HAS_ALPHA_MASKS: 0 },
};
export const traversalVariant = (maskedTriangles: number): TraversalVariant => (maskedTriangles > 0 ? 'masked' : 'opaque');
