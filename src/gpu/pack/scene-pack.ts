/**
 * Scene + BVH → the byte arrays of bind group 0 (shaders/scene/bindings.wgsl), pure CPU. Triangles
 * are reordered into BVH leaf order and split into a hot array (what traversal reads: a vertex and
 * two edges) and a cold one (world-space normals, uvs, material, read once per closest hit).
 * Materials and textures are packed by material-pack.ts, lights by light-pack.ts. Every layout comes
 * from reflection. What the scene uses (alpha tests, non-diffuse materials, lights of each kind)
 * becomes `features`, from which the pipelines' override constants are chosen.
 */
import type { Bvh } from '../../bvh/types.ts';
import type { Grid } from '../../bvh/grid.ts';
import { packWide, type WideBvh } from '../../bvh/wide.ts';
import { tlasCapacity, type Tlas } from '../../bvh/tlas.ts';
import { determinant3, IDENTITY, invertAffine, normalMatrix, type Mat4 } from '../../math/mat4.ts';
import { meshScene, type SceneLevels } from '../../bvh/levels.ts';
import { luminance } from '../../math/vec3.ts';
import { meshPrimitiveCount, PRIMITIVE_KIND, type TriangleList } from '../../scene/triangles.ts';
import type { Material, Scene } from '../../scene/types.ts';
import { reflectModule, structLayout } from '../wgsl/reflect.ts';
import { packEnvironment, type PackedEnvironment } from './environment-pack.ts';
import { packLights } from './light-pack.ts';
import { packMaterials, type PackedMaterials } from './material-pack.ts';
import { StructArray } from './struct-array.ts';
import type { TextureAtlas } from './texture-atlas.ts';

export { MATERIAL_ALPHA_MASK, MATERIAL_EMISSION_PANORAMA, NO_TEXTURE } from './material-pack.ts';

/** What a scene uses, each compiled out of the tracing pipelines where absent (gpu/kernel.ts). */
/** The static world's structures, by STATIC_ACCEL's value (ACCEL_* of shaders/scene/accel.wgsl). */
export const STATIC_ACCELS = ['bvh2', 'bvh4', 'cwbvh', 'grid'] as const;
export type StaticAccel = (typeof STATIC_ACCELS)[number];

export interface SceneFeatures {
  /** Triangles whose hits are filtered by coverage (alpha mask or blend). */
  readonly alphaMasks: boolean;
  /** Materials other than diffuse/emissive, or normal maps. */
  readonly generalMaterials: boolean;
  readonly punctualLights: boolean;
  /** An environment map or a sun. */
  readonly environment: boolean;
  /** Spheres or capsules among the primitives. */
  readonly analyticPrimitives: boolean;
  /** Moving instances: the two-level BVH (bvh/levels.ts). */
  readonly instances: boolean;
  /**
   * What the static world is traced through: its binary BVH, its BVH4 or compressed 8-wide BVH
   * (bvh/wide.ts), or its uniform grid (bvh/grid.ts). STATIC_ACCEL (shaders/scene/accel.wgsl).
   */
  readonly staticAccel: StaticAccel;
  /**
   * No traversal can hold more than SHALLOW_STACK_ENTRIES on its stack (no moving instances, and the
   * static tree at most that deep): the kernels use the shorter stack (shaders/scene/bvh.wgsl).
   */
  readonly shallowStack: boolean;
}

/** shaders/scene/bvh.wgsl's BVH_SHALLOW_STACK_SIZE: a traversal at depth d holds at most d entries. */
export const SHALLOW_STACK_ENTRIES = 32;

/** The group-0 resources, keyed by their WGSL variable names. */
export interface PackedScene {
  readonly scene_info: ArrayBuffer;
  readonly bvh_nodes: ArrayBuffer;
  readonly triangles_hot: ArrayBuffer;
  readonly triangles_shading: ArrayBuffer;
  readonly materials: ArrayBuffer;
  readonly light_slots: ArrayBuffer;
  readonly texture_refs: ArrayBuffer;
  readonly punctual_lights: ArrayBuffer;
  /** The Instance records (binding 16): the static world, then the moving instances. */
  readonly instances: ArrayBuffer;
  /**
   * triangle_attributes (binding 15): per leaf-order triangle, the world-space tangents of its three
   * vertices and its second uv set, as f32 texels of an rgba32uint texture; 1×1 when no material
   * needs them (see TRIANGLE_ATTRIBUTE_* in shaders/scene/types.wgsl).
   */
  readonly triangleAttributes: { readonly width: number; readonly height: number; readonly data: Float32Array };
  /** The pages of texture_atlas (sRGB colour) and texture_atlas_linear (data), bound as 2D array textures. */
  readonly atlas: TextureAtlas;
  readonly linearAtlas: TextureAtlas;
  readonly counts: {
    readonly triangles: number;
    readonly nodes: number;
    /** Slots of the light table (every light of every kind). */
    readonly lights: number;
    readonly emissiveTriangles: number;
    readonly punctualLights: number;
    readonly textures: number;
    readonly maskedTriangles: number;
    readonly spheres: number;
    readonly capsules: number;
    readonly emissiveSpheres: number;
    /** Instance records: 1 (the static world) plus the moving instances. */
    readonly instances: number;
  };
  readonly features: SceneFeatures;
  /** Σ of the light powers (the light table's normaliser). */
  readonly totalLightPower: number;
  /** What packing had to work around. */
  readonly warnings: readonly string[];
  /** Group 0 bindings 8–10: the environment's info, map and sampling CDFs. */
  readonly environment: PackedEnvironment;
  /** The packed materials and textures, kept so geometry can be packed again alone. */
  readonly packedMaterials: PackedMaterials;
  /** Where the levels' parts lie in the buffers (renderer/prepare.ts rewrites them in place). */
  readonly layout: PackedLayout;
  /** The emitters of the light table, kept so it can be rebuilt when moving emitters change power. */
  readonly lightList: LightList;
}

