// BVH traversal: closest hit with an ordered stack (nearer child first, the closest hit so far prunes
// boxes), and any hit for shadow rays. Alpha-masked triangles count only where their texture is
// opaque. Expects the scene bindings (group 0). The CPU oracles bvh/traverse.ts (one level) and
// bvh/levels.ts traceScene (two levels) run the same algorithm, so hits and visited-node counts
// agree; with BVH_COUNT_WORK, trace_closest reports those counts in bvh_work (the debug views' heat
// map), both levels together.
//
// With moving instances (SCENE_HAS_INSTANCES) the same loop runs over the top-level tree, whose
// leaves are instances: the ray enters each instance's object space (its direction transformed, not
// normalised, so t is the same in both spaces) and its bottom level is traced from its root. The
// hit then says which instance; the primitive records are read through scene/instances.
//
// With STATIC_ACCEL = ACCEL_GRID (scene/accel; scene/grid.wgsl) the static world is walked through its uniform grid
// instead of its tree, then the top level runs as above, pruned by the grid's hit; likewise through
// its wide tree with ACCEL_BVH4 or ACCEL_CWBVH (scene/wide.wgsl).

#import scene/hit-filter
#import scene/bindings
#import scene/intersect
#import scene/materials
#import scene/instances
#import scene/grid
#import scene/wide

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

// A scene whose stack never holds more than BVH_SHALLOW_STACK_SIZE entries (no moving instances, a
// static tree at most that deep: scene-pack features.shallowStack) traces with a stack of that size
// instead: less per-thread memory. On the H200 it made the Dragon's rays 2–9 % faster (docs/perf.md).
// The unused array is folded away with the constant.
override BVH_SHALLOW_STACK: bool = false;
const BVH_SHALLOW_STACK_SIZE: u32 = 32u;

// The loop below is deliberately plain. Measured on the H200 (docs/perf.md, issue #14), each of these
// made the Dragon's rays slower (by up to 28 %): carrying the entered child's record from the box test instead
// of fetching it again (the second fetch hits the cache; the records cost registers), and dropping
// popped nodes that start beyond the closest hit (by re-testing the box, or by pushing entry distances:
// the extra work in the pop path costs more than the visits it saves on a closed mesh).
fn node_entry(node: u32, origin: vec3f, inv_dir: vec3f, t_best: f32) -> f32 {
  let n = scene_bvh_node(node);
  return intersect_aabb(origin, inv_dir, n.aabb_min, n.aabb_max, t_best);
}

// The instance a traversal is in while it walks the top level (no bottom level entered yet).
const NO_INSTANCE: u32 = 0xffffffffu;

// The ray as the traversal loop tests it: in world space, or in the object space of the instance
// whose bottom level it is in (the direction transformed, not normalised, so t is the same).
struct TraversalRay {
  origin: vec3f,
  direction: vec3f,
  inv_dir: vec3f,
}

// The ray in instance `instance`'s space (0: the world; the static world is stored in it), its alpha
// test following that instance's material.
fn traversal_ray(ray: Ray, instance: u32) -> TraversalRay {
  set_filter_instance(instance);
  if (instance_is_static(instance)) {
    return TraversalRay(ray.origin, ray.direction, safe_inverse(ray.direction));
  }
  let inst = instance_record(instance);
  let direction = object_vector(inst, ray.direction);
  return TraversalRay(object_point(inst, ray.origin), direction, safe_inverse(direction));
}

// Where a traversal starts (node, instance): the static world's root, or the top level's when the ray
// misses the static world (or it is empty); node NO_NODE when it misses both before t.
fn traversal_start(local: TraversalRay, t: f32) -> vec2u {
  let static_world = STATIC_ACCEL != ACCEL_GRID && !static_accel_wide() && !(SCENE_HAS_INSTANCES && scene_info.static_world_empty != 0u);
  if (static_world && node_entry(0u, local.origin, local.inv_dir, t) != T_MISS) {
    return vec2u(0u, 0u);
  }
  if (SCENE_HAS_INSTANCES && node_entry(scene_info.tlas_root, local.origin, local.inv_dir, t) != T_MISS) {
    return vec2u(scene_info.tlas_root, NO_INSTANCE);
  }
  return vec2u(NO_NODE, 0u);
}

// The traversal stack's entry at depth sp, written and read in the stack the scene uses
// (BVH_SHALLOW_STACK): the loops declare both, and the unused one folds away.
fn bvh_stack_push(stack: ptr<function, array<u32, BVH_STACK_SIZE>>, shallow_stack: ptr<function, array<u32, BVH_SHALLOW_STACK_SIZE>>, sp: u32, node: u32) {
  if (BVH_SHALLOW_STACK) {
    (*shallow_stack)[sp] = node;
  } else {
    (*stack)[sp] = node;
  }
}

