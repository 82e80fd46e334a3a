// Word access to the static world's wide tree (bvh/wide.ts packWide), which lives in bvh_nodes from
// record scene_info.grid_base with no binding of its own: a header record (word 0: the word index of
// node 0; word 1: the word index of the leaf table), the nodes, the leaf table. Words are read four at
// a time (one half of a BvhNode record: 16 bytes). Expects the scene bindings (group 0).

#import lib/constants
#import scene/bindings

// An unused child slot (bvh/wide.ts WIDE_EMPTY).
const WIDE_EMPTY: u32 = 0xffffffffu;

// Stack entries of the wide traversals (bvh/wide.ts WIDE_STACK_SIZE; the collapse refuses a deeper tree).
const WIDE_STACK_SIZE: u32 = 64u;

// The four words from word `w` (a multiple of 4) of bvh_nodes. A branch, not a select, so that only
// the half of the record that is needed is loaded.
fn wide_quad(w: u32) -> vec4u {
  let r = w >> 3u;
  if ((w & 4u) != 0u) {
    return scene_bvh_node_high(r);
  }
  return scene_bvh_node_low(r);
}

fn wide_word(w: u32) -> u32 {
  return wide_quad(w & ~3u)[w & 3u];
}

// (word of node 0, word of the leaf table).
fn wide_header() -> vec2u {
  let n = scene_bvh_node(scene_info.grid_base);
  return bitcast<vec3u>(n.aabb_min).xy;
}

// Slab tests of four boxes at once, each as scene/intersect intersect_aabb tests one: the entry
// distance, or T_MISS where the ray misses the box or enters it at or beyond t_best.
fn wide_slabs4(lo_x: vec4f, lo_y: vec4f, lo_z: vec4f, hi_x: vec4f, hi_y: vec4f, hi_z: vec4f, origin: vec3f, inv_dir: vec3f, t_best: f32) -> vec4f {
  let tx0 = (lo_x - origin.x) * inv_dir.x;
  let tx1 = (hi_x - origin.x) * inv_dir.x;
  let ty0 = (lo_y - origin.y) * inv_dir.y;
  let ty1 = (hi_y - origin.y) * inv_dir.y;
  let tz0 = (lo_z - origin.z) * inv_dir.z;
  let tz1 = (hi_z - origin.z) * inv_dir.z;
  let t_near = max(max(min(tx0, tx1), min(ty0, ty1)), min(tz0, tz1));
  let t_far = min(min(max(tx0, tx1), max(ty0, ty1)), max(tz0, tz1));
  let hit = (t_near <= t_far) & (t_far >= vec4f(0.0)) & (t_near < vec4f(t_best));
  return select(vec4f(T_MISS), t_near, hit);
}