export function sceneLayouts() {
  const { defs } = reflectModule('scene/bindings');
  return {
    defs,
    sceneInfo: structLayout(defs, 'SceneInfo'),
    node: structLayout(defs, 'BvhNode'),
    hot: structLayout(defs, 'TriangleHot'),
    shading: structLayout(defs, 'TriangleShading'),
    material: structLayout(defs, 'Material'),
    lightSlot: structLayout(defs, 'LightSlot'),
    instance: structLayout(defs, 'Instance'),
    textureRef: structLayout(defs, 'TextureRef'),
  };
}

export const TRIANGLE_ALPHA_MASKED = 1;
/** PRIMITIVE_* kind bits of TriangleHot.flags (shaders/scene/types.wgsl), by scene/triangles.ts kind. */
export const PRIMITIVE_FLAGS: readonly number[] = [0, 256, 512];

/** Options of packing that depend on the device. */
export interface PackOptions {
  /** Largest 2D texture side the device allows (maxTextureDimension2D). */
  readonly maxTextureSide: number;
}

export function packScene(scene: Scene, triangles: TriangleList, bvh: Bvh, options: PackOptions = { maxTextureSide: 8192 }, levels?: SceneLevels, grid?: Grid | WideBvh): PackedScene {
  const packedMaterials = packMaterials(scene, sceneLayouts(), options.maxTextureSide);
  return packGeometry(scene, triangles, bvh, packedMaterials, undefined, levels, grid);
}

/**
 * One stored run of primitives with its BVH: the static world (world space, indexing the scene's
 * flattened list) or a moving mesh's bottom level (object space, flattened from one identity instance
 * of the mesh: `scene` is that one-instance scene).
 */
interface PrimitivePart {
  readonly scene: Scene;
  readonly triangles: TriangleList;
  readonly bvh: Bvh;
  /** Whether its emitters go into the light table as they are (the static world's, in world space). */
  readonly worldLights: boolean;
}

/** Where each part of the two-level layout lies in bvh_nodes and the primitive arrays. */
export interface PackedLayout {
  /** First node and first leaf-order primitive of each moving mesh's bottom level, by mesh index. */
  readonly meshes: ReadonlyMap<number, { readonly nodeBase: number; readonly nodeCount: number; readonly leafBase: number; readonly leafCount: number }>;
  /** The top level's slots at the end of bvh_nodes (rewritten whenever an instance moves). */
  readonly tlasBase: number;
  readonly tlasCapacity: number;
  /** The static world's grid (packGrid) or wide tree (bvh/wide.ts packWide) after the top level, when the scene is traced through one; else 0. */
  readonly gridBase: number;
}

/**
 * Everything that depends on where triangles are: nodes, triangle records, the light table and the
 * scene info, around materials already packed. After instances move (renderer/prepare.ts
 * updateGeometry) only this, or parts of it, runs again; the textures stay as they are.
 *
 * With `levels` (a scene with moving instances) the arrays hold the static world, then each moving
 * mesh's object-space primitives and bottom level, then the top level (bvh/levels.ts).
 */
