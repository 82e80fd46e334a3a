/**
 * Scene-specialised kernels: what a frozen scene lets the compiler know, as data in one place.
 * The generic kernels read the scene from buffers, like an interpreter; once a scene stops changing
 * the renderer compiles its tracing kernels again with a SceneSpecialisation:
 *
 *   (a) material kinds present: the kind bits of SCENE_MATERIALS (scene/bsdf.wgsl)
 *       and the scene features (gpu/kernel-variants.ts FEATURE_CONSTANTS) fold absent kinds' code away;
 *   (b) what uniforms hold but a frozen scene fixes: INLINED_MAX_BOUNCES, INLINED_LIGHT_SAMPLING
 *       (passes/path-trace.wgsl) and INLINED_LIGHT_COUNT (scene/lights.wgsl) become constants
 *       (a scene without lights loses light sampling altogether);
 *   (c) small scenes (an unroll cost, UNROLL_COST per primitive kind, of at most `unrollLimit`): scene/traversal-unrolled is linked in place
 *       of scene/bvh, with the scene's primitives as constants in a generated module
 *       (gpu/pack/primitives-module.ts) and one intersection call per primitive: no BVH at all.
 *
 * Every choice keeps the estimator: the constants equal what the buffers hold, and the unrolled
 * traversal returns the same closest hit as the BVH (the same ray/triangle arithmetic; a tie between
 * equally distant triangles may go either way). Images therefore agree within Monte Carlo error.
 */
import { LanternError } from '../errors.ts';
import { ComputeKernel, type KernelOptions } from './kernel.ts';
import { FEATURE_CONSTANTS, featureConstants, type MaterialKindsPresent } from './kernel-variants.ts';
import { PRIMITIVES_MODULE, primitivesModule } from './pack/primitives-module.ts';
import { sceneLayouts, type PackedScene, type SceneFeatures } from './pack/scene-pack.ts';
import { linkWgsl } from './wgsl/linker.ts';
import { reflectLinked, reflectModule, type ReflectedShader } from './wgsl/reflect.ts';
import { SHADER_MODULES } from '../shaders/index.ts';

/**
 * Scenes with at most this many primitives trace without a BVH. Unrolled code grows with the count
 * (two calls per primitive) and so does compile time; the BVH wins once a ray would skip most
 * primitives. docs/perf.md records the measurements that place it.
 */
export const UNROLL_PRIMITIVE_LIMIT = 64;

/**
 * What one primitive of each kind costs against the unroll limit: unrolled, every primitive is its
 * own inlined intersection test, and a capsule's (a cylinder and two spheres) is several times a
 * triangle's. Measured on an H200 (docs/perf.md): caffeine's 6 triangles, 24 spheres and 29
 * capsules unrolled ran at 0.13× the BVH kernel after a 26 s compile, while 22 triangles (prism) or
 * 5 spheres (spheres) ran 1.5–1.7× faster.
 */
export const UNROLL_COST = { triangle: 1, sphere: 2, capsule: 8 } as const;

/** The unroll cost of a packed scene's primitives (UNROLL_COST). */
export function unrollCost(counts: { readonly triangles: number; readonly spheres: number; readonly capsules: number }): number {
  const triangles = counts.triangles - counts.spheres - counts.capsules;
  return triangles * UNROLL_COST.triangle + counts.spheres * UNROLL_COST.sphere + counts.capsules * UNROLL_COST.capsule;
}

/** The module the unrolled traversal replaces, and its replacement. */
const TRAVERSAL_MODULE = 'scene/bvh';
const UNROLLED_TRAVERSAL_MODULE = 'scene/traversal-unrolled';

/** Sampling settings inlined as constants; they are fixed while a specialised kernel is in use. */
export interface InlinedSettings {
  readonly maxBounces: number;
  /** Index in passes/variants.ts LIGHT_SAMPLING (LIGHT_SAMPLING_* of integrator/path.wgsl). */
  readonly lightSampling: number;
}

export type { MaterialKindsPresent };

export interface SceneSpecialisation {
  readonly sceneName: string;
  readonly features: SceneFeatures;
  readonly materialKinds: MaterialKindsPresent;
  readonly settings: InlinedSettings;
  readonly primitiveCount: number;
  /** The generated primitives module when the scene is traced without a BVH. */
  readonly unrolled?: string;
  /** Every override constant the specialisation sets (a kernel takes those its module declares). */
  readonly constants: Readonly<Record<string, number>>;
}

/** The independent parts of a specialisation, each of which can be left out (bench --specialise measures them one by one). */
export const SPECIALISATION_PARTS = ['kinds', 'bounces', 'light-sampling', 'light-count', 'unroll'] as const;
export type SpecialisationPart = (typeof SPECIALISATION_PARTS)[number];

/** The parts applied unless told otherwise. */
export const DEFAULT_SPECIALISATION_PARTS: readonly SpecialisationPart[] = SPECIALISATION_PARTS;

export interface SpecialiseOptions {
  /** Largest unroll cost (unrollCost: triangles count 1, spheres and capsules more) traced without a BVH (0: never). */
  readonly unrollLimit?: number;
  /** Which parts to apply (default: DEFAULT_SPECIALISATION_PARTS). */
  readonly parts?: readonly SpecialisationPart[];
}

/** MATERIAL_KIND_* of shaders/scene/types.wgsl, in the order of scene/types.ts MaterialKind. */
const MATERIAL_KIND_METALLIC_ROUGHNESS = 1;
const MATERIAL_KIND_DIELECTRIC = 2;

