/**
 * Scene + BVH → the byte arrays of bind group 0 (shaders/scene/bindings.wgsl), pure CPU. Triangles
 * are reordered into BVH leaf order and split into a hot array (what traversal reads: a vertex and
 * two edges) and a cold one (normals, uvs, material, read once per closest hit). Emissive triangles
 * become an alias table proportional to their emitted power. Every layout comes from reflection.
 */
import type { Bvh } from '../../bvh/types.ts';
import { buildAliasTable } from '../../math/alias-table.ts';
import { luminance } from '../../math/vec3.ts';
import type { TriangleList } from '../../scene/triangles.ts';
import type { Scene } from '../../scene/types.ts';
import { reflectModule, structLayout } from '../wgsl/reflect.ts';
import { StructArray } from './struct-array.ts';
import { meanLinearColor, packTextureAtlas, type TextureAtlas } from './texture-atlas.ts';

/** The group-0 resources, keyed by their WGSL variable names. */
export interface PackedScene {
  readonly scene_info: ArrayBuffer;
  readonly bvh_nodes: ArrayBuffer;
  readonly triangles_hot: ArrayBuffer;
  readonly triangles_shading: ArrayBuffer;
  readonly materials: ArrayBuffer;
  readonly light_slots: ArrayBuffer;
  readonly texture_rects: ArrayBuffer;
  /** The pages of texture_atlas (bound as a 2D array texture). */
  readonly atlas: TextureAtlas;
  readonly counts: { readonly triangles: number; readonly nodes: number; readonly lights: number; readonly textures: number; readonly maskedTriangles: number };
  /** Σ luminance(emission) × area over emissive triangles. */
  readonly totalLightPower: number;
}

export function sceneLayouts() {
  const { defs } = reflectModule('scene/bindings');
  return {
    sceneInfo: structLayout(defs, 'SceneInfo'),
    node: structLayout(defs, 'BvhNode'),
    hot: structLayout(defs, 'TriangleHot'),
    shading: structLayout(defs, 'TriangleShading'),
    material: structLayout(defs, 'Material'),
    lightSlot: structLayout(defs, 'LightSlot'),
    textureRect: structLayout(defs, 'TextureRect'),
  };
}

/** Sentinels and flag bits shared with shaders/scene/types.wgsl and lib/constants.wgsl. */
export const NO_TEXTURE = 0xffffffff;
export const TRIANGLE_ALPHA_MASKED = 1;
export const MATERIAL_ALPHA_MASK = 1;
export const MATERIAL_EMISSION_PANORAMA = 2;

/** Options of packing that depend on the device. */
export interface PackOptions {
  /** Largest 2D texture side the device allows (maxTextureDimension2D). */
  readonly maxTextureSide: number;
}