export function packGeometry(scene: Scene, triangles: TriangleList, bvh: Bvh, packedMaterials: PackedMaterials, packedEnvironment?: PackedEnvironment, levels?: SceneLevels, accel?: Grid | WideBvh): PackedScene {
  const layouts = sceneLayouts();
  const parts: PrimitivePart[] = [{ scene, triangles, bvh, worldLights: true }];
  for (const [m, blas] of levels?.blas ?? []) parts.push({ scene: meshScene(scene, m), triangles: blas.triangles, bvh: blas.bvh, worldLights: false });
  const tlasCapacityValue = levels ? tlasCapacity(levels.dynamic.length + 1) : 0;
  const treeTotal = parts.reduce((n, p) => n + p.bvh.nodeCount, 0) + tlasCapacityValue;
  // The static world's grid or wide tree: `grid` is whichever it is traced through.
  const grid = accel && !('layout' in accel) ? accel : undefined, wide = accel && 'layout' in accel ? accel : undefined;
  const gridWords = grid ? packGrid(grid, treeTotal, layouts.node.strideWords) : wide ? packWide(wide, treeTotal, layouts.node.strideWords) : undefined;
  const nodeTotal = treeTotal + (gridWords ? gridWords.length / layouts.node.strideWords : 0);
  const primTotal = parts.reduce((n, p) => n + p.bvh.triIndices.length, 0);

  const nodes = new StructArray(layouts.node, Math.max(nodeTotal, 1));
  if (gridWords) nodes.u32.set(gridWords, treeTotal * layouts.node.strideWords);
  const hot = new StructArray(layouts.hot, Math.max(primTotal, 1));
  const shading = new StructArray(layouts.shading, Math.max(primTotal, 1));
  const lights: LightList = { leaves: [], powers: [], instances: [] };
  const warnings: string[] = [];
  let maskedTriangles = 0, emissiveSpheres = 0, emissiveCapsules = 0;
  const meshes = new Map<number, { nodeBase: number; nodeCount: number; leafBase: number; leafCount: number }>();
  let nodeBase = 0, leafBase = 0;
  parts.forEach((part, i) => {
    writeNodes(nodes, part.bvh, nodeBase, nodeBase, leafBase);
    const c = writePrimitives(part, packedMaterials, hot, shading, leafBase, part.worldLights ? lights : undefined);
    maskedTriangles += c.masked;
    if (part.worldLights) {
      emissiveSpheres += c.emissiveSpheres;
      emissiveCapsules += c.emissiveCapsules;
    }
    if (i > 0) meshes.set(part.scene.instances[0]!.mesh, { nodeBase, nodeCount: part.bvh.nodeCount, leafBase, leafCount: part.bvh.triIndices.length });
    nodeBase += part.bvh.nodeCount;
    leafBase += part.bvh.triIndices.length;
  });
  const layout: PackedLayout = { meshes, tlasBase: nodeBase, tlasCapacity: tlasCapacityValue, gridBase: accel ? treeTotal : 0 };
  if (levels) {
    writeTlasNodes(nodes, levels.tlas, layout.tlasBase, layout.tlasBase);
    const dynamic = dynamicLights(scene, triangles, levels, layout, packedMaterials);
    // Appended in a loop: push(...list) overflows the call stack once a scene has ~100k moving emitters.
    for (let i = 0; i < dynamic.leaves.length; i++) lights.leaves.push(dynamic.leaves[i]!);
    for (let i = 0; i < dynamic.powers.length; i++) lights.powers.push(dynamic.powers[i]!);
    for (let i = 0; i < dynamic.instances.length; i++) lights.instances.push(dynamic.instances[i]!);
    emissiveSpheres += dynamic.spheres;
  }
  if (emissiveCapsules > 0) {
    warnings.push(`${emissiveCapsules} emissive capsule(s) are not sampled as lights: only rays that happen to hit them find their light (unbiased, but noisy)`);
  }

  const triangleAttributes = packTriangleAttributes(parts, primTotal, packedMaterials.needsVertexAttributes);
  const environment = packedEnvironment ?? packEnvironment(scene.environment ?? { kind: 'none' });
  const packedLights = packSceneLights(scene, bvh, levels, lights, environment, layouts);
  const info = sceneInfo(layouts, primTotal, nodeTotal, packedLights, levels ? layout.tlasBase : 0, levels ? levels.dynamic.length + 1 : 1, bvh.triIndices.length === 0, layout.gridBase);

  return {
    scene_info: info,
    bvh_nodes: nodes.bytes,
    triangles_hot: hot.bytes,
    triangles_shading: shading.bytes,
    materials: packedMaterials.materials,
    light_slots: packedLights.lightSlots,
    texture_refs: packedMaterials.textureRefs,
    punctual_lights: packedLights.punctualLights,
    instances: packInstances(scene, levels, layout, packedMaterials, new Map()),
    triangleAttributes,
    atlas: packedMaterials.atlas,
    linearAtlas: packedMaterials.linearAtlas,
    counts: {
      triangles: primTotal,
      nodes: nodeTotal,
      lights: packedLights.slotCount,
      emissiveTriangles: lights.leaves.length,
      punctualLights: packedLights.punctualCount,
      textures: (scene.textures ?? []).length,
      maskedTriangles,
      spheres: triangles.kindCounts.sphere,
      capsules: triangles.kindCounts.capsule,
      emissiveSpheres,
      instances: levels ? levels.dynamic.length + 1 : 1,
    },
    features: {
      alphaMasks: maskedTriangles > 0 || (levels?.dynamic.some((ii) => instanceHasFilter(scene, ii, packedMaterials)) ?? false),
      generalMaterials: packedMaterials.general,
      punctualLights: packedLights.punctualCount > 0,
      environment: packedLights.environmentSelectPmf > 0 || packedLights.sunSelectPmf > 0,
      analyticPrimitives: triangles.kindCounts.sphere + triangles.kindCounts.capsule > 0,
      instances: levels !== undefined,
      staticAccel: grid !== undefined ? 'grid' : (wide?.layout ?? 'bvh2'),
      shallowStack: levels === undefined && bvh.stats.maxDepth <= SHALLOW_STACK_ENTRIES,
    },
    totalLightPower: packedLights.totalPower,
    warnings: [...packedMaterials.warnings, ...packedLights.warnings, ...warnings],
    packedMaterials,
    environment,
    layout,
    lightList: lights,
  };
}

/** Emissive primitives for the light table: leaf-order index, power, instance. */
export interface LightList {
  readonly leaves: number[];
  readonly powers: number[];
  readonly instances: number[];
}

function instanceHasFilter(scene: Scene, ii: number, packedMaterials: PackedMaterials): boolean {
  const m = scene.instances[ii]!.material;
  return m !== undefined && packedMaterials.hasHitFilter[m] === true;
}

