/**
 * Whether a packed scene fits the device's limits, checked before anything is allocated: a scene
 * too large for this GPU is refused in one line naming what needs how much and what the GPU allows
 * (a storage buffer, a texture side, the atlas's array layers), instead of a validation error in
 * the middle of an upload that has already replaced half of the previous scene's resources.
 */
import { LanternError } from '../errors.ts';
import { INSTANCE_TEXELS, INSTANCES_PER_ROW, type PackedScene } from './pack/scene-pack.ts';

/** The limits a scene's resources meet (GPUSupportedLimits has them all; tests pass smaller ones). */
export interface SceneLimits {
  readonly maxBufferSize: number;
  readonly maxStorageBufferBindingSize: number;
  readonly maxUniformBufferBindingSize: number;
  readonly maxTextureDimension2D: number;
  readonly maxTextureArrayLayers: number;
}

/** One resource's need against one limit. */
export interface SceneNeed {
  /** What needs it, in words: "the BVH nodes (bvh_nodes)". */
  readonly what: string;
  readonly limit: keyof SceneLimits;
  readonly need: number;
}

const STORAGE: ReadonlyArray<[keyof PackedScene & string, string]> = [
  ['bvh_nodes', 'the BVH nodes'],
  ['triangles_hot', 'the triangles'],
  ['triangles_shading', "the triangles' shading data"],
  ['materials', 'the materials'],
  ['light_slots', 'the light table'],
  ['texture_refs', 'the texture references'],
];
const UNIFORM: ReadonlyArray<[keyof PackedScene & string, string]> = [
  ['scene_info', 'the scene info'],
  ['punctual_lights', 'the point and spot lights'],
];

/** instance_data's size for records of `bytes` bytes: INSTANCES_PER_ROW records a row (shaders/scene/types.wgsl). */
export function instanceTextureSize(bytes: number): { width: number; height: number } {
  const records = Math.max(1, Math.ceil(bytes / (INSTANCE_TEXELS * 16)));
  return { width: INSTANCES_PER_ROW * INSTANCE_TEXELS, height: Math.ceil(records / INSTANCES_PER_ROW) };
}

/** Every need of a packed scene that a device limit bounds. */
export function sceneNeeds(packed: PackedScene): SceneNeed[] {
  const needs: SceneNeed[] = [];
  for (const [name, words] of STORAGE) {
    const bytes = (packed[name] as ArrayBuffer).byteLength;
    needs.push({ what: `${words} (${name})`, limit: 'maxStorageBufferBindingSize', need: bytes }, { what: `${words} (${name})`, limit: 'maxBufferSize', need: bytes });
  }
  for (const [name, words] of UNIFORM) {
    const bytes = (packed[name] as ArrayBuffer).byteLength;
    needs.push({ what: `${words} (${name})`, limit: 'maxUniformBufferBindingSize', need: bytes }, { what: `${words} (${name})`, limit: 'maxBufferSize', need: bytes });
  }
  for (const [atlas, words] of [[packed.atlas, 'the colour texture atlas'], [packed.linearAtlas, 'the linear texture atlas']] as const) {
    needs.push({ what: `${words}'s pages`, limit: 'maxTextureArrayLayers', need: atlas.pages.length }, { what: `${words}'s page side`, limit: 'maxTextureDimension2D', need: atlas.pageSize });
  }
  const side = (what: string, size: { width: number; height: number }) => ({ what, limit: 'maxTextureDimension2D' as const, need: Math.max(size.width, size.height) });
  needs.push(
    side('the environment map', packed.environment.environment_map),
    side("the environment map's sampling table", packed.environment.environment_cdf),
    side(`the tangents of ${packed.counts.triangles.toLocaleString('en-US')} triangles`, packed.triangleAttributes),
    side(`the records of ${packed.counts.instances.toLocaleString('en-US')} instances`, instanceTextureSize(packed.instances.byteLength)),
  );
  return needs;
}

const BYTE_LIMITS: ReadonlySet<keyof SceneLimits> = new Set(['maxBufferSize', 'maxStorageBufferBindingSize', 'maxUniformBufferBindingSize']);

function amount(limit: keyof SceneLimits, n: number): string {
  if (BYTE_LIMITS.has(limit)) return n >= 2 ** 20 ? `${(n / 2 ** 20).toFixed(1)} MiB` : `${n.toLocaleString('en-US')} bytes`;
  return limit === 'maxTextureArrayLayers' ? `${n.toLocaleString('en-US')} texture layers` : `${n.toLocaleString('en-US')} texels a side`;
}

/** The first need over its limit, or undefined when the scene fits. */
export function sceneOverLimit(packed: PackedScene, limits: SceneLimits): SceneNeed | undefined {
  return sceneNeeds(packed).find((n) => n.need > limits[n.limit]);
}

/** Refuses a scene that does not fit: "scene 'x' is too large for this GPU: ... needs A, the GPU allows B (limit)". */
export function checkSceneFits(packed: PackedScene, limits: SceneLimits, label: string): void {
  const over = sceneOverLimit(packed, limits);
  if (!over) return;
  throw new LanternError(
    `scene '${label}' is too large for this GPU: ${over.what} needs ${amount(over.limit, over.need)}, the GPU allows ${amount(over.limit, limits[over.limit])} (${over.limit})`,
    'Use a smaller scene or a GPU with higher limits',
  );
}