fn bvh_stack_entry(stack: ptr<function, array<u32, BVH_STACK_SIZE>>, shallow_stack: ptr<function, array<u32, BVH_SHALLOW_STACK_SIZE>>, sp: u32) -> u32 {
  if (BVH_SHALLOW_STACK) {
    return (*shallow_stack)[sp];
  }
  return (*stack)[sp];
}

// A top-level leaf entered: the traversal goes into `entered`'s bottom level, the ray in that
// instance's space, until the stack is back at depth sp. Returns the bottom level's root.
fn enter_instance(ray: Ray, entered: u32, sp: u32, instance: ptr<function, u32>, local: ptr<function, TraversalRay>, leave_at: ptr<function, u32>) -> u32 {
  *instance = entered;
  *local = traversal_ray(ray, entered);
  *leave_at = sp;
  return instance_record(entered).blas_root;
}

// One loop walks both levels with one stack, so that a scene with moving instances compiles to about
// the code (and the registers) of the single-level loop. It starts in the static world's tree (root
// 0, world space: exactly the single-level traversal), then walks the top level over the moving
// instances with the static hit's distance pruning it. Entering a top-level leaf switches the ray to
// the instance's object space and notes the stack depth; when the stack is back at that depth the
// bottom level is done and the ray returns to world space. Without moving instances the switches
// fold away.
fn trace_closest(ray: Ray) -> Hit {
  var hit = Hit(ray.t_max, NO_TRIANGLE, 0.0, 0.0, 0u);
  set_alpha_salt(ray);
  if (BVH_COUNT_WORK) {
    // Through the grid, the count is of cells (none when the ray misses the grid) plus top-level nodes.
    bvh_work = TraversalWork(select(1u, 0u, STATIC_ACCEL == ACCEL_GRID || static_accel_wide()), 0u, NO_NODE);
  }
  var local = traversal_ray(ray, 0u);
  if (STATIC_ACCEL == ACCEL_GRID && !(SCENE_HAS_INSTANCES && scene_info.static_world_empty != 0u)) {
    // The static world through its grid: cells count as nodes. The leaf views (leaf size, BVH
    // depth) have no leaf to show for a grid hit and show the root's.
    let work = grid_closest(local.origin, local.direction, local.inv_dir, ray.t_min, &hit);
    if (BVH_COUNT_WORK) {
      bvh_work = TraversalWork(work.x, work.y, select(NO_NODE, 0u, hit.triangle != NO_TRIANGLE));
    }
  } else if (static_accel_wide() && !(SCENE_HAS_INSTANCES && scene_info.static_world_empty != 0u)) {
    // The static world through its wide tree: wide nodes count as nodes; the leaf views show the root's.
    let work = wide_closest(local.origin, local.direction, local.inv_dir, ray.t_min, &hit);
    if (BVH_COUNT_WORK) {
      bvh_work = TraversalWork(work.x, work.y, select(NO_NODE, 0u, hit.triangle != NO_TRIANGLE));
    }
  }
  let start = traversal_start(local, hit.t);
  if (start.x == NO_NODE) {
    return hit;
  }
  var node = start.x;
  var instance = start.y;
  var leave_at = 0u;
  if (BVH_COUNT_WORK && STATIC_ACCEL != ACCEL_GRID && !static_accel_wide()) {
    bvh_work.nodes_visited = 0u;
  }
  var stack: array<u32, BVH_STACK_SIZE>;
  var shallow_stack: array<u32, BVH_SHALLOW_STACK_SIZE>;
  var sp = 0u;
  loop {
    let n = scene_bvh_node(node);
    if (BVH_COUNT_WORK) {
      bvh_work.nodes_visited += 1u;
    }
    var descend = false;
    if (n.tri_count > 0u) {
      if (SCENE_HAS_INSTANCES && instance == NO_INSTANCE) {
        node = enter_instance(ray, n.left_first, sp, &instance, &local, &leave_at);
        continue;
      }
      for (var i = n.left_first; i < n.left_first + n.tri_count; i++) {
        let tri = scene_triangle_hot(i);
        let r = intersect_primitive(local.origin, local.direction, tri, ray.t_min, hit.t);
        if (BVH_COUNT_WORK) {
          bvh_work.triangles_tested += 1u;
        }
        if (r.x < hit.t && accept_hit(tri, i, r.yz)) {
          hit = Hit(r.x, i, r.y, r.z, instance);
          if (BVH_COUNT_WORK) {
            bvh_work.hit_leaf = node;
          }
        }
      }
    } else {
      var near = n.left_first;
      var far = near + 1u;
      var t_near = node_entry(near, local.origin, local.inv_dir, hit.t);
      var t_far = node_entry(far, local.origin, local.inv_dir, hit.t);
      if (t_far < t_near) {
        let swap_node = near;
        near = far;
        far = swap_node;
        let swap_t = t_near;
        t_near = t_far;
        t_far = swap_t;
      }
      if (t_near != T_MISS) {
        if (t_far != T_MISS) {
          bvh_stack_push(&stack, &shallow_stack, sp, far);
          sp += 1u;
        }
        node = near;
        descend = true;
      }
    }
    if (descend) {
      continue;
    }
    if (SCENE_HAS_INSTANCES && instance != NO_INSTANCE && sp == leave_at) {
      if (instance == 0u) {
        // The static world is done: on to the moving instances, if the closest hit so far leaves room.
        instance = NO_INSTANCE;
        if (node_entry(scene_info.tlas_root, local.origin, local.inv_dir, hit.t) == T_MISS) {
          break;
        }
        node = scene_info.tlas_root;
        continue;
      }
      // The bottom level is done: back to the top level in world space.
      instance = NO_INSTANCE;
      local = traversal_ray(ray, 0u);
    }
    if (sp == 0u) {
      break;
    }
    sp -= 1u;
    node = bvh_stack_entry(&stack, &shallow_stack, sp);
  }
  // A mirroring instance's world triangle has v1 and v2 swapped (scene/instances world_primitive): so do the barycentrics.
  if (SCENE_HAS_INSTANCES && hit.triangle != NO_TRIANGLE && instance_mirrored(hit.instance) && (scene_triangle_flags(hit.triangle) & PRIMITIVE_ANALYTIC) == 0u) {
    let u = hit.u;
    hit.u = hit.v;
    hit.v = u;
  }
  return hit;
}