/** The light table and punctual lights of the scene, from its emitters and environment. */
function packSceneLights(scene: Scene, bvh: Bvh, levels: SceneLevels | undefined, lights: LightList, environment: PackedEnvironment, layouts: ReturnType<typeof sceneLayouts>) {
  // The scene's radius: the static world's box with every instance's.
  let b: ArrayLike<number> = bvh.bounds;
  if (levels) {
    const box = [Infinity, Infinity, Infinity, -Infinity, -Infinity, -Infinity];
    for (let i = 0; i < levels.boxes.length; i += 6) {
      if (!(levels.boxes[i]! <= levels.boxes[i + 3]!)) continue;
      for (let c = 0; c < 3; c++) {
        box[c] = Math.min(box[c]!, levels.boxes[i + c]!);
        box[c + 3] = Math.max(box[c + 3]!, levels.boxes[i + 3 + c]!);
      }
    }
    b = box;
  }
  const sceneRadius = b[0]! <= b[3]! ? 0.5 * Math.hypot(b[3]! - b[0]!, b[4]! - b[1]!, b[5]! - b[2]!) : 1;
  // Lights at infinity: the flux through a disk of the scene's radius (irradiance × πR²), with the
  // irradiance of a uniform environment of mean luminance L being πL.
  const disk = Math.PI * sceneRadius * sceneRadius;
  return packLights(
    {
      triangles: lights.leaves,
      trianglePowers: lights.powers,
      triangleInstances: lights.instances,
      punctual: scene.lights ?? [],
      environmentPower: Math.PI * environment.meanLuminance * disk,
      sunPower: environment.sunIrradiance * disk,
      sceneRadius,
    },
    layouts,
    layouts.defs,
  );
}

function sceneInfo(layouts: ReturnType<typeof sceneLayouts>, primitives: number, nodeCount: number, lights: ReturnType<typeof packLights>, tlasRoot: number, instanceCount: number, staticWorldEmpty: boolean, gridBase: number): ArrayBuffer {
  const info = new StructArray(layouts.sceneInfo, 1);
  info.u32Field('triangle_count')(0, primitives);
  info.u32Field('node_count')(0, nodeCount);
  info.u32Field('light_count')(0, lights.slotCount);
  info.f32Field('total_light_power')(0, lights.totalPower);
  info.f32Field('environment_select_pmf')(0, lights.environmentSelectPmf);
  info.f32Field('sun_select_pmf')(0, lights.sunSelectPmf);
  info.u32Field('tlas_root')(0, tlasRoot);
  info.u32Field('instance_count')(0, instanceCount);
  info.u32Field('static_world_empty')(0, staticWorldEmpty ? 1 : 0);
  info.u32Field('grid_base')(0, gridBase);
  return info.bytes;
}

/** The light table again, around the same emitters with the moving instances' powers recomputed (they moved, scaled or changed material). */
export function repackLights(scene: Scene, triangles: TriangleList, bvh: Bvh, levels: SceneLevels | undefined, packed: PackedScene, staticLights?: LightList): Pick<PackedScene, 'scene_info' | 'light_slots' | 'punctual_lights' | 'totalLightPower' | 'lightList' | 'counts'> {
  const layouts = sceneLayouts();
  const staticCount = packed.lightList.instances.filter((g) => g === 0).length;
  const own = staticLights ?? { leaves: packed.lightList.leaves.slice(0, staticCount), powers: packed.lightList.powers.slice(0, staticCount), instances: packed.lightList.instances.slice(0, staticCount) };
  const dynamic = levels ? dynamicLights(scene, triangles, levels, packed.layout, packed.packedMaterials) : { leaves: [], powers: [], instances: [], spheres: 0 };
  const lights: LightList = {
    leaves: [...own.leaves, ...dynamic.leaves],
    powers: [...own.powers, ...dynamic.powers],
    instances: [...own.instances, ...dynamic.instances],
  };
  const packedLights = packSceneLights(scene, bvh, levels, lights, packed.environment, layouts);
  const spheres = own.leaves.filter((leaf) => triangles.kinds[bvh.triIndices[leaf]!] === PRIMITIVE_KIND.sphere).length + dynamic.spheres;
  return {
    scene_info: sceneInfo(layouts, packed.counts.triangles, packed.counts.nodes, packedLights, levels ? packed.layout.tlasBase : 0, levels ? levels.dynamic.length + 1 : 1, bvh.triIndices.length === 0, packed.layout.gridBase),
    light_slots: packedLights.lightSlots,
    punctual_lights: packedLights.punctualLights,
    totalLightPower: packedLights.totalPower,
    lightList: lights,
    counts: { ...packed.counts, lights: packedLights.slotCount, emissiveTriangles: lights.leaves.length, emissiveSpheres: spheres },
  };
}

/** A material's power per unit of emitting area (luminance; both faces for two-sided emitters), as the light table weighs it. */
export function emitterStrength(material: Material, emissionMean: number): number {
  return luminance(material.emission) * emissionMean * (material.twoSidedEmission ? 2 : 1);
}

/**
 * The light table after emission edits, without walking the geometry: the static world's emitters
 * keep their order and take their materials' new strengths, powers computed as packing computes
 * them (so the table is the one a fresh preparation makes), those gone dark dropped; the moving
 * instances' are recomputed. Undefined when an edited material starts to emit (its primitives are
 * not in the table yet: pack the geometry again).
 */
