// The hybrid recipe's visibility buffer (Burns & Hunt 2013): the raster pass (passes/hybrid-raster)
// stores, per pixel, which primitive of which instance covers the pixel's jittered sample point; the
// compute passes (passes/hybrid) turn that back into the exact hit a camera ray through the same
// point would report: the ray is intersected with that one primitive, in the primitive's own space,
// so t, the barycentrics and everything surface_at derives from them are the ray tracer's.
// Expects the scene (group 0) and the view (group 1).

#import lib/constants
#import scene/bindings
#import scene/intersect
#import scene/instances
#import view/bindings

// A pixel the raster pass left uncovered (the sky or the void): both words of its texel.
const VISIBILITY_NONE: u32 = 0xffffffffu;

// The camera ray through image point `point` (pixels) in the space of `instance`'s primitives: world
// space for the static world, object space for a moving instance (direction transformed, not
// normalised, so t is the world ray's).
struct LocalRay {
  origin: vec3f,
  direction: vec3f,
}

fn local_ray(ray: Ray, instance: u32) -> LocalRay {
  if (instance_is_static(instance)) {
    return LocalRay(ray.origin, ray.direction);
  }
  let inst = instance_record(instance);
  return LocalRay(object_point(inst, ray.origin), object_vector(inst, ray.direction));
}

// Where a ray meets a triangle's plane: (t, u, v) by Möller–Trumbore without the inside test, the
// barycentrics clamped into the triangle. The raster pass decided coverage; a pixel centre a rounding
// error outside its triangle still gets that triangle's nearest point rather than a hole.
fn triangle_plane_hit(r: LocalRay, tri: TriangleHot) -> vec3f {
  let p = cross(r.direction, tri.e2);
  let det = dot(tri.e1, p);
  let inv = select(0.0, 1.0 / det, abs(det) > 1e-30);
  let s = r.origin - tri.v0;
  var u = dot(s, p) * inv;
  let q = cross(s, tri.e1);
  var v = dot(r.direction, q) * inv;
  let t = dot(tri.e2, q) * inv;
  u = clamp(u, 0.0, 1.0);
  v = clamp(v, 0.0, 1.0);
  let excess = max(u + v - 1.0, 0.0);
  return vec3f(t, u - 0.5 * excess, v - 0.5 * excess);
}

// The hit of `ray` on primitive `primitive` of `instance`, as trace_closest would report it; a miss
// (Hit.triangle = NO_TRIANGLE) for an uncovered pixel or a sphere the ray grazes past.
fn visible_hit(ray: Ray, id: vec2u) -> Hit {
  let none = Hit(T_MISS, NO_TRIANGLE, 0.0, 0.0, 0u);
  if (id.x == VISIBILITY_NONE) {
    return none;
  }
  let r = local_ray(ray, id.x);
  let tri = scene_triangle_hot(id.y);
  var h: vec3f;
  if (SCENE_HAS_ANALYTIC_PRIMITIVES && (tri.flags & PRIMITIVE_ANALYTIC) != 0u) {
    h = intersect_primitive(r.origin, r.direction, tri, 0.0, T_MISS);
    if (h.x == T_MISS) {
      return none;
    }
  } else {
    h = triangle_plane_hit(r, tri);
  }
  return Hit(h.x, id.y, h.y, h.z, id.x);
}
