// The static world traced through its compressed 8-wide BVH (bvh/wide.ts), after Ylitie, Karras &
// Laine, "Efficient Incoherent Ray Traversal on GPUs Through Compressed Wide BVHs" (HPG 2017): an
// 80-byte node holds an origin p and a power-of-two scale per axis, and each child's box as 8-bit
// planes, rounded outward, so a child box is p + q·scale (exactly what the CPU oracle computes, then
// the same slab test). Slots suit direction octants; a ray visits slot (b ^ octant) for b = 0, 1, ...
// from a stack of node groups (child base, hits in visiting order, internal-child mask). Leaves are
// the static BVH's leaf ranges (their first positions in the leaf table), tested when their node is
// visited. The CPU oracle is bvh/wide.ts traceWide / traceWideAny, step for step, with the same counts.
//
// Node words (bvh/wide.ts packCwbvh): 0-2 p (f32), 3 exponent bytes x, y, z (biased by 127) and the
// internal-child mask, 4 the index of the first internal child (the others follow in slot order),
// 5 the node's first leaf-table entry, 6-7 a meta byte a slot (leaf: count | entry << 5; 0 else),
// 8-19 the quantised planes: lo x, lo y, lo z, hi x, hi y, hi z, two words (slots 0-3, 4-7) each.

#import lib/bits
#import scene/hit-filter
#import scene/bindings
#import scene/intersect
#import scene/wide-words
#import scene/accel

const CWBVH_NODE_WORDS: u32 = 20u;

// The four bytes of `w` as floats.
fn cwbvh_bytes(w: u32) -> vec4f {
  return vec4f((vec4u(w) >> vec4u(0u, 8u, 16u, 24u)) & vec4u(0xffu));
}

// The ray's octant: bit k set where direction component k is negative (bvh/wide.ts rayOctant).
fn cwbvh_octant(direction: vec3f) -> u32 {
  return select(0u, 1u, direction.x < 0.0) | select(0u, 2u, direction.y < 0.0) | select(0u, 4u, direction.z < 0.0);
}

// One node visit: the hit masks in visiting order (bit b: slot b ^ octant) of its internal and leaf
// children, and what the traversal needs next.
struct CwbvhVisit {
  internal_hits: u32,
  leaf_hits: u32,
  imask: u32,
  child_base: u32,
  leaf_base: u32,
  metas: vec2u,
}

// The 80-byte node from word `w` (a multiple of 4): it spans the three records from w >> 3, starting
// at the first's first half or its second, so all three are loaded whole (no divergence between
// threads on nodes of either alignment) and the five quads selected.
struct CwbvhNode {
  q0: vec4u,
  q1: vec4u,
  q2: vec4u,
  q3: vec4u,
  q4: vec4u,
}

fn cwbvh_node(w: u32) -> CwbvhNode {
  let r = w >> 3u;
  let a = scene_bvh_node(r);
  let b = scene_bvh_node(r + 1u);
  let c = scene_bvh_node(r + 2u);
  let a_lo = vec4u(bitcast<vec3u>(a.aabb_min), a.left_first);
  let a_hi = vec4u(bitcast<vec3u>(a.aabb_max), a.tri_count);
  let b_lo = vec4u(bitcast<vec3u>(b.aabb_min), b.left_first);
  let b_hi = vec4u(bitcast<vec3u>(b.aabb_max), b.tri_count);
  let c_lo = vec4u(bitcast<vec3u>(c.aabb_min), c.left_first);
  let c_hi = vec4u(bitcast<vec3u>(c.aabb_max), c.tri_count);
  let odd = (w & 4u) != 0u;
  return CwbvhNode(select(a_lo, a_hi, odd), select(a_hi, b_lo, odd), select(b_lo, b_hi, odd), select(b_hi, c_lo, odd), select(c_lo, c_hi, odd));
}

fn cwbvh_visit(w: u32, octant: u32, origin: vec3f, inv_dir: vec3f, t_best: f32) -> CwbvhVisit {
  let n = cwbvh_node(w);
  let q0 = n.q0;
  let q1 = n.q1;
  let q2 = n.q2;
  let q3 = n.q3;
  let q4 = n.q4;
  let p = bitcast<vec3f>(q0.xyz);
  let e = vec3u(q0.w, q0.w >> 8u, q0.w >> 16u) & vec3u(0xffu);
  let scale = bitcast<vec3f>(e << vec3u(23u));
  let imask = q0.w >> 24u;
  // Slots 0-3 then 4-7: lo = p + q·scale (q·scale is exact, so one rounding as on the CPU).
  let t_lo = wide_slabs4(p.x + cwbvh_bytes(q2.x) * scale.x, p.y + cwbvh_bytes(q2.z) * scale.y, p.z + cwbvh_bytes(q3.x) * scale.z,
    p.x + cwbvh_bytes(q3.z) * scale.x, p.y + cwbvh_bytes(q4.x) * scale.y, p.z + cwbvh_bytes(q4.z) * scale.z, origin, inv_dir, t_best);
  let t_hi = wide_slabs4(p.x + cwbvh_bytes(q2.y) * scale.x, p.y + cwbvh_bytes(q2.w) * scale.y, p.z + cwbvh_bytes(q3.y) * scale.z,
    p.x + cwbvh_bytes(q3.w) * scale.x, p.y + cwbvh_bytes(q4.y) * scale.y, p.z + cwbvh_bytes(q4.w) * scale.z, origin, inv_dir, t_best);
  var v = CwbvhVisit(0u, 0u, imask, q1.x, q1.y, q1.zw);
  for (var s = 0u; s < 8u; s++) {
    let slot_meta = (v.metas[s >> 2u] >> (8u * (s & 3u))) & 0xffu;
    let internal = ((imask >> s) & 1u) != 0u;
    let t = select(t_lo[s & 3u], t_hi[s & 3u], s >= 4u);
    if ((internal || slot_meta != 0u) && t != T_MISS) {
      let bit = 1u << (s ^ octant);
      if (internal) {
        v.internal_hits |= bit;
      } else {
        v.leaf_hits |= bit;
      }
    }
  }
  return v;
}