export function rescaleLights(scene: Scene, triangles: TriangleList, bvh: Bvh, levels: SceneLevels | undefined, packed: PackedScene, before: readonly Material[], edited: Iterable<number>): ReturnType<typeof repackLights> | undefined {
  const mean = packed.packedMaterials.emissionMean;
  const changed = new Set<number>();
  for (const m of edited) {
    if (!(emitterStrength(before[m]!, mean[m]!) > 0) && emitterStrength(scene.materials[m]!, mean[m]!) > 0) return undefined;
    changed.add(m);
  }
  const { leaves, powers, instances } = packed.lightList;
  const kept: LightList = { leaves: [], powers: [], instances: [] };
  const p = triangles.positions;
  for (let i = 0; i < instances.length && instances[i] === 0; i++) {
    const t = bvh.triIndices[leaves[i]!]!;
    const m = triangles.materialIds[t]!;
    let power = powers[i]!;
    if (changed.has(m)) {
      const strength = emitterStrength(scene.materials[m]!, mean[m]!);
      const o = t * 9;
      power = triangles.kinds[t] === PRIMITIVE_KIND.sphere ? strength * (4 * Math.PI * p[o + 3]! * p[o + 3]!) : strength * 0.5 * triangleTwiceArea(p, o);
    }
    if (!(power > 0)) continue;
    kept.leaves.push(leaves[i]!);
    kept.powers.push(power);
    kept.instances.push(0);
  }
  return repackLights(scene, triangles, bvh, levels, packed, kept);
}

/** |(v1 − v0) × (v2 − v0)| of the triangle at float `o` of `p`, as packing computes it. */
function triangleTwiceArea(p: Float32Array, o: number): number {
  const ax = p[o]!, ay = p[o + 1]!, az = p[o + 2]!;
  const e1x = p[o + 3]! - ax, e1y = p[o + 4]! - ay, e1z = p[o + 5]! - az;
  const e2x = p[o + 6]! - ax, e2y = p[o + 7]! - ay, e2z = p[o + 8]! - az;
  return Math.hypot(e1y * e2z - e1z * e2y, e1z * e2x - e1x * e2z, e1x * e2y - e1y * e2x);
}

/**
 * The static world's grid (bvh/grid.ts) as node-sized records of u32 words, to live from record
 * `base` of bvh_nodes (shaders/scene/grid.wgsl reads it; no binding of its own: the real-time passes
 * use every storage buffer a browser gives a stage). `strideWords` words a record (8):
 * - record base: lo xyz (f32 bits), dims x, hi xyz (f32 bits), dims y — a BvhNode's aabb_min,
 *   left_first, aabb_max, tri_count;
 * - record base + 1: cell size xyz (f32 bits), dims z, the first word of the cell ranges, the first
 *   word of the items, 0, 0 (word indices from record 0 of bvh_nodes);
 * - the cell ranges: per cell its first item and its count, two words, four cells a record;
 * - the items: leaf positions of the static world (records of triangles_hot), one word each.
 */
export function packGrid(grid: Grid, base: number, strideWords: number): Uint32Array {
  const cells = grid.cellStart.length;
  const cellRecords = Math.ceil((2 * cells) / strideWords), itemRecords = Math.max(1, Math.ceil(grid.items.length / strideWords));
  const words = new Uint32Array((2 + cellRecords + itemRecords) * strideWords);
  const f32 = new Float32Array(words.buffer);
  const cellsWord = (base + 2) * strideWords, itemsWord = (base + 2 + cellRecords) * strideWords;
  f32.set(grid.lo, 0);
  words[3] = grid.dims[0];
  f32.set(grid.hi, 4);
  words[7] = grid.dims[1];
  f32.set(grid.cellSize, 8);
  words[11] = grid.dims[2];
  words[12] = cellsWord;
  words[13] = itemsWord;
  for (let c = 0; c < cells; c++) {
    words[2 * strideWords + 2 * c] = grid.cellStart[c]!;
    words[2 * strideWords + 2 * c + 1] = grid.cellCount[c]!;
  }
  words.set(grid.items, (2 + cellRecords) * strideWords);
  return words;
}

/**
 * A BVH's nodes written from record `at`, for a tree living at `nodeBase` of bvh_nodes: child links
 * offset by nodeBase, leaf ranges by leafBase.
 */
function writeNodes(nodes: StructArray, bvh: Bvh, at: number, nodeBase: number, leafBase: number): void {
  const min = nodes.vec3('aabb_min'), max = nodes.vec3('aabb_max');
  const leftFirst = nodes.u32Field('left_first'), count = nodes.u32Field('tri_count');
  const b = bvh.bounds;
  for (let i = 0; i < bvh.nodeCount; i++) {
    const o = at + i;
    min(o, b[i * 6]!, b[i * 6 + 1]!, b[i * 6 + 2]!);
    max(o, b[i * 6 + 3]!, b[i * 6 + 4]!, b[i * 6 + 5]!);
    const leaf = bvh.triCount[i]! > 0;
    leftFirst(o, bvh.leftFirst[i]! + (leaf ? leafBase : i === 1 ? 0 : nodeBase));
    count(o, bvh.triCount[i]!);
  }
}

/** The top level written from record `at`, living at `base` of bvh_nodes: interior links offset, leaves naming their instance. */
function writeTlasNodes(nodes: StructArray, tlas: Tlas, at: number, base: number): void {
  const min = nodes.vec3('aabb_min'), max = nodes.vec3('aabb_max');
  const leftFirst = nodes.u32Field('left_first'), count = nodes.u32Field('tri_count');
  const b = tlas.bounds;
  for (let i = 0; i < tlas.nodeCount; i++) {
    const o = at + i;
    min(o, b[i * 6]!, b[i * 6 + 1]!, b[i * 6 + 2]!);
    max(o, b[i * 6 + 3]!, b[i * 6 + 4]!, b[i * 6 + 5]!);
    const leaf = tlas.triCount[i]! > 0;
    leftFirst(o, tlas.leftFirst[i]! + (leaf || i === 1 ? 0 : base));
    count(o, tlas.triCount[i]!);
  }
}

