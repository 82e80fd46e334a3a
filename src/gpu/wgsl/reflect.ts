/**
 * Reads GPU layouts out of WGSL so the host never writes a byte offset, a stride, a padding field or
 * a binding number by hand: struct and uniform layouts (webgpu-utils' makeShaderDataDefinitions) and
 * the resources each entry point uses (wgsl_reflect's WgslReflect, both parsers of WGSL). Pure CPU:
 * packing code and unit tests use it without a device.
 *
 * The answers come one of two ways, the same answers either way:
 * - precomputed, in every bundle (the CLI and its worker threads, the page and its workers): at build
 *   time scripts/shader-reflection.ts has ./precompute.ts reflect every module of src/shaders with
 *   the live functions below and writes the result into ./precomputed.ts. reflectModule takes a
 *   module from there when its linked code hashes as the code the data was made from; nothing is
 *   parsed.
 * - live, parsed here on first use: run from sources (Vitest, the dev server), where ./precomputed.ts
 *   holds nothing; shaders linked from other sources (reflectLinked: the test kernels, a small
 *   scene's unrolled traversal with its generated module, gpu/specialisation.ts); and a module or
 *   entry point the data lacks (it failed to reflect at build time, or its code differs).
 * ./precompute.test.ts holds the precomputed data equal to live reflection for every module.
 */
import { makeShaderDataDefinitions, type ShaderDataDefinitions, type TypeDefinition } from 'webgpu-utils';
import { ResourceType, WgslReflect, type VariableInfo } from 'wgsl_reflect/wgsl_reflect.module.js';
import { LanternError } from '../../errors.ts';
import { linkWgsl, type LinkedShader } from './linker.ts';
import { PRECOMPUTED_REFLECTION } from './precomputed.ts';

// webgpu-utils reads GPUShaderStage while reflecting. Browsers and Dawn define it; plain Node (unit
// tests, packing in a worker without WebGPU, the build) does not. These are the spec's constant values.
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

/**
 * What the host reads of a module's reflection: its structs' layouts and its uniforms' (for
 * webgpu-utils' makeStructuredView). The rest of makeShaderDataDefinitions' answer is not kept.
 */
export type ShaderLayouts = Pick<ShaderDataDefinitions, 'structs' | 'uniforms'>;

export function structLayout(defs: ShaderLayouts, name: string): StructLayout {
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
  readonly defs: ShaderLayouts;
  /** 'precomputed': defs and entry point resources were read from the data the build made; 'live': parsed here when first asked for. */
  readonly source: 'precomputed' | 'live';
}

const reflectedCache = new Map<string, ReflectedShader>();

/** Whether reflectModule(entry) has been done already (start-up timelines report the first, costly one). */
export const isReflected = (entry: string): boolean => reflectedCache.has(entry);

/** Links and reflects a module of src/shaders once per process: precomputed where the bundle holds it, else live. */
export function reflectModule(entry: string): ReflectedShader {
  let r = reflectedCache.get(entry);
  if (!r) {
    const linked = linkWgsl(entry);
    r = precomputedShader(linked) ?? reflectLinked(linked);
    reflectedCache.set(entry, r);
  }
  return r;
}

/**
 * Live reflection of a linked shader. Nothing is parsed until asked for: `defs` on first read (a
 * kernel never reads them), each entry point's resources on the first entryPointBindings.
 */
export function reflectLinked(linked: LinkedShader): ReflectedShader {
  let defs: ShaderLayouts | undefined;
  return {
    linked,
    source: 'live',
    get defs() {
      return (defs ??= liveLayouts(linked));
    },
  };
}

/** makeShaderDataDefinitions' structs and uniforms of `linked` (a parse of all its code). */
export function liveLayouts(linked: LinkedShader): ShaderLayouts {
  let defs: ShaderDataDefinitions;
  try {
    defs = makeShaderDataDefinitions(linked.code);
  } catch (e) {
    throw cannotReflect(linked, e);
  }
  return { structs: defs.structs, uniforms: defs.uniforms };
}

const cannotReflect = (linked: LinkedShader, e: unknown) => new LanternError(`could not reflect WGSL module '${linked.entry}': ${(e as Error).message}`, undefined, { cause: e });

