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
  e1: vec3f,
  e2: vec3f,
}

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

// A diffuse surface that may emit (scene/types.ts Material).
struct Material {
  // Diffuse reflectance, linear RGB in [0, 1].
  albedo: vec3f,
  // Emitted radiance, linear RGB, on the side the geometric normal (e1 × e2) faces.
  emission: vec3f,
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
  // Σ over emissive triangles of luminance(emission) × area: the normaliser of light selection.
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
