/**
 * Everything between a loaded Scene and GPU upload that runs on the CPU: validation, flattening,
 * BVH build and packing. Pure (no GPU, no DOM), so it can run in a worker; the Renderer uploads the
 * result.
 */
import { buildBvh } from '../bvh/build.ts';
import { refitBvh } from '../bvh/refit.ts';
import type { Mat4 } from '../math/mat4.ts';
import type { Bvh } from '../bvh/types.ts';
import { packEnvironment } from '../gpu/pack/environment-pack.ts';
import { repackMaterialRecords } from '../gpu/pack/material-pack.ts';
import { packGeometry, packScene, sceneLayouts, type PackedScene } from '../gpu/pack/scene-pack.ts';
import { applyMaterialEdit, editChangesEmission, type MaterialEdit } from '../scene/material-edit.ts';
import { withEnvironment } from '../scene/environment-override.ts';
import type { Environment } from '../scene/environment.ts';
import { flattenTriangles, writeInstanceTriangles, type TriangleList } from '../scene/triangles.ts';
import { LanternError } from '../errors.ts';
import type { InstancePose } from '../scene/dynamics.ts';
import { morphMesh } from '../scene/morph.ts';
import type { Mesh, Scene } from '../scene/types.ts';
import { validateScene } from '../scene/validate.ts';

export interface PreparedScene {
  readonly scene: Scene;
  readonly triangles: TriangleList;
  readonly bvh: Bvh;
  readonly packed: PackedScene;
  /** The meshes as loaded, of those morphed since (SceneUpdate.morphWeights apply to these). */
  readonly restMeshes?: ReadonlyMap<number, Mesh>;
  /** Milliseconds spent in each CPU stage. */
  readonly timings: { readonly flattenMs: number; readonly bvhMs: number; readonly packMs: number };
}

/** The CPU stages of preparation, in order, for progress reports. */
export const PREPARE_STAGES = ['flattening primitives', 'building the BVH', 'packing for the GPU'] as const;

/** Prepares `scene`; `onStage` hears of each stage as it begins (a worker reports progress with it). */
export function prepareScene(scene: Scene, onStage?: (stage: (typeof PREPARE_STAGES)[number]) => void): PreparedScene {
  validateScene(scene);
  const t0 = performance.now();
  onStage?.(PREPARE_STAGES[0]);
  const triangles = flattenTriangles(scene);
  const t1 = performance.now();
  onStage?.(PREPARE_STAGES[1]);
  const bvh = buildBvh(triangles.positions, {}, triangles.kinds);
  const t2 = performance.now();
  onStage?.(PREPARE_STAGES[2]);
  const packed = packScene(scene, triangles, bvh);
  const t3 = performance.now();
  return { scene, triangles, bvh, packed, timings: { flattenMs: t1 - t0, bvhMs: t2 - t1, packMs: t3 - t2 } };
}

/** The group-0 buffers moveInstances rewrites (the same sizes as before: the tree keeps its shape). */
export const MOVED_BUFFERS = ['scene_info', 'bvh_nodes', 'triangles_hot', 'triangles_shading', 'light_slots', 'punctual_lights'] as const;

/**
 * Instances moved (new world-from-object transforms by instance id); see updateGeometry.
 */
export function moveInstances(prepared: PreparedScene, moves: ReadonlyMap<number, Mat4>): PreparedScene {
  return updateGeometry(prepared, new Map([...moves].map(([id, worldFromObject]) => [id, { worldFromObject }])), new Map());
}

/**
 * Instances moved or changed material (InstancePose by instance id) and meshes morphed (weights by
 * mesh index, Mesh.morphTargets): their primitives are written again, the BVH is refitted rather than
 * rebuilt, and the geometry and lights are packed again around the materials and textures already
 * packed. The mesh as loaded stays in `restMeshes`, so weights always apply to it.
 */