/** A resource an entry point uses: its WGSL variable name and where it is bound. */
export interface BindingSlot {
  readonly name: string;
  readonly group: number;
  readonly entry: GPUBindGroupLayoutEntry;
}

/**
 * A resource an entry point uses, as reflected: a bind group layout entry but for its visibility,
 * which is the pipeline's stages (the caller's to say).
 */
export interface EntryResource {
  readonly name: string;
  readonly group: number;
  readonly binding: number;
  readonly layout: Omit<GPUBindGroupLayoutEntry, 'binding' | 'visibility'>;
}

/**
 * wgsl_reflect's parse of a linked module, made once: the path tracer takes most of a second to
 * parse, and each of its pipeline variants asks for its bindings.
 */
const parsed = new WeakMap<LinkedShader, WgslReflect>();
function parsedModule(linked: LinkedShader): WgslReflect {
  let reflect = parsed.get(linked);
  if (!reflect) {
    try {
      reflect = new WgslReflect(linked.code);
    } catch (e) {
      throw cannotReflect(linked, e);
    }
    parsed.set(linked, reflect);
  }
  return reflect;
}

const TEXTURE_SAMPLE_TYPES: Record<string, GPUTextureSampleType> = { f32: 'float', u32: 'uint', i32: 'sint' };
const STORAGE_TEXTURE_ACCESS: Record<string, GPUStorageTextureAccess> = { write: 'write-only', read: 'read-only', read_write: 'read-write' };

function resourceLayout(v: VariableInfo): EntryResource['layout'] {
  const typeName = v.type.name;
  switch (v.resourceType) {
    case ResourceType.Uniform:
      return { buffer: { type: 'uniform' } };
    case ResourceType.Storage:
      return { buffer: { type: v.access === 'read' ? 'read-only-storage' : 'storage' } };
    case ResourceType.StorageTexture: {
      const t = v.type as { format?: { name: string } | null; access?: string };
      return {
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
        texture: {
          sampleType: depth ? 'depth' : TEXTURE_SAMPLE_TYPES[t.format?.name ?? 'f32'] ?? 'float',
          viewDimension: typeName.includes('cube') ? 'cube' : typeName.includes('3d') ? '3d' : typeName.includes('array') ? '2d-array' : '2d',
        },
      };
    }
    case ResourceType.Sampler:
      return { sampler: { type: typeName === 'sampler_comparison' ? 'comparison' : 'filtering' } };
    default:
      throw new Error(`unsupported WGSL resource '${v.name}' (${typeName})`);
  }
}

function liveEntryPoints(linked: LinkedShader) {
  const reflect = parsedModule(linked);
  return [...reflect.entry.compute, ...reflect.entry.vertex, ...reflect.entry.fragment];
}

/** The names of every entry point of `linked` (compute, vertex, fragment), parsed live. */
export function liveEntryPointNames(linked: LinkedShader): string[] {
  return liveEntryPoints(linked).map((e) => e.name);
}

/**
 * The resources entry point `name` of `linked` uses, directly or through the functions it calls,
 * parsed live. wgsl_reflect's call-graph analysis decides "uses": it follows calls, not values, so
 * override constants (which only choose branches) never change the answer.
 */
export function liveEntryResources(linked: LinkedShader, name: string): EntryResource[] {
  const all = liveEntryPoints(linked);
  const entry = all.find((e) => e.name === name);
  if (!entry) throw new Error(`WGSL module '${linked.entry}' has no entry point '${name}' (has: ${all.map((e) => e.name).join(', ')})`);
  return entry.resources.map((v) => ({ name: v.name, group: v.group, binding: v.binding, layout: resourceLayout(v) }));
}

/** Entry points' resources read from the precomputed data, by linked shader (reflectModule puts them here). */
const precomputedEntries = new WeakMap<LinkedShader, Readonly<Record<string, readonly EntryResource[]>>>();

function entryResources(shader: Pick<ReflectedShader, 'linked'>, name: string): readonly EntryResource[] {
  return precomputedEntries.get(shader.linked)?.[name] ?? liveEntryResources(shader.linked, name);
}

/** Whether entryPointBindings would answer without parsing (start-up timelines report the parse). */
export function bindingsKnown(shader: Pick<ReflectedShader, 'linked'>, entryPoints: readonly string[]): boolean {
  const known = precomputedEntries.get(shader.linked);
  return parsed.has(shader.linked) || (known !== undefined && entryPoints.every((e) => known[e] !== undefined));
}

