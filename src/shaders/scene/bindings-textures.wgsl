// Bind group 0 with the scene's record arrays in textures instead of storage buffers: linked in place
// of scene/bindings (the linker's substitutes) by the fragment tracer (passes/path-trace-fragment),
// which WebGL2 runs translated to GLSL ES 3.00 (no storage buffers there; textureLoad becomes
// texelFetch). The same accessors as scene/bindings, the same names, groups and bindings; the rest
// of group 0 is scene/bindings-shared, as there. Expects nothing.
//
// Each array is an rgba32uint texture (gpu/pack/scene-textures.ts): record i of a struct of S bytes
// takes the ceil(S / 16) texels from texel i · ceil(S / 16) on, its bytes in order as in the storage
// buffer (the last texel zero-padded), texel k at (k mod 2^SCENE_TEXTURE_ROW_SHIFT,
// k >> SCENE_TEXTURE_ROW_SHIFT). The offsets below are those of scene/types under WGSL's storage
// layout (tests/gpu/fragment-tracer.test.ts reads every record back through them).

#import scene/types
#import scene/bindings-shared

// log2 of the textures' row width in texels: 11 (2048, WebGL2's guaranteed MAX_TEXTURE_SIZE) unless
// a scene needs wider rows and the device has them (scene-textures.ts sceneTextureRowShift).
override SCENE_TEXTURE_ROW_SHIFT: u32 = 11u;

@group(0) @binding(1) var bvh_nodes: texture_2d<u32>;
@group(0) @binding(2) var triangles_hot: texture_2d<u32>;
@group(0) @binding(3) var triangles_shading: texture_2d<u32>;
@group(0) @binding(4) var materials: texture_2d<u32>;
@group(0) @binding(5) var light_slots: texture_2d<u32>;
@group(0) @binding(6) var texture_refs: texture_2d<u32>;

// Texels per record (the structs' sizes over 16 bytes, rounded up).
const BVH_NODE_TEXELS: u32 = 2u;
const TRIANGLE_HOT_TEXELS: u32 = 3u;
const TRIANGLE_SHADING_TEXELS: u32 = 5u;
const MATERIAL_TEXELS: u32 = 12u;
const LIGHT_SLOT_TEXELS: u32 = 2u;
const TEXTURE_REF_TEXELS: u32 = 4u;

// Where texel k of a record texture lies.
fn scene_texel_coord(k: u32) -> vec2u {
  return vec2u(k & ((1u << SCENE_TEXTURE_ROW_SHIFT) - 1u), k >> SCENE_TEXTURE_ROW_SHIFT);
}

fn bvh_node_texel(k: u32) -> vec4u {
  return textureLoad(bvh_nodes, scene_texel_coord(k), 0);
}

fn triangle_hot_texel(k: u32) -> vec4u {
  return textureLoad(triangles_hot, scene_texel_coord(k), 0);
}

fn triangle_shading_texel(k: u32) -> vec4u {
  return textureLoad(triangles_shading, scene_texel_coord(k), 0);
}

fn material_texel(k: u32) -> vec4u {
  return textureLoad(materials, scene_texel_coord(k), 0);
}

fn scene_bvh_node(i: u32) -> BvhNode {
  let lo = bvh_node_texel(i * BVH_NODE_TEXELS);
  let hi = bvh_node_texel(i * BVH_NODE_TEXELS + 1u);
  return BvhNode(bitcast<vec3f>(lo.xyz), lo.w, bitcast<vec3f>(hi.xyz), hi.w);
}

// The node's first 16 bytes as words: (aabb_min bits, left_first).
fn scene_bvh_node_low(i: u32) -> vec4u {
  return bvh_node_texel(i * BVH_NODE_TEXELS);
}

// Its last 16: (aabb_max bits, tri_count).
fn scene_bvh_node_high(i: u32) -> vec4u {
  return bvh_node_texel(i * BVH_NODE_TEXELS + 1u);
}

