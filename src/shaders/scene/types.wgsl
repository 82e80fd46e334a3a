// The GPU scene layout: the single source of truth. The host packs these structs through reflection
// (gpu/wgsl/reflect.ts reads every offset and stride from here); nothing on the host repeats them.
// Expects nothing. All positions are world space in scene units.

// One node of the binary BVH, 32 bytes. Siblings are adjacent: an interior node's children are
// left_first and left_first + 1. Node 0 is the root; slot 1 is unused so sibling pairs share a 64-byte block.
struct BvhNode {
  aabb_min: vec3f,
  // Interior: index of the left child. Leaf: index of the first triangle (leaf order).
  left_first: u32,
  aabb_max: vec3f,
  // 0 for an interior node; the number of triangles for a leaf.
  tri_count: u32,
}

// What traversal reads: one primitive in leaf order. A triangle is a vertex and two edges, ready for
// Möller–Trumbore (v1 = v0 + e1, v2 = v0 + e2). A sphere (PRIMITIVE_SPHERE) is its centre v0 and
// radius e1.x; a capsule (PRIMITIVE_CAPSULE) its end a = v0, axis e1 = b − a and radius e2.x. The
// "hot" half of the primitive data (scene/triangles.ts has the kinds).
struct TriangleHot {
  v0: vec3f,
  // TRIANGLE_* and PRIMITIVE_* bits; fills the slot after v0 that alignment would leave empty anyway.
  flags: u32,
  e1: vec3f,
  e2: vec3f,
}

// The triangle's material is alpha-masked: a hit counts only where its texture is opaque.
const TRIANGLE_ALPHA_MASKED: u32 = 1u;
// The primitive's kind, when not a triangle (gpu/pack/scene-pack.ts sets these bits).
const PRIMITIVE_SPHERE: u32 = 256u;
const PRIMITIVE_CAPSULE: u32 = 512u;
const PRIMITIVE_ANALYTIC: u32 = 768u;

// One placement of a bottom-level BVH in the world (bvh/levels.ts): instance 0 is the static
// world (identity; its primitives are stored in world space), the others are moving instances of a
// mesh whose primitives are stored once, in object space. Rows of 3×4 affine transforms: a point p
// maps to (dot(r0.xyz, p) + r0.w, dot(r1.xyz, p) + r1.w, dot(r2.xyz, p) + r2.w).
struct Instance {
  world_from_object_0: vec4f,
  world_from_object_1: vec4f,
  world_from_object_2: vec4f,
  object_from_world_0: vec4f,
  object_from_world_1: vec4f,
  object_from_world_2: vec4f,
  // world_from_object of the previous frame (motion vectors: where a point of the instance was).
  previous_0: vec4f,
  previous_1: vec4f,
  previous_2: vec4f,
  // The bottom level's root in bvh_nodes.
  blas_root: u32,
  // The instance's first primitive in the scene's flattened list (HitRecord source indices).
  source_base: u32,
  // Scene material replacing the mesh's (scene/types.ts Instance.material), or NO_MATERIAL.
  material: u32,
  // INSTANCE_* bits.
  flags: u32,
}

// The transform mirrors (negative determinant): v1 and v2 swap, as scene/triangles.ts swaps them.
const INSTANCE_MIRRORED: u32 = 1u;
// The instance's material has a hit filter (alpha mask or blend), whatever its mesh's materials say.
const INSTANCE_ALPHA_FILTER: u32 = 2u;
const NO_MATERIAL: u32 = 0xffffffffu;
// How instance_data stores the records (gpu/pack/scene-pack.ts INSTANCE_TEXELS, INSTANCES_PER_ROW).
const INSTANCE_TEXELS: u32 = 10u;
const INSTANCES_PER_ROW: u32 = 128u;

// What shading reads once per closest hit, same order as TriangleHot. The "cold" half. Spheres and
// capsules use only material and source_index (their normals and uvs are analytic).
struct TriangleShading {
  // Unit shading normals at v0, v1, v2 (the geometric normal where the mesh has none).
  n0: vec3f,
  n1: vec3f,
  n2: vec3f,
  uv0: vec2f,
  uv1: vec2f,
  uv2: vec2f,
  material: u32,
  // Index of this triangle in the scene's flattened triangle list (scene/triangles.ts).
  source_index: u32,
}