/** The top level's node records alone (the bytes of bvh_nodes from `layout.tlasBase` on). */
export function packTlasNodes(tlas: Tlas, layout: PackedLayout): ArrayBuffer {
  const nodes = new StructArray(sceneLayouts().node, layout.tlasCapacity);
  writeTlasNodes(nodes, tlas, 0, layout.tlasBase);
  return nodes.bytes;
}

/** One moving mesh's bottom level after it morphed: its node and primitive records, to write at the layout's offsets. */
export function packMeshPart(scene: Scene, mesh: number, blas: { readonly triangles: TriangleList; readonly bvh: Bvh }, layout: PackedLayout, packedMaterials: PackedMaterials): { nodes: ArrayBuffer; hot: ArrayBuffer; shading: ArrayBuffer } {
  const at = layout.meshes.get(mesh);
  if (!at) throw new Error(`packMeshPart: mesh ${mesh} has no bottom level`);
  const layouts = sceneLayouts();
  const nodes = new StructArray(layouts.node, at.nodeCount);
  writeNodes(nodes, blas.bvh, 0, at.nodeBase, at.leafBase);
  const hot = new StructArray(layouts.hot, at.leafCount);
  const shading = new StructArray(layouts.shading, at.leafCount);
  writePrimitives({ scene: meshScene(scene, mesh), triangles: blas.triangles, bvh: blas.bvh, worldLights: false }, packedMaterials, hot, shading, 0, undefined, at.leafBase);
  return { nodes: nodes.bytes, hot: hot.bytes, shading: shading.bytes };
}

/**
 * The Instance records (shaders/scene/types.wgsl): the static world, then each moving instance with
 * its transforms, the previous frame's (`previous`, by scene instance index; the current where absent).
 */
export function packInstances(scene: Scene, levels: SceneLevels | undefined, layout: PackedLayout, packedMaterials: PackedMaterials, previous: ReadonlyMap<number, Mat4>): ArrayBuffer {
  const layouts = sceneLayouts();
  const layoutOf = structLayout(layouts.defs, 'Instance');
  const count = levels ? levels.dynamic.length + 1 : 1;
  const records = new StructArray(layoutOf, count);
  const rows = (prefix: string) => [0, 1, 2].map((r) => records.vec4(`${prefix}_${r}`));
  const w = rows('world_from_object'), o = rows('object_from_world'), p = rows('previous');
  const blasRoot = records.u32Field('blas_root'), sourceBase = records.u32Field('source_base'), material = records.u32Field('material'), flags = records.u32Field('flags');
  const put = (set: ((i: number, x: number, y: number, z: number, w: number) => void)[], i: number, m: Mat4) => {
    for (let r = 0; r < 3; r++) set[r]!(i, m[r]!, m[4 + r]!, m[8 + r]!, m[12 + r]!);
  };
  put(w, 0, IDENTITY);
  put(o, 0, IDENTITY);
  put(p, 0, IDENTITY);
  blasRoot(0, 0);
  sourceBase(0, 0);
  material(0, NO_MATERIAL);
  flags(0, 0);
  levels?.dynamic.forEach((ii, k) => {
    const g = k + 1;
    const inst = scene.instances[ii]!;
    const m = inst.worldFromObject;
    put(w, g, m);
    put(o, g, invertAffine(m));
    put(p, g, previous.get(ii) ?? m);
    blasRoot(g, layout.meshes.get(inst.mesh)!.nodeBase);
    sourceBase(g, sourceBaseOf(scene, ii));
    material(g, inst.material ?? NO_MATERIAL);
    let f = determinant3(m) < 0 ? INSTANCE_MIRRORED : 0;
    if (instanceHasFilter(scene, ii, packedMaterials)) f |= INSTANCE_ALPHA_FILTER;
    flags(g, f);
  });
  return records.bytes;
}

export const NO_MATERIAL = 0xffffffff;
/** How instance_data stores the records (INSTANCE_TEXELS, INSTANCES_PER_ROW in shaders/scene/types.wgsl): 16-byte texels, a row of 128 records is 20,480 bytes, a multiple of 256 as texture writes require. */
export const INSTANCE_TEXELS = 10;
export const INSTANCES_PER_ROW = 128;
export const INSTANCE_MIRRORED = 1;
export const INSTANCE_ALPHA_FILTER = 2;

/** The first primitive of scene instance `ii` in the flattened list (scene/triangles.ts order). */
function sourceBaseOf(scene: Scene, ii: number): number {
  let n = 0;
  for (let i = 0; i < ii; i++) n += meshPrimitiveCount(scene.meshes[scene.instances[i]!.mesh]!);
  return n;
}