/** The material kinds the packed materials hold (read back from the bytes the GPU reads). */
export function materialKindsPresent(packed: PackedScene): MaterialKindsPresent {
  const layout = sceneLayouts().material;
  const words = new Uint32Array(packed.materials);
  const kindWord = layout.word('kind', 'u32');
  const count = Math.floor(packed.materials.byteLength / layout.stride);
  const kinds = new Set<number>();
  for (let i = 0; i < count; i++) kinds.add(words[i * layout.strideWords + kindWord]!);
  return { metallicRoughness: kinds.has(MATERIAL_KIND_METALLIC_ROUGHNESS), dielectric: kinds.has(MATERIAL_KIND_DIELECTRIC) };
}

/** What the kernels specialised to this packed scene and these settings know at compile time. */
export function specialiseScene(packed: PackedScene, sceneName: string, settings: InlinedSettings, options: SpecialiseOptions = {}): SceneSpecialisation {
  const limit = options.unrollLimit ?? UNROLL_PRIMITIVE_LIMIT;
  if (!Number.isInteger(limit) || limit < 0) throw new LanternError(`the unroll limit must be a whole number ≥ 0, not ${limit}`);
  if (!Number.isInteger(settings.maxBounces) || settings.maxBounces < 0) throw new LanternError(`max bounces must be a whole number ≥ 0, not ${settings.maxBounces}`);
  const materialKinds = materialKindsPresent(packed);
  const primitiveCount = packed.counts.triangles;
  const parts = new Set(options.parts ?? DEFAULT_SPECIALISATION_PARTS);
  const constants: Record<string, number> = {};
  Object.assign(constants, featureConstants(Object.keys(FEATURE_CONSTANTS) as (keyof SceneFeatures)[], packed.features, parts.has('kinds') ? materialKinds : undefined));
  if (parts.has('bounces')) constants.INLINED_MAX_BOUNCES = settings.maxBounces;
  if (parts.has('light-sampling')) constants.INLINED_LIGHT_SAMPLING = settings.lightSampling;
  if (parts.has('light-count')) constants.INLINED_LIGHT_COUNT = packed.counts.lights;
  const unrolled = parts.has('unroll') && primitiveCount > 0 && unrollCost(packed.counts) <= limit ? primitivesModule(sceneLayouts().hot, packed.triangles_hot, primitiveCount, sceneName) : undefined;
  return { sceneName, features: packed.features, materialKinds, settings, primitiveCount, ...(unrolled ? { unrolled } : {}), constants };
}

/** A one-line account of a specialisation, for logs and the bench report. */
export function describeSpecialisation(s: SceneSpecialisation): string {
  const kinds = ['diffuse', s.materialKinds.metallicRoughness ? 'metallic-roughness' : '', s.materialKinds.dielectric ? 'dielectric' : ''].filter(Boolean).join(' + ');
  const traversal = s.unrolled ? `${s.primitiveCount} primitives unrolled, no BVH` : `BVH over ${s.primitiveCount} primitives`;
  return `${traversal}; materials ${kinds}; ${s.settings.maxBounces} bounces inlined`;
}

/** Names of the `override` constants a WGSL text declares. */
export function declaredOverrides(code: string): Set<string> {
  return new Set([...code.matchAll(/^\s*override\s+([A-Za-z_][A-Za-z0-9_]*)/gm)].map((m) => m[1]!));
}

/** Unrolled shaders by specialisation and entry module: the kernels of one module compiled for one specialisation share one parse. */
const unrolledShaders = new WeakMap<SceneSpecialisation, Map<string, ReflectedShader>>();

/**
 * `entry` linked for a specialisation: the unrolled traversal and its generated data in place of
 * scene/bvh when the scene is small. Without it the code is the generic module's, so its reflection
 * is too (reflectModule: precomputed in a bundle). The unrolled code exists only for this scene and
 * is reflected live, once per module and specialisation: only its entry points' resources are parsed
 * (a kernel reads no layouts), a fraction of the seconds its pipelines take to compile.
 */
export function specialisedShader(entry: string, s: SceneSpecialisation): ReflectedShader {
  if (!s.unrolled) return reflectModule(entry);
  let byEntry = unrolledShaders.get(s);
  if (!byEntry) unrolledShaders.set(s, (byEntry = new Map()));
  let shader = byEntry.get(entry);
  if (!shader) {
    const sources = new Map(SHADER_MODULES);
    sources.set(PRIMITIVES_MODULE, s.unrolled);
    shader = reflectLinked(linkWgsl(entry, sources, new Map([[TRAVERSAL_MODULE, UNROLLED_TRAVERSAL_MODULE]])));
    byEntry.set(entry, shader);
  }
  return shader;
}

export interface SpecialisedKernel {
  readonly kernel: ComputeKernel;
  /** Wall milliseconds from linking to the pipeline being ready (createComputePipelineAsync). */
  readonly compileMs: number;
}

/**
 * Compiles `base` specialised to `s`, asynchronously. `extraConstants` are the entry point's own
 * (RESTIR, SAMPLER, SPECTRAL: gpu/kernel-variants.ts). Only constants the linked module declares are passed (WebGPU refuses others).
 */
export async function compileSpecialised(device: GPUDevice, base: { readonly module: string; readonly entryPoint: string }, s: SceneSpecialisation, extraConstants: Record<string, number> = {}): Promise<SpecialisedKernel> {
  const t0 = performance.now();
  const shader = specialisedShader(base.module, s);
  const declared = declaredOverrides(shader.linked.code);
  const constants = Object.fromEntries(Object.entries({ ...s.constants, ...extraConstants }).filter(([name]) => declared.has(name)));
  const options: KernelOptions = { module: shader, entryPoint: base.entryPoint, constants, cacheModule: false };
  const kernel = await ComputeKernel.create(device, options);
  return { kernel, compileMs: performance.now() - t0 };
}