export function packScene(scene: Scene, triangles: TriangleList, bvh: Bvh, options: PackOptions = { maxTextureSide: 8192 }): PackedScene {
  const layouts = sceneLayouts();
  const n = triangles.count;
  const textures = scene.textures ?? [];
  // Luminance of each texture's mean linear colour: the emitted power of a textured emitter.
  const textureMean = textures.map((t) => luminance(meanLinearColor(t)));
  const emissionMean = scene.materials.map((m) => (m.emissionTexture === undefined ? 1 : textureMean[m.emissionTexture] ?? 0));

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

  const hot = new StructArray(layouts.hot, n);
  const shading = new StructArray(layouts.shading, n);
  const lightTriangles: number[] = [];
  const lightPowers: number[] = [];
  let maskedTriangles = 0;
  {
    const v0 = hot.vec3('v0'), e1 = hot.vec3('e1'), e2 = hot.vec3('e2'), flags = hot.u32Field('flags');
    const normals = [shading.vec3('n0'), shading.vec3('n1'), shading.vec3('n2')] as const;
    const uvs = [shading.vec2('uv0'), shading.vec2('uv1'), shading.vec2('uv2')] as const;
    const material = shading.u32Field('material'), sourceIndex = shading.u32Field('source_index');
    const p = triangles.positions;
    for (let leaf = 0; leaf < n; leaf++) {
      const t = bvh.triIndices[leaf]!;
      const o = t * 9;
      const ax = p[o]!, ay = p[o + 1]!, az = p[o + 2]!;
      const e1x = p[o + 3]! - ax, e1y = p[o + 4]! - ay, e1z = p[o + 5]! - az;
      const e2x = p[o + 6]! - ax, e2y = p[o + 7]! - ay, e2z = p[o + 8]! - az;
      v0(leaf, ax, ay, az);
      e1(leaf, e1x, e1y, e1z);
      e2(leaf, e2x, e2y, e2z);

      const mesh = scene.meshes[triangles.meshIds[t]!]!;
      const k = triangles.meshTriangleIds[t]!;
      // Geometric normal e1 × e2, for meshes without normals and for the light's area.
      const cx = e1y * e2z - e1z * e2y, cy = e1z * e2x - e1x * e2z, cz = e1x * e2y - e1y * e2x;
      const twiceArea = Math.hypot(cx, cy, cz);
      for (let c = 0; c < 3; c++) {
        const vi = mesh.indices[k * 3 + c]!;
        if (mesh.normals) {
          normals[c]!(leaf, mesh.normals[vi * 3]!, mesh.normals[vi * 3 + 1]!, mesh.normals[vi * 3 + 2]!);
        } else if (twiceArea > 0) {
          normals[c]!(leaf, cx / twiceArea, cy / twiceArea, cz / twiceArea);
        }
        if (mesh.uvs) uvs[c]!(leaf, mesh.uvs[vi * 2]!, mesh.uvs[vi * 2 + 1]!);
      }
      const m = triangles.materialIds[t]!;
      material(leaf, m);
      sourceIndex(leaf, t);
      const mat = scene.materials[m]!;
      if (mat.alphaMode === 'mask' && mat.albedoTexture !== undefined) {
        flags(leaf, TRIANGLE_ALPHA_MASKED);
        maskedTriangles++;
      }

      // Power in the luminance sense, as lights.wgsl light_selection_pmf computes it.
      const power = luminance(mat.emission) * emissionMean[m]! * 0.5 * twiceArea;
      if (power > 0) {
        lightTriangles.push(leaf);
        lightPowers.push(power);
      }
    }
  }

  const materials = new StructArray(layouts.material, scene.materials.length);
  {
    const albedo = materials.vec3('albedo'), emission = materials.vec3('emission');
    const albedoTexture = materials.u32Field('albedo_texture'), emissionTexture = materials.u32Field('emission_texture');
    const mean = materials.f32Field('emission_texture_mean'), flags = materials.u32Field('flags');
    const repeats = materials.f32Field('panorama_repeats'), horizon = materials.f32Field('panorama_horizon_v'), vPerRadian = materials.f32Field('panorama_v_per_radian');
    scene.materials.forEach((m, i) => {
      albedo(i, ...m.albedo);
      emission(i, ...m.emission);
      albedoTexture(i, m.albedoTexture ?? NO_TEXTURE);
      emissionTexture(i, m.emissionTexture ?? NO_TEXTURE);
      mean(i, emissionMean[i]!);
      let f = 0;
      if (m.alphaMode === 'mask') f |= MATERIAL_ALPHA_MASK;
      const mapping = m.emissionMapping;
      if (mapping?.kind === 'panorama') {
        f |= MATERIAL_EMISSION_PANORAMA;
        repeats(i, mapping.repeats);
        horizon(i, mapping.horizonV);
        vPerRadian(i, mapping.vPerRadian);
      }
      flags(i, f);
    });
  }

  const atlas = packTextureAtlas(textures, options.maxTextureSide);
  const textureRects = new StructArray(layouts.textureRect, textures.length);
  {
    const origin = textureRects.vec2u('origin'), size = textureRects.vec2u('size'), page = textureRects.u32Field('page');
    atlas.rects.forEach((r, i) => {
      origin(i, r.x, r.y);
      size(i, r.width, r.height);
      page(i, r.page);
    });
  }

  const lightSlots = new StructArray(layouts.lightSlot, lightTriangles.length);
  let totalLightPower = 0;
  if (lightTriangles.length > 0) {
    const table = buildAliasTable(lightPowers);
    totalLightPower = table.total;
    const triangle = lightSlots.u32Field('triangle'), alias = lightSlots.u32Field('alias_triangle'), keep = lightSlots.f32Field('keep');
    for (let i = 0; i < lightTriangles.length; i++) {
      triangle(i, lightTriangles[i]!);
      alias(i, lightTriangles[table.alias[i]!]!);
      keep(i, table.keep[i]!);
    }
  }

  const info = new StructArray(layouts.sceneInfo, 1);
  info.u32Field('triangle_count')(0, n);
  info.u32Field('node_count')(0, bvh.nodeCount);
  info.u32Field('light_count')(0, lightTriangles.length);
  info.f32Field('total_light_power')(0, totalLightPower);

  return {
    scene_info: info.bytes,
    bvh_nodes: nodes.bytes,
    triangles_hot: hot.bytes,
    triangles_shading: shading.bytes,
    materials: materials.bytes,
    light_slots: lightSlots.bytes,
    texture_rects: textureRects.bytes,
    atlas,
    counts: { triangles: n, nodes: bvh.nodeCount, lights: lightTriangles.length, textures: textures.length, maskedTriangles },
    totalLightPower,
  };
}