/** The emitters of the moving instances: each emissive primitive of their meshes, with its world power. */
function dynamicLights(scene: Scene, triangles: TriangleList, levels: SceneLevels, layout: PackedLayout, packedMaterials: PackedMaterials): LightList & { spheres: number } {
  const out = { leaves: [] as number[], powers: [] as number[], instances: [] as number[], spheres: 0 };
  levels.dynamic.forEach((ii, k) => {
    const inst = scene.instances[ii]!;
    const blas = levels.blas.get(inst.mesh)!;
    const at = layout.meshes.get(inst.mesh)!;
    const list = blas.triangles;
    let leafOf: Uint32Array | undefined;
    const first = triangles.instanceFirstTriangle[ii]!;
    for (let t = 0; t < list.count; t++) {
      const m = inst.material ?? list.materialIds[t]!;
      const mat = scene.materials[m]!;
      const e = emitterStrength(mat, packedMaterials.emissionMean[m]!);
      if (!(e > 0)) continue;
      const kind = list.kinds[t]!;
      if (kind === PRIMITIVE_KIND.capsule) continue;
      // World area from the instance's world-space copy in the scene's flattened list.
      const o = (first + t) * 9, q = triangles.positions;
      let area: number;
      if (kind === PRIMITIVE_KIND.sphere) {
        area = 4 * Math.PI * q[o + 3]! * q[o + 3]!;
        out.spheres++;
      } else {
        const e1x = q[o + 3]! - q[o]!, e1y = q[o + 4]! - q[o + 1]!, e1z = q[o + 5]! - q[o + 2]!;
        const e2x = q[o + 6]! - q[o]!, e2y = q[o + 7]! - q[o + 1]!, e2z = q[o + 8]! - q[o + 2]!;
        area = 0.5 * Math.hypot(e1y * e2z - e1z * e2y, e1z * e2x - e1x * e2z, e1x * e2y - e1y * e2x);
      }
      if (!(area > 0)) continue;
      if (!leafOf) {
        leafOf = new Uint32Array(list.count);
        blas.bvh.triIndices.forEach((src, leaf) => (leafOf![src] = leaf));
      }
      out.leaves.push(at.leafBase + leafOf[t]!);
      out.powers.push(e * area);
      out.instances.push(k + 1);
    }
  });
  return out;
}

/** Counts of what writePrimitives wrote. */
interface PrimitiveCounts {
  readonly masked: number;
  readonly emissiveSpheres: number;
  readonly emissiveCapsules: number;
}

/**
 * The hot and shading records of a part's primitives in its leaf order, at `leafBase` of `hot` and
 * `shading` (source indices index the part's own list; `lightLeafBase` is where the records will live
 * when they are written elsewhere first). Emitters go to `lights` when given.
 */
function writePrimitives(part: PrimitivePart, packedMaterials: PackedMaterials, hot: StructArray, shading: StructArray, leafBase: number, lights: LightList | undefined, lightLeafBase = leafBase): PrimitiveCounts {
  const { scene, triangles, bvh } = part;
  // Normals go to world space with each instance's normal matrix (inverse transpose).
  const normalMatrices = scene.instances.map((inst) => normalMatrix(inst.worldFromObject));
  let masked = 0, emissiveSpheres = 0, emissiveCapsules = 0;
  const v0 = hot.vec3('v0'), e1 = hot.vec3('e1'), e2 = hot.vec3('e2'), flags = hot.u32Field('flags');
  const normals = [shading.vec3('n0'), shading.vec3('n1'), shading.vec3('n2')] as const;
  const uvs = [shading.vec2('uv0'), shading.vec2('uv1'), shading.vec2('uv2')] as const;
  const material = shading.u32Field('material'), sourceIndex = shading.u32Field('source_index');
  const p = triangles.positions;
  const n = bvh.triIndices.length;
  for (let j = 0; j < n; j++) {
    const leaf = leafBase + j;
    const t = bvh.triIndices[j]!;
    const o = t * 9;
    const kind = triangles.kinds[t]!;
    const m = triangles.materialIds[t]!;
    const mat = scene.materials[m]!;
    material(leaf, m);
    sourceIndex(leaf, t);
    let flagBits = PRIMITIVE_FLAGS[kind]!;
    if (packedMaterials.hasHitFilter[m]) {
      flagBits |= TRIANGLE_ALPHA_MASKED;
      masked++;
    }
    flags(leaf, flagBits);
    if (kind !== PRIMITIVE_KIND.triangle) {
      // Analytic: the record of shaders/scene/types.wgsl TriangleHot. The shading uvs (0,0), (1,0),
      // (0,1) make triangle_uv(prim, hit uv) return the hit's analytic uv unchanged.
      v0(leaf, p[o]!, p[o + 1]!, p[o + 2]!);
      uvs[1](leaf, 1, 0);
      uvs[2](leaf, 0, 1);
      let area: number;
      if (kind === PRIMITIVE_KIND.sphere) {
        const r = p[o + 3]!;
        e1(leaf, r, 0, 0);
        area = 4 * Math.PI * r * r;
      } else {
        const r = p[o + 6]!;
        const ax = p[o + 3]! - p[o]!, ay = p[o + 4]! - p[o + 1]!, az = p[o + 5]! - p[o + 2]!;
        e1(leaf, ax, ay, az);
        e2(leaf, r, 0, 0);
        area = 2 * Math.PI * r * Math.hypot(ax, ay, az) + 4 * Math.PI * r * r;
      }
      const power = emitterStrength(mat, packedMaterials.emissionMean[m]!) * area;
      if (power > 0 && kind === PRIMITIVE_KIND.sphere) {
        lights?.leaves.push(lightLeafBase + j);
        lights?.powers.push(power);
        lights?.instances.push(0);
        emissiveSpheres++;
      } else if (power > 0) {
        emissiveCapsules++;
      }
      continue;
    }
    const ax = p[o]!, ay = p[o + 1]!, az = p[o + 2]!;
    const e1x = p[o + 3]! - ax, e1y = p[o + 4]! - ay, e1z = p[o + 5]! - az;
    const e2x = p[o + 6]! - ax, e2y = p[o + 7]! - ay, e2z = p[o + 8]! - az;
    v0(leaf, ax, ay, az);
    e1(leaf, e1x, e1y, e1z);
    e2(leaf, e2x, e2y, e2z);

    const instanceIndex = triangles.instanceIds[t]!;
    const mesh = scene.meshes[scene.instances[instanceIndex]!.mesh]!;
    const nm = normalMatrices[instanceIndex]!;
    const k = triangles.meshTriangleIds[t]!;
    const swapped = triangles.swapped[t] === 1;
    // Geometric normal e1 × e2, for meshes without normals and for the light's area.
    const cx = e1y * e2z - e1z * e2y, cy = e1z * e2x - e1x * e2z, cz = e1x * e2y - e1y * e2x;
    const twiceArea = Math.hypot(cx, cy, cz);
    for (let c = 0; c < 3; c++) {
      const vi = mesh.indices[k * 3 + (swapped && c > 0 ? 3 - c : c)]!;
      if (mesh.normals) {
        const x = mesh.normals[vi * 3]!, y = mesh.normals[vi * 3 + 1]!, z = mesh.normals[vi * 3 + 2]!;
        const wx = nm[0]! * x + nm[3]! * y + nm[6]! * z, wy = nm[1]! * x + nm[4]! * y + nm[7]! * z, wz = nm[2]! * x + nm[5]! * y + nm[8]! * z;
        const len = Math.hypot(wx, wy, wz);
        if (len > 0) normals[c]!(leaf, wx / len, wy / len, wz / len);
      } else if (twiceArea > 0) {
        normals[c]!(leaf, cx / twiceArea, cy / twiceArea, cz / twiceArea);
      }
      if (mesh.uvs) uvs[c]!(leaf, mesh.uvs[vi * 2]!, mesh.uvs[vi * 2 + 1]!);
    }

    // Power in the luminance sense, as lights.wgsl light_selection_pmf computes it.
    const power = emitterStrength(mat, packedMaterials.emissionMean[m]!) * 0.5 * twiceArea;
    if (power > 0 && lights) {
      lights.leaves.push(lightLeafBase + j);
      lights.powers.push(power);
      lights.instances.push(0);
    }
  }
  return { masked, emissiveSpheres, emissiveCapsules };
}

