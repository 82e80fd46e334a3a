/**
 * Every compile-time switch of Lantern's kernels, in one place (as Falcor keeps a pass's defines in
 * one file): the WGSL `override` constants, what decides each, and the values. A kernel's variants are
 * the product of the switches its modules declare; a switch a module does not declare is never passed
 * (WebGPU refuses it).
 *
 *   decided by the scene (SceneFeatures, gpu/pack/scene-pack.ts), per scene, by SceneKernels:
 *     SCENE_HAS_ALPHA_MASKS, SCENE_HAS_PUNCTUAL_LIGHTS, SCENE_HAS_ENVIRONMENT,
 *     SCENE_HAS_ANALYTIC_PRIMITIVES, SCENE_HAS_INSTANCES, BVH_SHALLOW_STACK   bool
 *     SCENE_MATERIALS   mask of MATERIALS_* (scene/bsdf.wgsl): the general path and the BSDF kinds
 *     STATIC_ACCEL      enum ACCEL_* (scene/accel.wgsl): the static world's structure
 *   decided by the settings, per kernel set:
 *     SPECTRAL (lib/spectrum; the `spectral` setting), SAMPLER (lib/random; the chain's sampler,
 *     passes/path-trace-pass.ts withSampler)
 *   fixed per kernel (KERNEL_CONSTANTS below):
 *     RESTIR (integrator/path: the real-time frame kernel's estimator), BVH_COUNT_WORK (scene/bvh:
 *     the debug views count traversal work)
 *   decided by a frozen scene (gpu/specialisation.ts): the feature switches above with the kinds
 *     narrowed (SCENE_MATERIALS), INLINED_MAX_BOUNCES and INLINED_LIGHT_SAMPLING
 *     (integrator/dispatch), INLINED_LIGHT_COUNT (scene/lights)
 *   decided by the BVH builder's options (gpu/build/gpu-bvh-builder.ts): SEARCH_RADIUS,
 *     MAX_LEAF_SIZE, TRAVERSAL_COST, INTERSECTION_COST (build/ploc)
 *   workgroup sizes (WORKGROUP below; lib/workgroup declares them without a value): PIXEL_TILE_X,
 *     PIXEL_TILE_Y (the per-pixel passes), RAY_GROUP (trace-rays, the wavefront's queue kernels),
 *     given to every pipeline whose module declares them (gpu/kernel.ts); the passes size their
 *     dispatch grids from the same numbers. The exposure reduction and the BVH builder keep sizes of
 *     their own in WGSL: their workgroup arrays are sized by them.
 */
import { STATIC_ACCELS, type SceneFeatures } from './pack/scene-pack.ts';

/** The workgroup sizes of lib/workgroup: the only place they are set. */
export const WORKGROUP = {
  /** A per-pixel pass's tile: PIXEL_TILE_X × PIXEL_TILE_Y invocations, one a pixel. */
  pixelX: 8,
  pixelY: 8,
  /** A 1D pass over rays or queue entries; the benchmark's primary rays fill it with one pixel tile. */
  rays: 64,
} as const;

/** The overrides WORKGROUP sets, by their WGSL names. */
export const WORKGROUP_CONSTANTS: Readonly<Record<string, number>> = { PIXEL_TILE_X: WORKGROUP.pixelX, PIXEL_TILE_Y: WORKGROUP.pixelY, RAY_GROUP: WORKGROUP.rays };

/** Workgroups of a per-pixel pass over `width` × `height` pixels. */
export const pixelGroups = (width: number, height: number): [number, number] => [Math.ceil(width / WORKGROUP.pixelX), Math.ceil(height / WORKGROUP.pixelY)];

/** The workgroup overrides for a shader linked from `modules`: all of them if it imports lib/workgroup, else none (WebGPU refuses a constant the module does not declare). */
export const workgroupConstants = (modules: readonly string[]): Readonly<Record<string, number>> => (modules.includes('lib/workgroup') ? WORKGROUP_CONSTANTS : {});

/** MATERIALS_* of shaders/scene/bsdf.wgsl: SCENE_MATERIALS's bits. */
export const MATERIALS_GENERAL = 1;
export const MATERIALS_METALLIC_ROUGHNESS = 2;
export const MATERIALS_DIELECTRIC = 4;

/** Which BSDF kinds a scene's materials use (gpu/specialisation.ts materialKindsPresent). */
export interface MaterialKindsPresent {
  readonly metallicRoughness: boolean;
  readonly dielectric: boolean;
}

/** Generic kernels assume every kind may occur. */
const EVERY_KIND: MaterialKindsPresent = { metallicRoughness: true, dielectric: true };

/** The WGSL override each scene feature sets. */
export const FEATURE_CONSTANTS: Record<keyof SceneFeatures, string> = {
  alphaMasks: 'SCENE_HAS_ALPHA_MASKS',
  generalMaterials: 'SCENE_MATERIALS',
  punctualLights: 'SCENE_HAS_PUNCTUAL_LIGHTS',
  environment: 'SCENE_HAS_ENVIRONMENT',
  analyticPrimitives: 'SCENE_HAS_ANALYTIC_PRIMITIVES',
  instances: 'SCENE_HAS_INSTANCES',
  staticAccel: 'STATIC_ACCEL',
  shallowStack: 'BVH_SHALLOW_STACK',
};

/** SCENE_MATERIALS for a scene: the general path where it needs one, and the kinds it has. */
export function materialsMask(general: boolean, kinds: MaterialKindsPresent = EVERY_KIND): number {
  return (general ? MATERIALS_GENERAL : 0) | (kinds.metallicRoughness ? MATERIALS_METALLIC_ROUGHNESS : 0) | (kinds.dielectric ? MATERIALS_DIELECTRIC : 0);
}

/** The value scene feature `name` of `f` gives its override. */
export function featureValue(name: keyof SceneFeatures, f: SceneFeatures, kinds?: MaterialKindsPresent): number {
  if (name === 'staticAccel') return STATIC_ACCELS.indexOf(f.staticAccel);
  if (name === 'generalMaterials') return materialsMask(f.generalMaterials, kinds);
  return f[name] ? 1 : 0;
}

/** The override constants of the scene features `names` for a scene (narrowed to `kinds` where given). */
export function featureConstants(names: readonly (keyof SceneFeatures)[], f: SceneFeatures, kinds?: MaterialKindsPresent): Record<string, number> {
  return Object.fromEntries(names.map((name) => [FEATURE_CONSTANTS[name], featureValue(name, f, kinds)]));
}

/** A key of a scene's variant: its features' values, in the order of `names`. */
export const featureKey = (names: readonly (keyof SceneFeatures)[], f: SceneFeatures): string => names.map((name) => featureValue(name, f)).join(' ');

/** The constants fixed per kernel, by module and entry point. */
export const KERNEL_CONSTANTS = {
  /** The real-time frame's paths take the first bounce's direct light from the pixel's reservoir where ReSTIR is on. */
  pathTraceFrame: { RESTIR: 1 },
  /** The debug views count the nodes and primitives each traversal visits. */
  debugView: { BVH_COUNT_WORK: 1 },
} as const satisfies Record<string, Record<string, number>>;

/** SPECTRAL for a kernel set: four wavelengths per path. */
export const spectralConstants = (spectral: boolean): Record<string, number> => (spectral ? { SPECTRAL: 1 } : {});