/**
 * The resources the given entry points use (directly or through the functions they call), grouped by
 * bind group; groups in between that they do not use are empty. Layouts built from this hold exactly
 * what the pipeline needs, so a test kernel may import a bindings module without binding all of it.
 * wgsl_reflect's call-graph analysis decides "uses"; if it ever missed one, pipeline creation fails
 * loudly with "binding doesn't exist in the layout", never silently.
 */
export function entryPointBindings(shader: Pick<ReflectedShader, 'linked'>, entryPoints: readonly string[], visibility: GPUShaderStageFlags): BindingSlot[][] {
  const groups: BindingSlot[][] = [];
  const seen = new Set<string>();
  for (const name of entryPoints) {
    for (const r of entryResources(shader, name)) {
      if (seen.has(r.name)) continue;
      seen.add(r.name);
      (groups[r.group] ??= []).push({ name: r.name, group: r.group, entry: { binding: r.binding, visibility, ...r.layout } });
    }
  }
  for (let g = 0; g < groups.length; g++) groups[g] = (groups[g] ?? []).sort((a, b) => a.entry.binding - b.entry.binding);
  return groups;
}

// ---- The precomputed data (written by ./precompute.ts at build time, read here) ----

/** Reflection of every module of src/shaders, as the build wrote it (JSON). */
export interface PrecomputedReflection {
  /** Distinct struct and uniform definitions, each once: most modules share most of theirs (scene/bindings'). */
  readonly definitions: readonly unknown[];
  readonly modules: Readonly<Record<string, PrecomputedModule>>;
}

export interface PrecomputedModule {
  /** codeHash of the linked code this was reflected from: other code is reflected live. */
  readonly code: string;
  /** Indices into `definitions`, by struct name and by uniform variable name. */
  readonly structs: Readonly<Record<string, number>>;
  readonly uniforms: Readonly<Record<string, number>>;
  /** Each entry point's resources (an entry point that failed to reflect at build time is missing: it is parsed live). */
  readonly entryPoints: Readonly<Record<string, readonly EntryResource[]>>;
}

/** Length and FNV-1a hash of a text: tells the code the data was made from from other code (a sub-millisecond pass over the path tracer). */
export function codeHash(code: string): string {
  let h = 0x811c9dc5;
  for (let i = 0; i < code.length; i++) h = Math.imul(h ^ code.charCodeAt(i), 0x01000193);
  return `${code.length}:${(h >>> 0).toString(16)}`;
}

let decoded: PrecomputedReflection | null | undefined;

/** ./precomputed.ts's data, parsed on first use; undefined when run from sources. */
function precomputedData(): PrecomputedReflection | undefined {
  if (decoded === undefined) decoded = PRECOMPUTED_REFLECTION === undefined ? null : decodePrecomputed(PRECOMPUTED_REFLECTION);
  return decoded ?? undefined;
}

/** The data from its JSON text, frozen: modules share its definitions, so a write into one (there is none) throws rather than change another module's layout. */
export function decodePrecomputed(json: string): PrecomputedReflection {
  return deepFreeze(JSON.parse(json) as PrecomputedReflection);
}

function deepFreeze<T>(value: T): T {
  if (value && typeof value === 'object' && !Object.isFrozen(value)) {
    Object.freeze(value);
    for (const v of Object.values(value)) deepFreeze(v);
  }
  return value;
}

/**
 * `linked` reflected from the precomputed data (the bundle's unless given), if that holds
 * linked.entry reflected from this very code; undefined means it is to be reflected live.
 */
export function precomputedShader(linked: LinkedShader, data = precomputedData()): ReflectedShader | undefined {
  const m = data?.modules[linked.entry];
  if (!data || !m || m.code !== codeHash(linked.code)) return undefined;
  const pick = <T>(indices: Readonly<Record<string, number>>) => Object.fromEntries(Object.entries(indices).map(([name, i]) => [name, data.definitions[i] as T]));
  precomputedEntries.set(linked, m.entryPoints);
  return { linked, source: 'precomputed', defs: { structs: pick(m.structs), uniforms: pick(m.uniforms) } };
}
