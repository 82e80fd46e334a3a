/**
 * Reads GPU layouts out of WGSL so the host never writes a byte offset, a stride, a padding field or
 * a binding number by hand. Built on webgpu-utils' reflection (makeShaderDataDefinitions, which parses
 * WGSL with wgsl_reflect). Pure CPU: packing code and unit tests use it without a device.
 */
import { makeShaderDataDefinitions, type ShaderDataDefinitions, type TypeDefinition } from 'webgpu-utils';
import { ResourceType, WgslReflect, type VariableInfo } from 'wgsl_reflect/wgsl_reflect.module.js';
import { LanternError } from '../../errors.ts';
import { linkWgsl, type LinkedShader } from './linker.ts';

// webgpu-utils reads GPUShaderStage while reflecting. Browsers and Dawn define it; plain Node (unit
// tests, packing in a worker without WebGPU) does not. These are the spec's constant values.
(globalThis as { GPUShaderStage?: unknown }).GPUShaderStage ??= { VERTEX: 1, FRAGMENT: 2, COMPUTE: 4 };

/** A WGSL struct field: byte offset within the struct and its WGSL type ("vec3f", "u32", ...). */
export interface FieldLayout {
  readonly offset: number;
  readonly type: string;
  readonly size: number;
}

/** Spellings webgpu-utils may report, normalised to the short WGSL aliases. */
const TYPE_ALIASES: Record<string, string> = {
  'vec2<f32>': 'vec2f', 'vec3<f32>': 'vec3f', 'vec4<f32>': 'vec4f',
  'vec2<u32>': 'vec2u', 'vec3<u32>': 'vec3u', 'vec4<u32>': 'vec4u',
  'vec2<i32>': 'vec2i', 'vec3<i32>': 'vec3i', 'vec4<i32>': 'vec4i',
  'atomic<u32>': 'u32', 'atomic<i32>': 'i32',
};

function typeName(type: TypeDefinition): string {
  const t = (type as { type?: string }).type;
  if (typeof t === 'string') return TYPE_ALIASES[t] ?? t;
  if ('fields' in type) return 'struct';
  if ('elementType' in type) return 'array';
  return 'unknown';
}

/** The layout of one WGSL struct, as the GPU sees it. */
export class StructLayout {
  constructor(
    readonly name: string,
    /** Bytes per element in an array of this struct (WGSL's roundUp(align, size)). */
    readonly stride: number,
    readonly fields: ReadonlyMap<string, FieldLayout>,
  ) {}

  /** Elements of 4 bytes per array element: the stride in Float32Array/Uint32Array units. */
  get strideWords(): number {
    return this.stride / 4;
  }

  field(name: string, expectedType?: string): FieldLayout {
    const f = this.fields.get(name);
    if (!f) throw new Error(`WGSL struct ${this.name} has no field '${name}' (fields: ${[...this.fields.keys()].join(', ')})`);
    if (expectedType !== undefined && f.type !== expectedType) {
      throw new Error(`WGSL struct ${this.name}.${name} is ${f.type}, the host expects ${expectedType}`);
    }
    return f;
  }

  /** Offset of a field in 4-byte words, for writing through Float32Array/Uint32Array views. */
  word(name: string, expectedType?: string): number {
    return this.field(name, expectedType).offset / 4;
  }
}

export function structLayout(defs: ShaderDataDefinitions, name: string): StructLayout {
  const s = defs.structs[name];
  if (!s) throw new Error(`WGSL struct '${name}' not found (structs: ${Object.keys(defs.structs).join(', ')})`);
  const fields = new Map<string, FieldLayout>();
  for (const [fieldName, f] of Object.entries(s.fields)) {
    fields.set(fieldName, { offset: f.offset, type: typeName(f.type), size: f.type.size });
  }
  // An array element's stride is the struct size rounded up to its alignment; wgsl_reflect's `size`
  // already includes that rounding (checked by the GPU layout round-trip test).
  return new StructLayout(name, s.size, fields);
}

/** A linked shader with its reflection, independent of any device. */
export interface ReflectedShader {
  readonly linked: LinkedShader;
  readonly defs: ShaderDataDefinitions;
}

const reflectedCache = new Map<string, ReflectedShader>();

/** Whether reflectModule(entry) has been done already (start-up timelines report the first, costly one). */
export const isReflected = (entry: string): boolean => reflectedCache.has(entry);

/** Links and reflects a module of src/shaders once per process. */
export function reflectModule(entry: string): ReflectedShader {
  let r = reflectedCache.get(entry);
  if (!r) {
    r = reflectLinked(linkWgsl(entry));
    reflectedCache.set(entry, r);
  }
  return r;
}

export function reflectLinked(linked: LinkedShader): ReflectedShader {
  try {
    return { linked, defs: makeShaderDataDefinitions(linked.code) };
  } catch (e) {
    throw new LanternError(`could not reflect WGSL module '${linked.entry}': ${(e as Error).message}`, undefined, { cause: e });
  }
}

/** A resource an entry point uses: its WGSL variable name and where it is bound. */
export interface BindingSlot {
  readonly name: string;
  readonly group: number;
  readonly entry: GPUBindGroupLayoutEntry;
}

