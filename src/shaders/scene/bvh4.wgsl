// The static world traced through its BVH4 (bvh/wide.ts): four children a node, their fp32 boxes in
// the parent as structure of arrays, so one 128-byte node (four BvhNode records: min x, min y, min z,
// max x, max y, max z of the four children, then their references) gives every box a visit tests.
// Closest and any hit; the CPU oracle is bvh/wide.ts traceWide / traceWideAny, step for step, with
// the same counts. Leaves are the static BVH's leaf ranges, so a hit is the record it would give.

#import scene/hit-filter
#import scene/bindings
#import scene/intersect
#import scene/wide-words
#import scene/accel

// A knob for measurements: the closest hit visits a node's hit children nearest first (a sorting
// network over the four entry distances; the default) or in storage order (bvh/wide.ts sortChildren).
override BVH4_SORT_CHILDREN: bool = true;

// A child reference: an interior child's node index, or BVH4_LEAF_BIT | (count - 1) << 27 | the first
// leaf position (bvh/wide.ts).
const BVH4_LEAF_BIT: u32 = 0x80000000u;
const BVH4_FIRST_MASK: u32 = 0x07ffffffu;

fn bvh4_lo(r: u32) -> vec4f {
  return bitcast<vec4f>(scene_bvh_node_low(r));
}

fn bvh4_hi(r: u32) -> vec4f {
  return bitcast<vec4f>(scene_bvh_node_high(r));
}

// Node `node`'s four entry distances (T_MISS: missed, or an unused slot) and child references.
struct Bvh4Visit {
  t: vec4f,
  refs: vec4u,
}

fn bvh4_visit(nodes_record: u32, node: u32, origin: vec3f, inv_dir: vec3f, t_best: f32) -> Bvh4Visit {
  let r = nodes_record + 4u * node;
  let refs = scene_bvh_node_low(r + 3u);
  let t = wide_slabs4(bvh4_lo(r), bvh4_hi(r), bvh4_lo(r + 1u), bvh4_hi(r + 1u), bvh4_lo(r + 2u), bvh4_hi(r + 2u), origin, inv_dir, t_best);
  return Bvh4Visit(select(t, vec4f(T_MISS), refs == vec4u(WIDE_EMPTY)), refs);
}

// One compare-exchange of the sorting network: entries a and b in order of distance.
fn bvh4_order(v: ptr<function, Bvh4Visit>, a: u32, b: u32) {
  if ((*v).t[b] < (*v).t[a]) {
    let t = (*v).t[a];
    (*v).t[a] = (*v).t[b];
    (*v).t[b] = t;
    let r = (*v).refs[a];
    (*v).refs[a] = (*v).refs[b];
    (*v).refs[b] = r;
  }
}

// Pushes the children of `v` that were hit, farthest first, so that the nearest is popped next.
fn bvh4_push(v: Bvh4Visit, stack: ptr<function, array<u32, WIDE_STACK_SIZE>>, sp: ptr<function, u32>) {
  for (var i = 4u; i > 0u; i--) {
    if (v.t[i - 1u] != T_MISS) {
      (*stack)[*sp] = v.refs[i - 1u];
      *sp += 1u;
    }
  }
}

// A leaf reference's leaf positions: (first, end).
fn bvh4_leaf_range(child_ref: u32) -> vec2u {
  let first = child_ref & BVH4_FIRST_MASK;
  return vec2u(first, first + ((child_ref >> 27u) & 15u) + 1u);
}

// The closest hit of the static world before (*hit).t, written to `hit` (instance 0). Returns the
// nodes fetched and the primitives tested (the heat map's counts).
fn bvh4_closest(origin: vec3f, direction: vec3f, inv_dir: vec3f, t_min: f32, hit: ptr<function, Hit>) -> vec2u {
  let nodes_record = wide_header().x >> 3u;
  var stack: array<u32, WIDE_STACK_SIZE>;
  var sp = 0u;
  var node = 0u;
  var work = vec2u(0u);
  loop {
    work.x += 1u;
    var v = bvh4_visit(nodes_record, node, origin, inv_dir, (*hit).t);
    if (BVH4_SORT_CHILDREN) {
      bvh4_order(&v, 0u, 1u);
      bvh4_order(&v, 2u, 3u);
      bvh4_order(&v, 0u, 2u);
      bvh4_order(&v, 1u, 3u);
      bvh4_order(&v, 1u, 2u);
    }
    bvh4_push(v, &stack, &sp);
    // Pop: leaves are tested as they come, until an interior node turns up.
    var next = WIDE_EMPTY;
    loop {
      if (sp == 0u) {
        break;
      }
      sp -= 1u;
      let child_ref = stack[sp];
      if ((child_ref & BVH4_LEAF_BIT) == 0u) {
        next = child_ref;
        break;
      }
      let leaf = bvh4_leaf_range(child_ref);
      for (var i = leaf.x; i < leaf.y; i++) {
        let tri = scene_triangle_hot(i);
        let r = intersect_primitive(origin, direction, tri, t_min, (*hit).t);
        work.y += 1u;
        if (r.x < (*hit).t && accept_hit(tri, i, r.yz)) {
          *hit = Hit(r.x, i, r.y, r.z, 0u);
        }
      }
    }
    if (next == WIDE_EMPTY) {
      break;
    }
    node = next;
  }
  return work;
}

// Whether the static world has anything strictly between t_min and t_max along the ray (children in
// storage order: any hit ends the search).
fn bvh4_any(origin: vec3f, direction: vec3f, inv_dir: vec3f, t_min: f32, t_max: f32) -> bool {
  let nodes_record = wide_header().x >> 3u;
  var stack: array<u32, WIDE_STACK_SIZE>;
  var sp = 0u;
  var node = 0u;
  loop {
    let v = bvh4_visit(nodes_record, node, origin, inv_dir, t_max);
    bvh4_push(v, &stack, &sp);
    var next = WIDE_EMPTY;
    loop {
      if (sp == 0u) {
        break;
      }
      sp -= 1u;
      let child_ref = stack[sp];
      if ((child_ref & BVH4_LEAF_BIT) == 0u) {
        next = child_ref;
        break;
      }
      let leaf = bvh4_leaf_range(child_ref);
      for (var i = leaf.x; i < leaf.y; i++) {
        let tri = scene_triangle_hot(i);
        let r = intersect_primitive(origin, direction, tri, t_min, t_max);
        if (r.x < t_max && accept_hit(tri, i, r.yz)) {
          return true;
        }
      }
    }
    if (next == WIDE_EMPTY) {
      break;
    }
    node = next;
  }
  // After the loop, not inside it: naga (the fragment tracer's GLSL translation) wants a return at
  // the end of a function that returns a value.
  return false;
}