// True when anything lies strictly between t_min and t_max along the ray. Children are visited in
// storage order: any hit ends the search, so ordering buys little. Both levels in one loop, as
// trace_closest walks them.
fn trace_any(ray: Ray) -> bool {
  set_alpha_salt(ray);
  var local = traversal_ray(ray, 0u);
  if (STATIC_ACCEL == ACCEL_GRID && !(SCENE_HAS_INSTANCES && scene_info.static_world_empty != 0u) && grid_any(local.origin, local.direction, local.inv_dir, ray.t_min, ray.t_max)) {
    return true;
  } else if (static_accel_wide() && !(SCENE_HAS_INSTANCES && scene_info.static_world_empty != 0u) && wide_any(local.origin, local.direction, local.inv_dir, ray.t_min, ray.t_max)) {
    return true;
  }
  let start = traversal_start(local, ray.t_max);
  if (start.x == NO_NODE) {
    return false;
  }
  var node = start.x;
  var instance = start.y;
  var leave_at = 0u;
  var stack: array<u32, BVH_STACK_SIZE>;
  var shallow_stack: array<u32, BVH_SHALLOW_STACK_SIZE>;
  var sp = 0u;
  loop {
    let n = scene_bvh_node(node);
    if (n.tri_count > 0u) {
      if (SCENE_HAS_INSTANCES && instance == NO_INSTANCE) {
        node = enter_instance(ray, n.left_first, sp, &instance, &local, &leave_at);
        continue;
      }
      for (var i = n.left_first; i < n.left_first + n.tri_count; i++) {
        let tri = scene_triangle_hot(i);
        let r = intersect_primitive(local.origin, local.direction, tri, ray.t_min, ray.t_max);
        if (r.x < ray.t_max && accept_hit(tri, i, r.yz)) {
          return true;
        }
      }
    } else {
      let left = n.left_first;
      let hit_left = node_entry(left, local.origin, local.inv_dir, ray.t_max) != T_MISS;
      let hit_right = node_entry(left + 1u, local.origin, local.inv_dir, ray.t_max) != T_MISS;
      if (hit_left && hit_right) {
        bvh_stack_push(&stack, &shallow_stack, sp, left + 1u);
        sp += 1u;
        node = left;
        continue;
      }
      if (hit_left || hit_right) {
        node = select(left + 1u, left, hit_left);
        continue;
      }
    }
    if (SCENE_HAS_INSTANCES && instance != NO_INSTANCE && sp == leave_at) {
      if (instance == 0u) {
        instance = NO_INSTANCE;
        if (node_entry(scene_info.tlas_root, local.origin, local.inv_dir, ray.t_max) == T_MISS) {
          return false;
        }
        node = scene_info.tlas_root;
        continue;
      }
      // The bottom level is done: back to the top level in world space.
      instance = NO_INSTANCE;
      local = traversal_ray(ray, 0u);
    }
    if (sp == 0u) {
      break;
    }
    sp -= 1u;
    node = bvh_stack_entry(&stack, &shallow_stack, sp);
  }
  // After the loop, not inside it: naga (the fragment tracer's GLSL translation) wants a return at
  // the end of a function that returns a value.
  return false;
}