export function updateGeometry(prepared: PreparedScene, poses: ReadonlyMap<number, InstancePose>, morphWeights: ReadonlyMap<number, Float32Array>): PreparedScene {
  const { scene } = prepared;
  for (const id of poses.keys()) {
    if (!scene.instances.some((inst) => inst.id === id)) throw new LanternError(`scene '${scene.name}' has no instance with id ${id}`);
  }
  const restMeshes = new Map(prepared.restMeshes);
  const meshes = [...scene.meshes];
  for (const [index, weights] of morphWeights) {
    const rest = restMeshes.get(index) ?? scene.meshes[index];
    if (!rest) throw new LanternError(`scene '${scene.name}' has no mesh ${index}`);
    restMeshes.set(index, rest);
    meshes[index] = morphMesh(rest, weights);
  }
  const instances = scene.instances.map((inst) => {
    const pose = poses.get(inst.id);
    return pose ? { ...inst, ...pose } : inst;
  });
  const moved: Scene = { ...scene, meshes, instances };
  const triangles: TriangleList = { ...prepared.triangles, positions: new Float32Array(prepared.triangles.positions), swapped: new Uint8Array(prepared.triangles.swapped), materialIds: new Uint32Array(prepared.triangles.materialIds) };
  instances.forEach((inst, i) => {
    if (poses.has(inst.id) || morphWeights.has(inst.mesh)) writeInstanceTriangles(moved, inst, i, triangles, triangles.instanceFirstTriangle[i]!);
  });
  const t0 = performance.now();
  const bvh = refitBvh(prepared.bvh, triangles.positions, triangles.kinds);
  const t1 = performance.now();
  const packed = packGeometry(moved, triangles, bvh, prepared.packed.packedMaterials, prepared.packed.environment);
  const t2 = performance.now();
  return { scene: moved, triangles, bvh, packed, restMeshes, timings: { flattenMs: 0, bvhMs: t1 - t0, packMs: t2 - t1 } };
}

/**
 * The scene under another environment: only the environment, the light table and the scene info
 * change (packed again around the same BVH, triangles and materials); the camera's exposure follows
 * scene/environment-override.ts.
 */
export function withPreparedEnvironment(prepared: PreparedScene, environment: Environment): PreparedScene {
  const scene = withEnvironment(prepared.scene, environment);
  const packed = packGeometry(scene, prepared.triangles, prepared.bvh, prepared.packed.packedMaterials, packEnvironment(environment));
  return { ...prepared, scene, packed };
}

/** The group-0 buffers an emission edit rewrites besides `materials` (the light table and its normaliser in scene_info). */
export const LIGHT_BUFFERS = ['scene_info', 'light_slots', 'punctual_lights'] as const;

export interface EditedMaterials {
  readonly prepared: PreparedScene;
  /** Whether an emission changed: the light table (LIGHT_BUFFERS) was packed again and must be written too. */
  readonly lightsChanged: boolean;
  /**
   * Whether texture references changed (an animated material's uv offset, scene/material-animation.ts):
   * `texture_refs` was packed again and must be written too.
   */
  readonly textureRefsChanged: boolean;
}

/**
 * Material edits by material index (scene/material-edit.ts): only the edited records are packed
 * again, around the texture references and atlases already packed (an animated material's texture
 * swap points its record at a reference packed ahead; its uv offset rewrites its own references, so
 * then `texture_refs` is new too: textureRefsChanged). An emission edit changes light
 * powers, so then the light table is packed again too; that walks every triangle (packGeometry, the
 * same CPU cost as moveInstances: a few ms for a Doom map, a few hundred for a million triangles),
 * while a colour or roughness edit costs one record. BVH, triangles and textures never change.
 */
export function editMaterials(prepared: PreparedScene, edits: ReadonlyMap<number, MaterialEdit>): EditedMaterials {
  const { scene } = prepared;
  const materials = [...scene.materials];
  let lightsChanged = false;
  for (const [index, edit] of edits) {
    const m = materials[index];
    if (!m) throw new LanternError(`scene '${scene.name}' has no material ${index} (it has ${materials.length})`);
    lightsChanged ||= editChangesEmission(m, edit);
    materials[index] = applyMaterialEdit(m, edit);
  }
  const edited: Scene = { ...scene, materials };
  const packedMaterials = repackMaterialRecords(materials, prepared.packed.packedMaterials, sceneLayouts(), edits.keys());
  const textureRefsChanged = packedMaterials.textureRefs !== prepared.packed.packedMaterials.textureRefs;
  const packed: PackedScene = lightsChanged
    ? packGeometry(edited, prepared.triangles, prepared.bvh, packedMaterials, prepared.packed.environment)
    : { ...prepared.packed, materials: packedMaterials.materials, texture_refs: packedMaterials.textureRefs, packedMaterials };
  return { prepared: { ...prepared, scene: edited, packed }, lightsChanged, textureRefsChanged };
}
