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

// What traversal reads: one triangle in leaf order as a vertex and two edges, ready for
// Möller–Trumbore (v1 = v0 + e1, v2 = v0 + e2). The "hot" half of the triangle data.
struct TriangleHot {
  v0: vec3f,
  // TRIANGLE_* bits; fills the slot after v0 that alignment would leave empty anyway.
  flags: u32,
  e1: vec3f,
  e2: vec3f,
}

// The triangle's material is alpha-masked: a hit counts only where its texture is opaque.
const TRIANGLE_ALPHA_MASKED: u32 = 1u;

// What shading reads once per closest hit, same order as TriangleHot. The "cold" half.
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

// A diffuse surface that may emit (scene/types.ts Material). Textures multiply the constants.
struct Material {
  // Diffuse reflectance, linear RGB in [0, 1].
  albedo: vec3f,
  // Index into texture_rects, or NO_TEXTURE.
  albedo_texture: u32,
  // Emitted radiance, linear RGB, on the side the geometric normal (e1 × e2) faces.
  emission: vec3f,
  emission_texture: u32,
  // Luminance of the emission texture's mean linear colour (1 without one): emitted power is
  // luminance(emission) × this × area, the weight of light selection.
  emission_texture_mean: f32,
  // MATERIAL_* bits.
  flags: u32,
  // For MATERIAL_EMISSION_PANORAMA: texture repeats around the horizon, v at the horizon, and v per
  // radian of elevation.
  panorama_repeats: f32,
  panorama_horizon_v: f32,
  panorama_v_per_radian: f32,
}

const MATERIAL_ALPHA_MASK: u32 = 1u;
// The emission texture is looked up by the viewing direction (a sky panorama), not by uv.
const MATERIAL_EMISSION_PANORAMA: u32 = 2u;

// Where one texture lies in the atlas: texels [origin, origin + size) of page `page`.
struct TextureRect {
  origin: vec2u,
  size: vec2u,
  page: u32,
}

// One slot of the alias table over emissive triangles (Walker 1977; Vose 1991): pick a slot
// uniformly, keep its triangle with probability `keep`, otherwise take the slot's alias.
struct LightSlot {
  // Leaf-order triangle index of this slot's light.
  triangle: u32,
  // Leaf-order triangle index taken when this slot's own is not kept.
  alias_triangle: u32,
  keep: f32,
}

struct SceneInfo {
  triangle_count: u32,
  node_count: u32,
  light_count: u32,
  // Σ over emissive triangles of their power (see Material.emission_texture_mean): the normaliser
  // of light selection.
  total_light_power: f32,
}

// A ray with its valid interval (t_min, t_max). Directions need not be unit length unless a caller says so.
struct Ray {
  origin: vec3f,
  t_min: f32,
  direction: vec3f,
  t_max: f32,
}

// The closest hit along a ray: leaf-order triangle (NO_TRIANGLE for a miss), distance, barycentrics of v1, v2.
struct Hit {
  t: f32,
  triangle: u32,
  u: f32,
  v: f32,
}

// A hit as ray-buffer passes report it to the host: the triangle as a source index (scene/triangles.ts).
struct HitRecord {
  t: f32,
  // Source triangle index, or NO_TRIANGLE.
  triangle: u32,
  u: f32,
  v: f32,
}
