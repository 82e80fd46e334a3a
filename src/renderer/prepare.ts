/**
 * Everything between a loaded Scene and GPU upload that runs on the CPU: validation, flattening,
 * BVH build and packing. Pure (no GPU, no DOM), so it can run in a worker; the Renderer uploads the
 * result.
 */
import { buildBvhParallel, type BvhWorkerPool } from '../bvh/build-parallel.ts';
import { buildLevels, buildStaticBvh, buildStaticBvhWith, buildTopLevel, refitMeshBlas, type MeshBlas, type SceneLevels } from '../bvh/levels.ts';
import { refitBvh } from '../bvh/refit.ts';
import { buildGrid, type Accel, type Grid } from '../bvh/grid.ts';
import { buildWideBvh, WIDE_LAYOUTS, type WideBvh, type WideLayout } from '../bvh/wide.ts';
import type { Mat4 } from '../math/mat4.ts';
import type { Bvh } from '../bvh/types.ts';
import { packEnvironment } from '../gpu/pack/environment-pack.ts';
import { repackMaterialRecords } from '../gpu/pack/material-pack.ts';
import { packGeometry, packInstances, packMeshPart, packScene, packTlasNodes, repackLights, rescaleLights, sceneLayouts, type PackedScene } from '../gpu/pack/scene-pack.ts';
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
  /** The static world's BVH (all of the scene when nothing moves); its leaves index `triangles`. */
  readonly bvh: Bvh;
  /** The two-level structure, for scenes with moving instances (bvh/levels.ts). */
  readonly levels?: SceneLevels;
  /** The static world's uniform grid (bvh/grid.ts), when it is traced through one (accel 'grid'); it lists `bvh`'s leaves. */
  readonly grid?: Grid;
  /** The static world's wide tree (bvh/wide.ts), when it is traced through one (accel 'bvh4' or 'cwbvh'); collapsed from `bvh`. */
  readonly wide?: WideBvh;
  readonly packed: PackedScene;
  /** The meshes as loaded, of those morphed since (SceneUpdate.morphWeights apply to these). */
  readonly restMeshes?: ReadonlyMap<number, Mesh>;
  /** Milliseconds spent in each CPU stage. */
  readonly timings: { readonly flattenMs: number; readonly bvhMs: number; readonly packMs: number };
}

/** The CPU stages of preparation, in order, for progress reports. */
export const PREPARE_STAGES = ['flattening primitives', 'building the BVH', 'packing for the GPU'] as const;

export interface PrepareOptions {
  /** How the static world is traced (the setting `accel`): its BVH (the default) or a uniform grid over the same leaves. */
  readonly accel?: Accel;
}

/** The static world's structure for `accel` besides its BVH: a grid over the leaves of `bvh`, or a wide tree collapsed from it (none for 'bvh'). */
export function staticAccelFor(scene: Scene, triangles: TriangleList, bvh: Bvh, accel: Accel | undefined): { readonly grid?: Grid; readonly wide?: WideBvh } {
  if (accel === 'grid') return { grid: buildGrid(triangles.positions, triangles.kinds, bvh.triIndices, scene.tileGrid) };
  if ((WIDE_LAYOUTS as readonly string[]).includes(accel ?? '')) return { wide: buildWideBvh(bvh, accel as WideLayout) };
  return {};
}

/** What gpu/pack/scene-pack.ts packGeometry packs after the trees for the static world. */
export const staticAccelOf = (p: { readonly grid?: Grid; readonly wide?: WideBvh }): Grid | WideBvh | undefined => p.grid ?? p.wide;

/** Prepares `scene`; `onStage` hears of each stage as it begins (a worker reports progress with it). */
export function prepareScene(scene: Scene, onStage?: (stage: (typeof PREPARE_STAGES)[number]) => void, options: PrepareOptions = {}): PreparedScene {
  const { triangles, t0, t1 } = flattenStage(scene, onStage);
  return packStage(scene, triangles, buildStaticBvh(scene, triangles), t0, t1, onStage, options);
}

/**
 * `prepareScene` with the static world's BVH built on `bvhPool`'s workers (bvh/build-parallel.ts:
 * the same tree, sooner on a big scene); without a pool, or for a small scene, it is built here.
 */
