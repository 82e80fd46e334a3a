// BVH traversal: closest hit with an ordered stack (nearer child first, the closest hit so far prunes
// boxes), and any hit for shadow rays. Alpha-masked triangles count only where their texture is
// opaque. Expects the scene bindings (group 0). The CPU oracle bvh/traverse.ts runs the same
// algorithm (without alpha masks), so hits and visited-node counts agree; with BVH_COUNT_WORK,
// trace_closest reports those counts in bvh_work (the debug views' heat map).

#import scene/hit-filter
#import scene/bindings
#import scene/intersect
#import scene/materials

// Whether trace_closest counts its work into bvh_work. A pipeline constant, off by default: the path
// tracer's traversal compiles without the counters; only passes/debug-view turns them on.
override BVH_COUNT_WORK: bool = false;

// A leaf index meaning "no leaf" (the ray hit nothing).
const NO_NODE: u32 = 0xffffffffu;

// The work of the last trace_closest, counted as bvh/traverse.ts counts it: nodes whose record the
// loop fetched (1 when the root box is missed), ray/triangle tests run, and the leaf holding the hit.
struct TraversalWork {
  nodes_visited: u32,
  triangles_tested: u32,
  hit_leaf: u32,
}

var<private> bvh_work: TraversalWork;

// The builder caps depth at 60 (bvh/build.ts); a push happens at most once per level.
const BVH_STACK_SIZE: u32 = 64u;

fn node_entry(node: u32, origin: vec3f, inv_dir: vec3f, t_best: f32) -> f32 {
  let n = bvh_nodes[node];
  return intersect_aabb(origin, inv_dir, n.aabb_min, n.aabb_max, t_best);
}

fn trace_closest(ray: Ray) -> Hit {
  var hit = Hit(ray.t_max, NO_TRIANGLE, 0.0, 0.0);
  set_alpha_salt(ray);
  if (BVH_COUNT_WORK) {
    bvh_work = TraversalWork(1u, 0u, NO_NODE);
  }
  let inv_dir = safe_inverse(ray.direction);
  if (node_entry(0u, ray.origin, inv_dir, hit.t) == T_MISS) {
    return hit;
  }
  if (BVH_COUNT_WORK) {
    bvh_work.nodes_visited = 0u;
  }
  var stack: array<u32, BVH_STACK_SIZE>;
  var sp = 0u;
  var node = 0u;
  loop {
    let n = bvh_nodes[node];
    if (BVH_COUNT_WORK) {
      bvh_work.nodes_visited += 1u;
    }
    if (n.tri_count > 0u) {
      for (var i = n.left_first; i < n.left_first + n.tri_count; i++) {
        let tri = triangles_hot[i];
        let r = intersect_primitive(ray.origin, ray.direction, tri, ray.t_min, hit.t);
        if (BVH_COUNT_WORK) {
          bvh_work.triangles_tested += 1u;
        }
        if (r.x < hit.t && accept_hit(tri, i, r.yz)) {
          hit = Hit(r.x, i, r.y, r.z);
          if (BVH_COUNT_WORK) {
            bvh_work.hit_leaf = node;
          }
        }
      }
      if (sp == 0u) {
        break;
      }
      sp -= 1u;
      node = stack[sp];
      continue;
    }
    var near = n.left_first;
    var far = near + 1u;
    var t_near = node_entry(near, ray.origin, inv_dir, hit.t);
    var t_far = node_entry(far, ray.origin, inv_dir, hit.t);
    if (t_far < t_near) {
      let swap_node = near;
      near = far;
      far = swap_node;
      let swap_t = t_near;
      t_near = t_far;
      t_far = swap_t;
    }
    if (t_near == T_MISS) {
      if (sp == 0u) {
        break;
      }
      sp -= 1u;
      node = stack[sp];
      continue;
    }
    if (t_far != T_MISS) {
      stack[sp] = far;
      sp += 1u;
    }
    node = near;
  }
  return hit;
}

// True when anything lies strictly between t_min and t_max along the ray. Children are visited in
// storage order: any hit ends the search, so ordering buys little.
fn trace_any(ray: Ray) -> bool {
  set_alpha_salt(ray);
  let inv_dir = safe_inverse(ray.direction);
  if (node_entry(0u, ray.origin, inv_dir, ray.t_max) == T_MISS) {
    return false;
  }
  var stack: array<u32, BVH_STACK_SIZE>;
  var sp = 0u;
  var node = 0u;
  loop {
    let n = bvh_nodes[node];
    if (n.tri_count > 0u) {
      for (var i = n.left_first; i < n.left_first + n.tri_count; i++) {
        let tri = triangles_hot[i];
        let r = intersect_primitive(ray.origin, ray.direction, tri, ray.t_min, ray.t_max);
        if (r.x < ray.t_max && accept_hit(tri, i, r.yz)) {
          return true;
        }
      }
    } else {
      let left = n.left_first;
      let hit_left = node_entry(left, ray.origin, inv_dir, ray.t_max) != T_MISS;
      let hit_right = node_entry(left + 1u, ray.origin, inv_dir, ray.t_max) != T_MISS;
      if (hit_left && hit_right) {
        stack[sp] = left + 1u;
        sp += 1u;
        node = left;
        continue;
      }
      if (hit_left || hit_right) {
        node = select(left + 1u, left, hit_left);
        continue;
      }
    }
    if (sp == 0u) {
      return false;
    }
    sp -= 1u;
    node = stack[sp];
  }
}
