// Traversal without a BVH for small frozen scenes: trace_closest and trace_any with scene/bvh's
// signatures, testing every primitive of the generated module scene/specialised-primitives (its data
// as constants, one call per primitive: gpu/pack/primitives-module.ts writes it from triangles_hot).
// gpu/specialisation.ts links this module wherever scene/bvh is imported. Expects the scene bindings
// (group 0) for shading and alpha tests. Hits are leaf-order indices, exactly as scene/bvh's.

#import scene/hit-filter
#import scene/bindings
#import scene/intersect
#import scene/materials
#import scene/specialised-primitives
#import scene/accel

// Declared for the scene features' constants (gpu/kernel-variants.ts FEATURE_CONSTANTS; STATIC_ACCEL comes
// with scene/accel): an unrolled scene tests every primitive and has no grid, wide tree or stack.
override BVH_SHALLOW_STACK: bool = false;

// The one intersection routine every primitive goes through: scene/intersect's intersect_primitive,
// which reads the kind (triangle, sphere, capsule) from the record's flags; with the record constant,
// the compiler keeps only that kind's test. vec3f(t, u, v), or t = T_MISS.
fn unrolled_intersect(ray: Ray, prim: TriangleHot, t_best: f32) -> vec3f {
  return intersect_primitive(ray.origin, ray.direction, prim, ray.t_min, t_best);
}

// Closest-hit test of one primitive: `hit` becomes it when it is nearer and passes the alpha test.
// The generated unrolled_closest calls this once per primitive with constant arguments.
fn closest_candidate(ray: Ray, prim: TriangleHot, index: u32, hit: ptr<function, Hit>) {
  let r = unrolled_intersect(ray, prim, (*hit).t);
  if (r.x < (*hit).t && accept_hit(prim, index, r.yz)) {
    *hit = Hit(r.x, index, r.y, r.z, 0u);
  }
}

// Any-hit test of one primitive against (t_min, t_max).
fn any_candidate(ray: Ray, prim: TriangleHot, index: u32) -> bool {
  let r = unrolled_intersect(ray, prim, ray.t_max);
  return r.x < ray.t_max && accept_hit(prim, index, r.yz);
}

fn trace_closest(ray: Ray) -> Hit {
  var hit = Hit(ray.t_max, NO_TRIANGLE, 0.0, 0.0, 0u);
  set_alpha_salt(ray);
  unrolled_closest(ray, &hit);
  return hit;
}

// True when anything lies strictly between t_min and t_max along the ray.
fn trace_any(ray: Ray) -> bool {
  set_alpha_salt(ray);
  return unrolled_any(ray);
}