/** Texels per triangle and triangles per row of triangle_attributes (TRIANGLE_ATTRIBUTE_* in shaders/scene/types.wgsl). */
export const TRIANGLE_ATTRIBUTE_TEXELS = 5;
export const TRIANGLE_ATTRIBUTE_TRIANGLES_PER_ROW = 819;

/**
 * Tangents (transformed like directions, their handedness flipped by a mirroring instance) and the
 * second uv set per vertex of every leaf-order triangle of every part, where a material needs them.
 */
function packTriangleAttributes(parts: readonly PrimitivePart[], count: number, needed: boolean): PackedScene['triangleAttributes'] {
  if (!needed || count === 0) return { width: 1, height: 1, data: new Float32Array(4) };
  const perRow = TRIANGLE_ATTRIBUTE_TRIANGLES_PER_ROW, texels = TRIANGLE_ATTRIBUTE_TEXELS;
  const width = perRow * texels, height = Math.ceil(count / perRow);
  const data = new Float32Array(width * height * 4);
  let leafBase = 0;
  for (const { scene, triangles, bvh } of parts) {
    const mirrors = scene.instances.map((inst) => (determinant3(inst.worldFromObject) < 0 ? -1 : 1));
    for (let j = 0; j < bvh.triIndices.length; j++) {
      const leaf = leafBase + j;
      const t = bvh.triIndices[j]!;
      const base = (Math.floor(leaf / perRow) * width + (leaf % perRow) * texels) * 4;
      if (triangles.kinds[t] !== PRIMITIVE_KIND.triangle) {
        // Analytic: no tangents; the second uv set is the first (as triangle_uv1 interpolates it).
        data.set([0, 0, 1, 0, 0, 1, 0, 0], base + 12);
        continue;
      }
      const ii = triangles.instanceIds[t]!;
      const inst = scene.instances[ii]!;
      const mesh = scene.meshes[inst.mesh]!;
      const m = inst.worldFromObject;
      const k = triangles.meshTriangleIds[t]!;
      const swapped = triangles.swapped[t] === 1;
      for (let c = 0; c < 3; c++) {
        const vi = mesh.indices[k * 3 + (swapped && c > 0 ? 3 - c : c)]!;
        if (mesh.tangents) {
          const x = mesh.tangents[vi * 4]!, y = mesh.tangents[vi * 4 + 1]!, z = mesh.tangents[vi * 4 + 2]!, w = mesh.tangents[vi * 4 + 3]!;
          const wx = m[0]! * x + m[4]! * y + m[8]! * z, wy = m[1]! * x + m[5]! * y + m[9]! * z, wz = m[2]! * x + m[6]! * y + m[10]! * z;
          const len = Math.hypot(wx, wy, wz);
          if (len > 0) data.set([wx / len, wy / len, wz / len, (w < 0 ? -1 : 1) * mirrors[ii]!], base + c * 4);
        }
        if (mesh.uvs1) {
          const o = base + 12 + c * 2;
          data[o] = mesh.uvs1[vi * 2]!;
          data[o + 1] = mesh.uvs1[vi * 2 + 1]!;
        }
      }
    }
    leafBase += bvh.triIndices.length;
  }
  return { width, height, data };
}
