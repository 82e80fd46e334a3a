// The static world through a wide tree (bvh/wide.ts: scene/bvh4 or scene/cwbvh), for scene/bvh's
// trace_closest and trace_any, as scene/grid serves them: the top level over moving instances runs
// after it, pruned by its hit. Expects the scene bindings (group 0).

#import scene/bvh4
#import scene/cwbvh

// Whether the static world is walked through a wide tree instead of its binary BVH.
fn static_accel_wide() -> bool {
  return STATIC_ACCEL == ACCEL_BVH4 || STATIC_ACCEL == ACCEL_CWBVH;
}

// The closest hit of the static world before (*hit).t; returns (nodes fetched, primitives tested).
fn wide_closest(origin: vec3f, direction: vec3f, inv_dir: vec3f, t_min: f32, hit: ptr<function, Hit>) -> vec2u {
  if (STATIC_ACCEL == ACCEL_BVH4) {
    return bvh4_closest(origin, direction, inv_dir, t_min, hit);
  }
  return cwbvh_closest(origin, direction, inv_dir, t_min, hit);
}

fn wide_any(origin: vec3f, direction: vec3f, inv_dir: vec3f, t_min: f32, t_max: f32) -> bool {
  if (STATIC_ACCEL == ACCEL_BVH4) {
    return bvh4_any(origin, direction, inv_dir, t_min, t_max);
  }
  return cwbvh_any(origin, direction, inv_dir, t_min, t_max);
}