// The leaf of visiting-order bit b: (first leaf position, count).
fn cwbvh_leaf(v: CwbvhVisit, b: u32, octant: u32, table_word: u32) -> vec2u {
  let s = b ^ octant;
  let slot_meta = (v.metas[s >> 2u] >> (8u * (s & 3u))) & 0xffu;
  return vec2u(wide_word(table_word + v.leaf_base + (slot_meta >> 5u)), slot_meta & 31u);
}

// A node group: the node of its first internal child, its hits not yet taken (bit b: slot b ^ octant)
// and its internal-child mask. On the stack as (base, hits | imask << 8).
struct CwbvhGroup {
  base: u32,
  hits: u32,
  imask: u32,
}

fn cwbvh_group_entry(g: CwbvhGroup) -> vec2u {
  return vec2u(g.base, g.hits | (g.imask << 8u));
}

fn cwbvh_entry_group(e: vec2u) -> CwbvhGroup {
  return CwbvhGroup(e.x, e.y & 0xffu, e.y >> 8u);
}

// Takes the group's next hit in visiting order and returns its node (the internal children follow
// base in slot order).
fn cwbvh_take(g: ptr<function, CwbvhGroup>, octant: u32) -> u32 {
  let slot = bits_first_trailing((*g).hits) ^ octant;
  (*g).hits &= (*g).hits - 1u;
  return (*g).base + bits_count_ones((*g).imask & ((1u << slot) - 1u));
}

// The closest hit of the static world before (*hit).t, written to `hit` (instance 0). Returns the
// nodes fetched and the primitives tested (the heat map's counts).
fn cwbvh_closest(origin: vec3f, direction: vec3f, inv_dir: vec3f, t_min: f32, hit: ptr<function, Hit>) -> vec2u {
  let header = wide_header();
  let octant = cwbvh_octant(direction);
  var stack: array<vec2u, WIDE_STACK_SIZE>;
  var sp = 0u;
  // The current group: the root alone (slot 0 of a group based at node 0).
  var group = CwbvhGroup(0u, 1u << octant, 1u);
  var work = vec2u(0u);
  loop {
    if (group.hits == 0u) {
      if (sp == 0u) {
        break;
      }
      sp -= 1u;
      group = cwbvh_entry_group(stack[sp]);
    }
    let child = cwbvh_take(&group, octant);
    if (group.hits != 0u) {
      stack[sp] = cwbvh_group_entry(group);
      sp += 1u;
    }
    work.x += 1u;
    let v = cwbvh_visit(header.x + child * CWBVH_NODE_WORDS, octant, origin, inv_dir, (*hit).t);
    var leaves = v.leaf_hits;
    loop {
      if (leaves == 0u) {
        break;
      }
      let range = cwbvh_leaf(v, bits_first_trailing(leaves), octant, header.y);
      leaves &= leaves - 1u;
      for (var i = range.x; i < range.x + range.y; i++) {
        let tri = scene_triangle_hot(i);
        let r = intersect_primitive(origin, direction, tri, t_min, (*hit).t);
        work.y += 1u;
        if (r.x < (*hit).t && accept_hit(tri, i, r.yz)) {
          *hit = Hit(r.x, i, r.y, r.z, 0u);
        }
      }
    }
    group = CwbvhGroup(v.child_base, v.internal_hits, v.imask);
  }
  return work;
}

// Whether the static world has anything strictly between t_min and t_max along the ray.
fn cwbvh_any(origin: vec3f, direction: vec3f, inv_dir: vec3f, t_min: f32, t_max: f32) -> bool {
  let header = wide_header();
  let octant = cwbvh_octant(direction);
  var stack: array<vec2u, WIDE_STACK_SIZE>;
  var sp = 0u;
  var group = CwbvhGroup(0u, 1u << octant, 1u);
  loop {
    if (group.hits == 0u) {
      if (sp == 0u) {
        break;
      }
      sp -= 1u;
      group = cwbvh_entry_group(stack[sp]);
    }
    let child = cwbvh_take(&group, octant);
    if (group.hits != 0u) {
      stack[sp] = cwbvh_group_entry(group);
      sp += 1u;
    }
    let v = cwbvh_visit(header.x + child * CWBVH_NODE_WORDS, octant, origin, inv_dir, t_max);
    var leaves = v.leaf_hits;
    loop {
      if (leaves == 0u) {
        break;
      }
      let range = cwbvh_leaf(v, bits_first_trailing(leaves), octant, header.y);
      leaves &= leaves - 1u;
      for (var i = range.x; i < range.x + range.y; i++) {
        let tri = scene_triangle_hot(i);
        let r = intersect_primitive(origin, direction, tri, t_min, t_max);
        if (r.x < t_max && accept_hit(tri, i, r.yz)) {
          return true;
        }
      }
    }
    group = CwbvhGroup(v.child_base, v.internal_hits, v.imask);
  }
  // After the loop, not inside it: naga (the fragment tracer's GLSL translation) wants a return at
  // the end of a function that returns a value.
  return false;
}
