/**
 * Scene + BVH → the byte arrays of bind group 0 (shaders/scene/bindings.wgsl), pure CPU. Triangles
 * are reordered into BVH leaf order and split into a hot array (what traversal reads: a vertex and
 * two edges) and a cold one (world-space normals, uvs, material, read once per closest hit).
 * Materials and textures are packed by material-pack.ts, lights by light-pack.ts. Every layout comes
 * from reflection. What the scene uses (alpha tests, non-diffuse materials, lights of each kind)
 * becomes `features`, from which the pipelines' override constants are chosen.
 */
import type { Bvh } from '../../bvh/types.ts';
import { determinant3, normalMatrix } from '../../math/mat4.ts';
import { luminance } from '../../math/vec3.ts';
import { PRIMITIVE_KIND, type TriangleList } from '../../scene/triangles.ts';
import type { Scene } from '../../scene/types.ts';
import { reflectModule, structLayout } from '../wgsl/reflect.ts';
import { packEnvironment, type PackedEnvironment } from './environment-pack.ts';
import { packLights } from './light-pack.ts';
import { packMaterials, type PackedMaterials } from './material-pack.ts';
import { StructArray } from './struct-array.ts';
import type { TextureAtlas } from './texture-atlas.ts';

export { MATERIAL_ALPHA_MASK, MATERIAL_EMISSION_PANORAMA, NO_TEXTURE } from './material-pack.ts';

/** What a scene uses, each compiled out of the tracing pipelines where absent (gpu/kernel.ts). */
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
}

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

export function packScene(scene: Scene, triangles: TriangleList, bvh: Bvh, options: PackOptions = { maxTextureSide: 8192 }): PackedScene {
  const packedMaterials = packMaterials(scene, sceneLayouts(), options.maxTextureSide);
  return packGeometry(scene, triangles, bvh, packedMaterials);
}

/**
 * Everything that depends on where triangles are: nodes, triangle records, the light table and the
 * scene info, around materials already packed. After instances move (renderer/prepare.ts
 * moveInstances) only this runs again; the textures stay as they are.
 */