export async function prepareSceneAsync(scene: Scene, onStage?: (stage: (typeof PREPARE_STAGES)[number]) => void, options: PrepareOptions & { readonly bvhPool?: BvhWorkerPool } = {}): Promise<PreparedScene> {
  const { triangles, t0, t1 } = flattenStage(scene, onStage);
  const bvh = await buildStaticBvhWith(scene, triangles, (positions, kinds) => buildBvhParallel(positions, {}, kinds, options.bvhPool));
  return packStage(scene, triangles, bvh, t0, t1, onStage, options);
}

function flattenStage(scene: Scene, onStage: ((stage: (typeof PREPARE_STAGES)[number]) => void) | undefined) {
  validateScene(scene);
  const t0 = performance.now();
  onStage?.(PREPARE_STAGES[0]);
  const triangles = flattenTriangles(scene);
  const t1 = performance.now();
  onStage?.(PREPARE_STAGES[1]);
  return { triangles, t0, t1 };
}

function packStage(scene: Scene, triangles: TriangleList, bvh: Bvh, t0: number, t1: number, onStage: ((stage: (typeof PREPARE_STAGES)[number]) => void) | undefined, options: PrepareOptions): PreparedScene {
  const levels = buildLevels(scene, bvh);
  const accel = staticAccelFor(scene, triangles, bvh, options.accel);
  const t2 = performance.now();
  onStage?.(PREPARE_STAGES[2]);
  const packed = packScene(scene, triangles, bvh, undefined, levels, staticAccelOf(accel));
  const t3 = performance.now();
  return { scene, triangles, bvh, ...(levels ? { levels } : {}), ...accel, packed, timings: { flattenMs: t1 - t0, bvhMs: t2 - t1, packMs: t3 - t2 } };
}

/** The accel a prepared scene was prepared for. */
export const accelOf = (prepared: PreparedScene): Accel => (prepared.grid ? 'grid' : (prepared.wide?.layout ?? 'bvh'));

/**
 * The scene prepared for another accel: the grid built over the same static BVH (or dropped) and the
 * geometry packed again around the materials already packed. The same scene when nothing changes.
 */
export function withAccel(prepared: PreparedScene, accel: Accel): PreparedScene {
  if (accelOf(prepared) === accel) return prepared;
  const { grid: _, wide: _wide, ...rest } = prepared;
  const built = staticAccelFor(prepared.scene, prepared.triangles, prepared.bvh, accel);
  const packed = packGeometry(prepared.scene, prepared.triangles, prepared.bvh, prepared.packed.packedMaterials, prepared.packed.environment, prepared.levels, staticAccelOf(built));
  return { ...rest, ...built, packed };
}


/** A write into one group-0 buffer: `data` at byte `offset` (0 and the whole buffer for a full rewrite). */
export interface BufferWrite {
  readonly name: (typeof GEOMETRY_BUFFERS)[number];
  readonly offset: number;
  readonly data: ArrayBuffer;
}

/** The group-0 buffers a geometry update may write. */
export const GEOMETRY_BUFFERS = ['scene_info', 'bvh_nodes', 'triangles_hot', 'triangles_shading', 'light_slots', 'punctual_lights', 'instances'] as const;

export interface GeometryUpdate {
  readonly prepared: PreparedScene;
  /** What to write, in order. */
  readonly writes: readonly BufferWrite[];
  /** Whether triangle_attributes must be written again (a full repack). */
  readonly attributes: boolean;
  /** What the update cost on the CPU: ms of bottom-level refits, of the top-level build, of packing. */
  readonly ms: { readonly refit: number; readonly tlas: number; readonly pack: number };
}

/**
 * Instances moved (new world-from-object transforms by instance id); see updateGeometry.
 */
export function moveInstances(prepared: PreparedScene, moves: ReadonlyMap<number, Mat4>): PreparedScene {
  return updateGeometry(prepared, new Map([...moves].map(([id, worldFromObject]) => [id, { worldFromObject }])), new Map()).prepared;
}

/**
 * Instances moved or changed material (InstancePose by instance id) and meshes morphed (weights by
 * mesh index, Mesh.morphTargets). The mesh as loaded stays in `restMeshes`, so weights always apply to it.
 * - Moving instances (Instance.moves) and the meshes they use: the two-level BVH's fast path. A
 *   morphed mesh's bottom level is refitted and its records rewritten where they lie; the instance
 *   records are rewritten (with this frame's transforms as the previous ones of those that moved, for
 *   motion vectors) and the top level rebuilt; the light table is rebuilt when a moving emitter moved.
 *   The world-space primitive list is shared with `prepared` and updated in place: use the result.
 * - Anything else (an instance that does not move moved after all, or a mesh of the static world
 *   morphed): its world-space primitives are written again, the static world's BVH is refitted rather
 *   than rebuilt, and the geometry is packed again around the materials and textures already packed.
 */
