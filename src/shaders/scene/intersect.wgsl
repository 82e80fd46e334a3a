// Ray/box slab test and Möller–Trumbore ray/triangle intersection (Möller & Trumbore 1997, "Fast,
// Minimum Storage Ray/Triangle Intersection"). Expects lib/constants. The CPU oracle in bvh/ray.ts
// mirrors these operation for operation, so GPU results can be checked against it.

#import lib/constants

// 1/d with every component kept away from zero, so no infinities reach the slab test.
fn safe_inverse(d: vec3f) -> vec3f {
  let tiny = 1e-12;
  let sign = select(vec3f(-1.0), vec3f(1.0), d >= vec3f(0.0));
  let safe = select(d, sign * tiny, abs(d) < vec3f(tiny));
  return 1.0 / safe;
}

// Entry distance into the box, or T_MISS when the ray misses it or enters only at or beyond t_best.
fn intersect_aabb(origin: vec3f, inv_dir: vec3f, bmin: vec3f, bmax: vec3f, t_best: f32) -> f32 {
  let t0 = (bmin - origin) * inv_dir;
  let t1 = (bmax - origin) * inv_dir;
  let near = min(t0, t1);
  let far = max(t0, t1);
  let t_near = max(max(near.x, near.y), near.z);
  let t_far = min(min(far.x, far.y), far.z);
  let hit = t_near <= t_far && t_far >= 0.0 && t_near < t_best;
  return select(T_MISS, t_near, hit);
}

// Returns vec3f(t, u, v) where u, v are the barycentric weights of v1 and v2, or t = T_MISS.
fn intersect_triangle(origin: vec3f, direction: vec3f, tri: TriangleHot, t_min: f32, t_best: f32) -> vec3f {
  let p = cross(direction, tri.e2);
  let det = dot(tri.e1, p);
  if (abs(det) < 1e-30) {
    return vec3f(T_MISS, 0.0, 0.0);
  }
  let inv_det = 1.0 / det;
  let s = origin - tri.v0;
  let u = dot(s, p) * inv_det;
  if (u < 0.0 || u > 1.0) {
    return vec3f(T_MISS, 0.0, 0.0);
  }
  let q = cross(s, tri.e1);
  let v = dot(direction, q) * inv_det;
  if (v < 0.0 || u + v > 1.0) {
    return vec3f(T_MISS, 0.0, 0.0);
  }
  let t = dot(tri.e2, q) * inv_det;
  if (t > t_min && t < t_best) {
    return vec3f(t, u, v);
  }
  return vec3f(T_MISS, 0.0, 0.0);
}