// A material of any kind (scene/types.ts Material), as stored; scene/materials.wgsl resolves it at a
// hit (textures applied) into the BsdfParams of scene/bsdf.wgsl. Fields a kind does not use are zero.
struct Material {
  // MATERIAL_KIND_*.
  kind: u32,
  // MATERIAL_* bits.
  flags: u32,
  // Coverage below this is a hole (MATERIAL_ALPHA_MASK).
  alpha_cutoff: f32,
  // Constant coverage multiplying the colour texture's alpha.
  opacity: f32,
  // Diffuse albedo, glTF base colour or glass tint: linear RGB in [0, 1].
  base_color: vec3f,
  // Index into texture_refs, or NO_TEXTURE. Its alpha is the coverage.
  base_color_texture: u32,
  // Emitted radiance, linear RGB, on the side the geometric normal (e1 × e2) faces.
  emission: vec3f,
  emission_texture: u32,
  // Luminance of the emission texture's mean linear colour (1 without one): emitted power is
  // luminance(emission) × this × area, the weight of light selection.
  emission_texture_mean: f32,
  metallic: f32,
  // Perceptual roughness (GGX α = roughness²).
  roughness: f32,
  // G multiplies roughness, B metallic.
  metallic_roughness_texture: u32,
  // KHR_materials_specular colour; its texture's RGB multiplies it.
  specular_color: vec3f,
  // A multiplies specular.
  specular_texture: u32,
  ior: f32,
  transmission: f32,
  specular: f32,
  // R multiplies transmission.
  transmission_texture: u32,
  // Beer–Lambert absorption coefficient inside the volume, per scene unit: −ln(attenuation colour) / distance.
  absorption: vec3f,
  specular_color_texture: u32,
  // Tangent-space normal map (rgb = (n + 1) / 2), or NO_TEXTURE.
  normal_texture: u32,
  normal_scale: f32,
  // For MATERIAL_EMISSION_PANORAMA: texture repeats around the horizon, v at the horizon, and v per
  // radian of elevation.
  panorama_repeats: f32,
  panorama_horizon_v: f32,
  panorama_v_per_radian: f32,
  // Dispersion (scene/dispersion.ts, shaders/scene/dispersion.wgsl): a DISPERSION_* law, and the scale
  // of (n_law(λ) − 1) that puts n(589.3 nm) at `ior`. Read only by spectral mode.
  dispersion_law: u32,
  dispersion_scale: f32,
  // Sellmeier B₁, B₂, B₃; Cauchy (A, B in µm², 0).
  dispersion_b: vec3f,
  // Sellmeier C₁, C₂, C₃ in µm².
  dispersion_c: vec3f,
  // MATERIAL_SCATTER_IN_PLANE: the world-space unit normal of the plane scattered light stays in.
  scatter_plane_normal: vec3f,
}

// Material kinds, in the order of scene/types.ts MaterialKind (renderer/ mirrors them by name).
const MATERIAL_KIND_DIFFUSE: u32 = 0u;
const MATERIAL_KIND_METALLIC_ROUGHNESS: u32 = 1u;
const MATERIAL_KIND_DIELECTRIC: u32 = 2u;
const MATERIAL_KIND_EMISSIVE: u32 = 3u;

// Dispersion laws (gpu/pack/material-pack.ts DISPERSION_LAWS): none (n = ior at every wavelength),
// Sellmeier n² = 1 + Σ Bᵢ λ²/(λ² − Cᵢ), Cauchy n = A + B/λ² (λ in µm).
const DISPERSION_NONE: u32 = 0u;
const DISPERSION_SELLMEIER: u32 = 1u;
const DISPERSION_CAUCHY: u32 = 2u;

const MATERIAL_ALPHA_MASK: u32 = 1u;
// The emission texture is looked up by the viewing direction (a sky panorama), not by uv.
const MATERIAL_EMISSION_PANORAMA: u32 = 2u;
// Coverage is a probability (stochastic transparency).
const MATERIAL_ALPHA_BLEND: u32 = 4u;
// Transmission does not bend rays (glTF transmission without a volume).
const MATERIAL_THIN_WALLED: u32 = 16u;
// Scatters only in the plane perpendicular to scatter_plane_normal (scene/types.ts DiffuseMaterial.scatterPlaneNormal).
const MATERIAL_SCATTER_IN_PLANE: u32 = 32u;
// Both faces emit (scene/types.ts MaterialBase.twoSidedEmission: Doom's lamps on sprites).
const MATERIAL_TWO_SIDED_EMISSION: u32 = 64u;

// A material's use of one texture: where the texture lies in its atlas, how it is stored, and the
// uv transform (KHR_texture_transform) applied first.
struct TextureRef {
  // Texels [origin, origin + size) of page `page` of the atlas that TEXTURE_LINEAR picks.
  origin: vec2u,
  size: vec2u,
  page: u32,
  // TEXTURE_* bits.
  flags: u32,
  // uv' = (dot(transform_u, (u, v, 1)), dot(transform_v, (u, v, 1))).
  transform_u: vec3f,
  // Mip levels stored (1: level 0 only). Level k > 0 lies at origin + (size.x, Σ_{j=1}^{k-1} h_j)
  // with h_j = max(1, size.y >> j) (gpu/pack/mip-chain.ts).
  levels: u32,
  transform_v: vec3f,
}

// Stored linearly (data: normals, metallic-roughness), in texture_atlas_linear; else sRGB colour in texture_atlas.
const TEXTURE_LINEAR: u32 = 1u;
// Filtered bilinearly (glTF); else the nearest texel (Doom's pixels).
const TEXTURE_BILINEAR: u32 = 2u;
// Looked up with the second uv set (glTF TEXCOORD_1; triangle_attributes holds it).
const TEXTURE_UV1: u32 = 4u;