export function updateGeometry(prepared: PreparedScene, poses: ReadonlyMap<number, InstancePose>, morphWeights: ReadonlyMap<number, Float32Array>): GeometryUpdate {
  const { scene } = prepared;
  const indexOf = new Map(scene.instances.map((inst, i) => [inst.id, i]));
  for (const id of poses.keys()) {
    if (!indexOf.has(id)) throw new LanternError(`scene '${scene.name}' has no instance with id ${id}`);
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
  const touched = (i: number) => poses.has(instances[i]!.id) || morphWeights.has(instances[i]!.mesh);
  const levels = prepared.levels;
  const staticTouched = instances.some((inst, i) => !inst.moves && touched(i));
  // The world-space copies of what moved (CPU tools, light areas). When only moving instances moved
  // they are written in place: copying the whole scene's list every frame would cost a large scene
  // tens of megabytes per frame for a door. The static world's BVH indexes the list, so a static
  // move works on a copy.
  const fast = levels !== undefined && !staticTouched;
  const triangles: TriangleList = fast
    ? prepared.triangles
    : { ...prepared.triangles, positions: new Float32Array(prepared.triangles.positions), swapped: new Uint8Array(prepared.triangles.swapped), materialIds: new Uint32Array(prepared.triangles.materialIds) };
  instances.forEach((inst, i) => {
    if (touched(i)) writeInstanceTriangles(moved, inst, i, triangles, triangles.instanceFirstTriangle[i]!);
  });
  const t0 = performance.now();
  if (!levels || staticTouched) {
    const bvh = refitBvh(prepared.bvh, triangles.positions, triangles.kinds);
    let nextLevels = levels;
    if (levels) {
      const blas = new Map(levels.blas);
      for (const m of morphWeights.keys()) if (blas.has(m)) blas.set(m, refitMeshBlas(moved, blas.get(m)!, meshes[m]!));
      nextLevels = { ...levels, blas, ...buildTopLevel(moved, bvh, levels.dynamic, blas) };
    }
    // The grid or wide tree is built again over the moved static world (its cells are not refitted; the wide boxes are collapsed from the refitted BVH).
    const accel = staticAccelFor(moved, triangles, bvh, accelOf(prepared));
    const t1 = performance.now();
    const packed = packGeometry(moved, triangles, bvh, prepared.packed.packedMaterials, prepared.packed.environment, nextLevels, staticAccelOf(accel));
    const t2 = performance.now();
    const next: PreparedScene = { ...prepared, scene: moved, triangles, bvh, ...(nextLevels ? { levels: nextLevels } : {}), ...accel, packed, restMeshes, timings: { flattenMs: 0, bvhMs: t1 - t0, packMs: t2 - t1 } };
    return { prepared: next, writes: GEOMETRY_BUFFERS.map((name) => ({ name, offset: 0, data: packed[name] })), attributes: true, ms: { refit: t1 - t0, tlas: nextLevels?.tlasMs ?? 0, pack: t2 - t1 } };
  }

  // Only moving instances and their meshes changed: the fast path.
  const layouts = sceneLayouts();
  const writes: BufferWrite[] = [];
  const blas = new Map(levels.blas);
  for (const m of morphWeights.keys()) {
    const before = blas.get(m);
    if (!before) continue;
    const after: MeshBlas = refitMeshBlas(moved, before, meshes[m]!);
    blas.set(m, after);
    const part = packMeshPart(moved, m, after, prepared.packed.layout, prepared.packed.packedMaterials);
    const at = prepared.packed.layout.meshes.get(m)!;
    writes.push({ name: 'bvh_nodes', offset: at.nodeBase * layouts.node.strideWords * 4, data: part.nodes });
    writes.push({ name: 'triangles_hot', offset: at.leafBase * layouts.hot.strideWords * 4, data: part.hot });
    writes.push({ name: 'triangles_shading', offset: at.leafBase * layouts.shading.strideWords * 4, data: part.shading });
  }
  const t1 = performance.now();
  const top = buildTopLevel(moved, prepared.bvh, levels.dynamic, blas, levels.tlas);
  const nextLevels: SceneLevels = { ...levels, blas, ...top };
  writes.push({ name: 'bvh_nodes', offset: prepared.packed.layout.tlasBase * layouts.node.strideWords * 4, data: packTlasNodes(top.tlas, prepared.packed.layout) });
  // Motion vectors: the instances that moved were where they were before this update.
  const previous = new Map<number, Mat4>();
  instances.forEach((inst, i) => {
    if (inst.moves && poses.get(inst.id)?.worldFromObject) previous.set(i, scene.instances[i]!.worldFromObject);
  });
  const instanceBytes = packInstances(moved, nextLevels, prepared.packed.layout, prepared.packed.packedMaterials, previous);
  writes.push({ name: 'instances', offset: 0, data: instanceBytes });
  let packed: PackedScene = { ...prepared.packed, instances: instanceBytes };
  // The light table: moving emitters may have changed power (scale, material, morph).
  const emitters = new Set(prepared.packed.lightList.instances);
  const lightsMoved = levels.dynamic.some((ii, k) => touched(ii) && (emitters.has(k + 1) || powerMayChange(scene, moved, ii, prepared)));
  if (lightsMoved) {
    const lights = repackLights(moved, triangles, prepared.bvh, nextLevels, packed);
    packed = { ...packed, ...lights };
    writes.push({ name: 'scene_info', offset: 0, data: lights.scene_info }, { name: 'light_slots', offset: 0, data: lights.light_slots }, { name: 'punctual_lights', offset: 0, data: lights.punctual_lights });
  }
  const t2 = performance.now();
  const next: PreparedScene = { ...prepared, scene: moved, triangles, levels: nextLevels, packed, restMeshes, timings: { flattenMs: 0, bvhMs: t1 - t0 + top.tlasMs, packMs: t2 - t1 - top.tlasMs } };
  return { prepared: next, writes, attributes: false, ms: { refit: t1 - t0, tlas: top.tlasMs, pack: t2 - t1 - top.tlasMs } };
}

/** Whether moving instance `ii` now shows an emitting material it did not show before (its emitters are not in the light table yet). */
function powerMayChange(before: Scene, after: Scene, ii: number, prepared: PreparedScene): boolean {
  const m = after.instances[ii]!.material;
  return m !== undefined && m !== before.instances[ii]!.material && prepared.packed.packedMaterials.emissionMean[m]! * Math.max(...after.materials[m]!.emission) > 0;
}

/**
 * The scene under another environment: only the environment, the light table and the scene info
 * change (packed again around the same BVH, triangles and materials); the camera's exposure follows
 * scene/environment-override.ts.
 */
export function withPreparedEnvironment(prepared: PreparedScene, environment: Environment): PreparedScene {
  const scene = withEnvironment(prepared.scene, environment);
  const packed = packGeometry(scene, prepared.triangles, prepared.bvh, prepared.packed.packedMaterials, packEnvironment(environment), prepared.levels, staticAccelOf(prepared));
  return { ...prepared, scene, packed };
}

/** The group-0 buffers an emission edit rewrites besides `materials` (the light table and its normaliser in scene_info). */
export const LIGHT_BUFFERS = ['scene_info', 'light_slots', 'punctual_lights'] as const;

export interface EditedMaterials {
  readonly prepared: PreparedScene;
  /** Whether an emission changed: the light table (LIGHT_BUFFERS) was packed again and must be written too. */
  readonly lightsChanged: boolean;
  /**
   * Whether texture references changed (an animated material's uv offset, world/material-animation.ts):
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
  const base: PackedScene = { ...prepared.packed, materials: packedMaterials.materials, texture_refs: packedMaterials.textureRefs, packedMaterials };
  // New emission: the light table is rebuilt from the emitters it holds (no walk over the geometry),
  // unless a material starts to emit, whose primitives it does not hold yet.
  const rescaled = lightsChanged ? rescaleLights(edited, prepared.triangles, prepared.bvh, prepared.levels, base, scene.materials, edits.keys()) : undefined;
  const packed: PackedScene = !lightsChanged
    ? base
    : rescaled
      ? { ...base, ...rescaled }
      : packGeometry(edited, prepared.triangles, prepared.bvh, packedMaterials, prepared.packed.environment, prepared.levels, staticAccelOf(prepared));
  return { prepared: { ...prepared, scene: edited, packed }, lightsChanged, textureRefsChanged };
}