/**
 * wgsl_reflect's parse of a linked module, made once: the path tracer takes most of a second to
 * parse, and each of its pipeline variants asks for its bindings.
 */
const parsed = new WeakMap<LinkedShader, WgslReflect>();
function parsedModule(linked: LinkedShader): WgslReflect {
  let reflect = parsed.get(linked);
  if (!reflect) parsed.set(linked, (reflect = new WgslReflect(linked.code)));
  return reflect;
}

/**
 * Bindings worked out elsewhere from the same code (the CLI parses the path tracer on another
 * thread while this one does other work), by module, code length, entry points and visibility.
 */
const provided = new Map<string, BindingSlot[][]>();
const bindingsKey = (module: string, codeLength: number, entryPoints: readonly string[], visibility: GPUShaderStageFlags) => `${module}|${codeLength}|${entryPoints.join(',')}|${visibility}`;

/** Whether entryPointBindings would answer without parsing (start-up timelines report the parse). */
export function bindingsKnown(shader: Pick<ReflectedShader, 'linked'>, entryPoints: readonly string[], visibility: GPUShaderStageFlags): boolean {
  return parsed.has(shader.linked) || provided.has(bindingsKey(shader.linked.entry, shader.linked.code.length, entryPoints, visibility));
}

/** Hands entryPointBindings a result worked out elsewhere from a module's code (`codeLength` long), so that it need not parse it here. */
export function provideEntryPointBindings(module: string, codeLength: number, entryPoints: readonly string[], visibility: GPUShaderStageFlags, slots: BindingSlot[][]): void {
  provided.set(bindingsKey(module, codeLength, entryPoints, visibility), slots);
}

const TEXTURE_SAMPLE_TYPES: Record<string, GPUTextureSampleType> = { f32: 'float', u32: 'uint', i32: 'sint' };
const STORAGE_TEXTURE_ACCESS: Record<string, GPUStorageTextureAccess> = { write: 'write-only', read: 'read-only', read_write: 'read-write' };

function layoutEntry(v: VariableInfo, visibility: GPUShaderStageFlags): GPUBindGroupLayoutEntry {
  const base = { binding: v.binding, visibility };
  const typeName = v.type.name;
  switch (v.resourceType) {
    case ResourceType.Uniform:
      return { ...base, buffer: { type: 'uniform' } };
    case ResourceType.Storage:
      return { ...base, buffer: { type: v.access === 'read' ? 'read-only-storage' : 'storage' } };
    case ResourceType.StorageTexture: {
      const t = v.type as { format?: { name: string } | null; access?: string };
      return {
        ...base,
        storageTexture: {
          access: STORAGE_TEXTURE_ACCESS[t.access ?? 'write'] ?? 'write-only',
          format: t.format!.name as GPUTextureFormat,
          viewDimension: typeName.includes('3d') ? '3d' : typeName.includes('array') ? '2d-array' : '2d',
        },
      };
    }
    case ResourceType.Texture: {
      const t = v.type as { format?: { name: string } | null };
      const depth = typeName.startsWith('texture_depth');
      return {
        ...base,
        texture: {
          sampleType: depth ? 'depth' : TEXTURE_SAMPLE_TYPES[t.format?.name ?? 'f32'] ?? 'float',
          viewDimension: typeName.includes('cube') ? 'cube' : typeName.includes('3d') ? '3d' : typeName.includes('array') ? '2d-array' : '2d',
        },
      };
    }
    case ResourceType.Sampler:
      return { ...base, sampler: { type: typeName === 'sampler_comparison' ? 'comparison' : 'filtering' } };
    default:
      throw new Error(`unsupported WGSL resource '${v.name}' (${typeName})`);
  }
}

/**
 * The resources the given entry points use (directly or through the functions they call), grouped by
 * bind group; groups in between that they do not use are empty. Layouts built from this hold exactly
 * what the pipeline needs, so a test kernel may import a bindings module without binding all of it.
 * wgsl_reflect's call-graph analysis decides "uses"; if it ever missed one, pipeline creation fails
 * loudly with "binding doesn't exist in the layout", never silently.
 */
export function entryPointBindings(shader: Pick<ReflectedShader, 'linked'>, entryPoints: readonly string[], visibility: GPUShaderStageFlags): BindingSlot[][] {
  const known = provided.get(bindingsKey(shader.linked.entry, shader.linked.code.length, entryPoints, visibility));
  if (known) return known;
  const reflect = parsedModule(shader.linked);
  const all = [...reflect.entry.compute, ...reflect.entry.vertex, ...reflect.entry.fragment];
  const groups: BindingSlot[][] = [];
  const seen = new Set<string>();
  for (const name of entryPoints) {
    const entry = all.find((e) => e.name === name);
    if (!entry) {
      throw new Error(`WGSL module '${shader.linked.entry}' has no entry point '${name}' (has: ${all.map((e) => e.name).join(', ')})`);
    }
    for (const v of entry.resources) {
      if (seen.has(v.name)) continue;
      seen.add(v.name);
      (groups[v.group] ??= []).push({ name: v.name, group: v.group, entry: layoutEntry(v, visibility) });
    }
  }
  for (let g = 0; g < groups.length; g++) groups[g] = (groups[g] ?? []).sort((a, b) => a.entry.binding - b.entry.binding);
  return groups;
}
