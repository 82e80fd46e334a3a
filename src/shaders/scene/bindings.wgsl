// Bind group 0, the scene, shared by every pass that traces rays (gpu/scene-resources.ts fills it).
// Expects nothing; provides the scene's records through the accessors below (scene_bvh_node, ...),
// which every module calls instead of indexing the arrays: scene/bindings-textures declares the same
// functions and bindings with the arrays in rgba32uint textures (the fragment tracer, which WebGL2
// runs: docs/fragment-tracer.md), linked in place of this module. Storage buffers are few on purpose:
// with group 2's they must fit WebGPU's default limit of 8 per shader stage.

#import scene/types
#import scene/bindings-shared

@group(0) @binding(1) var<storage, read> bvh_nodes: array<BvhNode>;
@group(0) @binding(2) var<storage, read> triangles_hot: array<TriangleHot>;
@group(0) @binding(3) var<storage, read> triangles_shading: array<TriangleShading>;
@group(0) @binding(4) var<storage, read> materials: array<Material>;
@group(0) @binding(5) var<storage, read> light_slots: array<LightSlot>;
@group(0) @binding(6) var<storage, read> texture_refs: array<TextureRef>;

// The records, by index. The _low/_high and field accessors load only what their callers read.
fn scene_bvh_node(i: u32) -> BvhNode {
  return bvh_nodes[i];
}

// The node's first 16 bytes as words: (aabb_min bits, left_first).
fn scene_bvh_node_low(i: u32) -> vec4u {
  return vec4u(bitcast<vec3u>(bvh_nodes[i].aabb_min), bvh_nodes[i].left_first);
}

// Its last 16: (aabb_max bits, tri_count).
fn scene_bvh_node_high(i: u32) -> vec4u {
  return vec4u(bitcast<vec3u>(bvh_nodes[i].aabb_max), bvh_nodes[i].tri_count);
}

fn scene_triangle_hot(i: u32) -> TriangleHot {
  return triangles_hot[i];
}

fn scene_triangle_flags(i: u32) -> u32 {
  return triangles_hot[i].flags;
}

fn scene_triangle_shading(i: u32) -> TriangleShading {
  return triangles_shading[i];
}

fn scene_triangle_material(i: u32) -> u32 {
  return triangles_shading[i].material;
}

fn scene_material(i: u32) -> Material {
  return materials[i];
}

fn scene_light_slot(i: u32) -> LightSlot {
  return light_slots[i];
}

fn scene_texture_ref(i: u32) -> TextureRef {
  return texture_refs[i];
}