export function packGeometry(scene: Scene, triangles: TriangleList, bvh: Bvh, packedMaterials: PackedMaterials, packedEnvironment?: PackedEnvironment): PackedScene {
  const layouts = sceneLayouts();
  const n = triangles.count;

  const nodes = new StructArray(layouts.node, bvh.nodeCount);
  {
    const min = nodes.vec3('aabb_min'), max = nodes.vec3('aabb_max');
    const leftFirst = nodes.u32Field('left_first'), count = nodes.u32Field('tri_count');
    const b = bvh.bounds;
    for (let i = 0; i < bvh.nodeCount; i++) {
      min(i, b[i * 6]!, b[i * 6 + 1]!, b[i * 6 + 2]!);
      max(i, b[i * 6 + 3]!, b[i * 6 + 4]!, b[i * 6 + 5]!);
      leftFirst(i, bvh.leftFirst[i]!);
      count(i, bvh.triCount[i]!);
    }
  }

  // Normals go to world space with each instance's normal matrix (inverse transpose).
  const normalMatrices = scene.instances.map((inst) => normalMatrix(inst.worldFromObject));
  const hot = new StructArray(layouts.hot, n);
  const shading = new StructArray(layouts.shading, n);
  const lightTriangles: number[] = [];
  const lightPowers: number[] = [];
  let maskedTriangles = 0, emissiveSpheres = 0;
  const warnings: string[] = [];
  {
    const v0 = hot.vec3('v0'), e1 = hot.vec3('e1'), e2 = hot.vec3('e2'), flags = hot.u32Field('flags');
    const normals = [shading.vec3('n0'), shading.vec3('n1'), shading.vec3('n2')] as const;
    const uvs = [shading.vec2('uv0'), shading.vec2('uv1'), shading.vec2('uv2')] as const;
    const material = shading.u32Field('material'), sourceIndex = shading.u32Field('source_index');
    const p = triangles.positions;
    let emissiveCapsules = 0;
    for (let leaf = 0; leaf < n; leaf++) {
      const t = bvh.triIndices[leaf]!;
      const o = t * 9;
      const kind = triangles.kinds[t]!;
      const m = triangles.materialIds[t]!;
      const mat = scene.materials[m]!;
      material(leaf, m);
      sourceIndex(leaf, t);
      let flagBits = PRIMITIVE_FLAGS[kind]!;
      if (packedMaterials.hasHitFilter[m]) {
        flagBits |= TRIANGLE_ALPHA_MASKED;
        maskedTriangles++;
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
        const power = luminance(mat.emission) * packedMaterials.emissionMean[m]! * area * (mat.twoSidedEmission ? 2 : 1);
        if (power > 0 && kind === PRIMITIVE_KIND.sphere) {
          lightTriangles.push(leaf);
          lightPowers.push(power);
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
      const power = luminance(mat.emission) * packedMaterials.emissionMean[m]! * 0.5 * twiceArea * (mat.twoSidedEmission ? 2 : 1);
      if (power > 0) {
        lightTriangles.push(leaf);
        lightPowers.push(power);
      }
    }
    if (emissiveCapsules > 0) {
      warnings.push(`${emissiveCapsules} emissive capsule(s) are not sampled as lights: only rays that happen to hit them find their light (unbiased, but noisy)`);
    }
  }

  const triangleAttributes = packTriangleAttributes(scene, triangles, bvh, packedMaterials.needsVertexAttributes);

  const b = bvh.bounds;
  const sceneRadius = bvh.nodeCount > 0 ? 0.5 * Math.hypot(b[3]! - b[0]!, b[4]! - b[1]!, b[5]! - b[2]!) : 1;
  // Lights at infinity: the flux through a disk of the scene's radius (irradiance × πR²), with the
  // irradiance of a uniform environment of mean luminance L being πL.
  const environment = packedEnvironment ?? packEnvironment(scene.environment ?? { kind: 'none' });
  const disk = Math.PI * sceneRadius * sceneRadius;
  const lights = packLights(
    {
      triangles: lightTriangles,
      trianglePowers: lightPowers,
      punctual: scene.lights ?? [],
      environmentPower: Math.PI * environment.meanLuminance * disk,
      sunPower: environment.sunIrradiance * disk,
      sceneRadius,
    },
    layouts,
    layouts.defs,
  );

  const info = new StructArray(layouts.sceneInfo, 1);
  info.u32Field('triangle_count')(0, n);
  info.u32Field('node_count')(0, bvh.nodeCount);
  info.u32Field('light_count')(0, lights.slotCount);
  info.f32Field('total_light_power')(0, lights.totalPower);
  info.f32Field('environment_select_pmf')(0, lights.environmentSelectPmf);
  info.f32Field('sun_select_pmf')(0, lights.sunSelectPmf);

  return {
    scene_info: info.bytes,
    bvh_nodes: nodes.bytes,
    triangles_hot: hot.bytes,
    triangles_shading: shading.bytes,
    materials: packedMaterials.materials,
    light_slots: lights.lightSlots,
    texture_refs: packedMaterials.textureRefs,
    punctual_lights: lights.punctualLights,
    triangleAttributes,
    atlas: packedMaterials.atlas,
    linearAtlas: packedMaterials.linearAtlas,
    counts: {
      triangles: n,
      nodes: bvh.nodeCount,
      lights: lights.slotCount,
      emissiveTriangles: lightTriangles.length,
      punctualLights: lights.punctualCount,
      textures: (scene.textures ?? []).length,
      maskedTriangles,
      spheres: triangles.kindCounts.sphere,
      capsules: triangles.kindCounts.capsule,
      emissiveSpheres,
    },
    features: {
      alphaMasks: maskedTriangles > 0,
      generalMaterials: packedMaterials.general,
      punctualLights: lights.punctualCount > 0,
      environment: lights.environmentSelectPmf > 0 || lights.sunSelectPmf > 0,
      analyticPrimitives: triangles.kindCounts.sphere + triangles.kindCounts.capsule > 0,
    },
    totalLightPower: lights.totalPower,
    warnings: [...packedMaterials.warnings, ...lights.warnings, ...warnings],
    packedMaterials,
    environment,
  };
}

/** Texels per triangle and triangles per row of triangle_attributes (TRIANGLE_ATTRIBUTE_* in shaders/scene/types.wgsl). */
export const TRIANGLE_ATTRIBUTE_TEXELS = 5;
export const TRIANGLE_ATTRIBUTE_TRIANGLES_PER_ROW = 819;

/**
 * Tangents (transformed like directions, their handedness flipped by a mirroring instance) and the
 * second uv set per vertex of every leaf-order triangle, where a material needs them.
 */
function packTriangleAttributes(scene: Scene, triangles: TriangleList, bvh: Bvh, needed: boolean): PackedScene['triangleAttributes'] {
  if (!needed || triangles.count === 0) return { width: 1, height: 1, data: new Float32Array(4) };
  const perRow = TRIANGLE_ATTRIBUTE_TRIANGLES_PER_ROW, texels = TRIANGLE_ATTRIBUTE_TEXELS;
  const width = perRow * texels, height = Math.ceil(triangles.count / perRow);
  const data = new Float32Array(width * height * 4);
  const mirrors = scene.instances.map((inst) => (determinant3(inst.worldFromObject) < 0 ? -1 : 1));
  for (let leaf = 0; leaf < triangles.count; leaf++) {
    const t = bvh.triIndices[leaf]!;
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
  return { width, height, data };
}