// v0 and flags, e1, e2.
fn scene_triangle_hot(i: u32) -> TriangleHot {
  let k = i * TRIANGLE_HOT_TEXELS;
  let a = triangle_hot_texel(k);
  return TriangleHot(bitcast<vec3f>(a.xyz), a.w, bitcast<vec3f>(triangle_hot_texel(k + 1u).xyz), bitcast<vec3f>(triangle_hot_texel(k + 2u).xyz));
}

fn scene_triangle_flags(i: u32) -> u32 {
  return triangle_hot_texel(i * TRIANGLE_HOT_TEXELS).w;
}

// n0, n1, n2, (uv0, uv1), (uv2, material, source_index).
fn scene_triangle_shading(i: u32) -> TriangleShading {
  let k = i * TRIANGLE_SHADING_TEXELS;
  let uv01 = bitcast<vec4f>(triangle_shading_texel(k + 3u));
  let last = triangle_shading_texel(k + 4u);
  return TriangleShading(
    bitcast<vec3f>(triangle_shading_texel(k).xyz),
    bitcast<vec3f>(triangle_shading_texel(k + 1u).xyz),
    bitcast<vec3f>(triangle_shading_texel(k + 2u).xyz),
    uv01.xy,
    uv01.zw,
    bitcast<vec2f>(last.xy),
    last.z,
    last.w,
  );
}

fn scene_triangle_material(i: u32) -> u32 {
  return triangle_shading_texel(i * TRIANGLE_SHADING_TEXELS + 4u).z;
}

// Twelve texels: byte offsets 0, 16, ..., 176 of Material.
fn scene_material(i: u32) -> Material {
  let k = i * MATERIAL_TEXELS;
  let t0 = material_texel(k);
  let t1 = material_texel(k + 1u);
  let t2 = material_texel(k + 2u);
  let t3 = material_texel(k + 3u);
  let t4 = material_texel(k + 4u);
  let t5 = material_texel(k + 5u);
  let t6 = material_texel(k + 6u);
  let t7 = material_texel(k + 7u);
  let t8 = material_texel(k + 8u);
  let t9 = material_texel(k + 9u);
  let t10 = material_texel(k + 10u);
  let t11 = material_texel(k + 11u);
  return Material(
    t0.x, t0.y, bitcast<f32>(t0.z), bitcast<f32>(t0.w),
    bitcast<vec3f>(t1.xyz), t1.w,
    bitcast<vec3f>(t2.xyz), t2.w,
    bitcast<f32>(t3.x), bitcast<f32>(t3.y), bitcast<f32>(t3.z), t3.w,
    bitcast<vec3f>(t4.xyz), t4.w,
    bitcast<f32>(t5.x), bitcast<f32>(t5.y), bitcast<f32>(t5.z), t5.w,
    bitcast<vec3f>(t6.xyz), t6.w,
    t7.x, bitcast<f32>(t7.y), bitcast<f32>(t7.z), bitcast<f32>(t7.w),
    bitcast<f32>(t8.x), t8.y, bitcast<f32>(t8.z),
    bitcast<vec3f>(t9.xyz),
    bitcast<vec3f>(t10.xyz),
    bitcast<vec3f>(t11.xyz),
  );
}

// light, alias_light, keep, instance; alias_instance.
fn scene_light_slot(i: u32) -> LightSlot {
  let k = i * LIGHT_SLOT_TEXELS;
  let a = textureLoad(light_slots, scene_texel_coord(k), 0);
  let b = textureLoad(light_slots, scene_texel_coord(k + 1u), 0);
  return LightSlot(a.x, a.y, bitcast<f32>(a.z), a.w, b.x);
}

// (origin, size), (page, flags), (transform_u, levels), transform_v.
fn scene_texture_ref(i: u32) -> TextureRef {
  let k = i * TEXTURE_REF_TEXELS;
  let a = textureLoad(texture_refs, scene_texel_coord(k), 0);
  let b = textureLoad(texture_refs, scene_texel_coord(k + 1u), 0);
  let c = textureLoad(texture_refs, scene_texel_coord(k + 2u), 0);
  let d = textureLoad(texture_refs, scene_texel_coord(k + 3u), 0);
  return TextureRef(a.xy, a.zw, b.x, b.y, bitcast<vec3f>(c.xyz), c.w, bitcast<vec3f>(d.xyz));
}