// triangle_attributes: per leaf-order triangle, TRIANGLE_ATTRIBUTE_TEXELS texels of a row of
// TRIANGLE_ATTRIBUTE_TRIANGLES_PER_ROW triangles: the world-space tangents of v0, v1, v2 (xyz, w =
// bitangent sign; all zero without tangents), then the second uv set ((u0, v0, u1, v1), (u2, v2, 0, 0)).
const TRIANGLE_ATTRIBUTE_TEXELS: u32 = 5u;
const TRIANGLE_ATTRIBUTE_TRIANGLES_PER_ROW: u32 = 819u;

// One slot of the alias table over every light (Walker 1977; Vose 1991): pick a slot uniformly,
// keep its light with probability `keep`, otherwise take the slot's alias. Lights are LIGHT_* codes.
struct LightSlot {
  light: u32,
  alias_light: u32,
  keep: f32,
  // The instances of an emissive primitive (light, alias_light): 0 for the static world.
  instance: u32,
  alias_instance: u32,
}

// A light code: the kind in the top two bits, an index below. Emissive triangles are coded by their
// leaf-order index (kind 0), so a code of an emitter is the triangle itself.
const LIGHT_KIND_SHIFT: u32 = 30u;
const LIGHT_INDEX_MASK: u32 = 0x3fffffffu;
const LIGHT_KIND_TRIANGLE: u32 = 0u;
const LIGHT_KIND_PUNCTUAL: u32 = 1u;
const LIGHT_KIND_ENVIRONMENT: u32 = 2u;
const LIGHT_KIND_SUN: u32 = 3u;

// KHR_lights_punctual, world space (scene/types.ts PunctualLight).
struct PunctualLight {
  // Point and spot: position. Directional: the unit direction toward the light.
  position: vec3f,
  // PUNCTUAL_*.
  kind: u32,
  // Colour × intensity (W/sr) for point and spot; colour × irradiance (W/m²) for directional.
  intensity: vec3f,
  // Point and spot: cut-off distance (T_MISS for none).
  range: f32,
  // Spot: unit direction the light shines in.
  direction: vec3f,
  // Spot: cos of the outer cone angle, and 1 / (cos inner − cos outer) for the smooth falloff.
  cos_outer: f32,
  cone_scale: f32,
  // Probability that light selection picks this light (its power over the total).
  select_pmf: f32,
}

const PUNCTUAL_POINT: u32 = 0u;
const PUNCTUAL_SPOT: u32 = 1u;
const PUNCTUAL_DIRECTIONAL: u32 = 2u;
// Punctual lights live in a uniform array of this size (the loader keeps the brightest).
const MAX_PUNCTUAL_LIGHTS: u32 = 64u;

struct PunctualLights {
  count: u32,
  // The size is MAX_PUNCTUAL_LIGHTS, written out: the reflection library reads literal sizes only.
  lights: array<PunctualLight, 64>,
}

struct SceneInfo {
  triangle_count: u32,
  node_count: u32,
  // Slots of the light alias table.
  light_count: u32,
  // Σ over all lights of their (estimated) power: the normaliser of light selection. An emissive
  // triangle's power is luminance(emission) × Material.emission_texture_mean × area.
  total_light_power: f32,
  // Selection probabilities of the environment map and of the sun (0 without them), for MIS.
  environment_select_pmf: f32,
  sun_select_pmf: f32,
  // The top-level tree's root in bvh_nodes (bvh/levels.ts), for scenes with moving instances.
  tlas_root: u32,
  instance_count: u32,
  // 1 when the static world has no primitives (everything moves): traversal starts at the top level.
  static_world_empty: u32,
  // The record of bvh_nodes where the static world's grid (gpu/pack/scene-pack.ts packGrid) or wide
  // tree (bvh/wide.ts packWide) begins, when it is traced through one (STATIC_ACCEL of scene/accel not
  // ACCEL_BVH2); 0 otherwise.
  grid_base: u32,
}

// A ray with its valid interval (t_min, t_max). Directions need not be unit length unless a caller says so.
struct Ray {
  origin: vec3f,
  t_min: f32,
  direction: vec3f,
  t_max: f32,
}

// The closest hit along a ray: leaf-order primitive (NO_TRIANGLE for a miss), distance, and for a
// triangle the barycentrics of v1, v2, for a sphere or capsule the surface uv.
struct Hit {
  t: f32,
  triangle: u32,
  u: f32,
  v: f32,
  // The instance whose primitive was hit (0: the static world; see Instance).
  instance: u32,
}

// A hit as ray-buffer passes report it to the host: the triangle as a source index (scene/triangles.ts).
struct HitRecord {
  t: f32,
  // Source triangle index, or NO_TRIANGLE.
  triangle: u32,
  u: f32,
  v: f32,
}
