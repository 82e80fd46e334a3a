// Ray/box slab test, Möller–Trumbore ray/triangle intersection (Möller & Trumbore 1997, "Fast,
// Minimum Storage Ray/Triangle Intersection") and the analytic spheres and capsules, behind
// intersect_primitive. Expects lib/constants, lib/sampling. The CPU oracle in bvh/ray.ts mirrors
// these operation for operation, so GPU results can be checked against it.

#import lib/constants
#import lib/sampling

// 1/d with every component kept away from zero, so no infinities reach the slab test.
fn safe_inverse(d: vec3f) -> vec3f {
  let tiny = 1e-12;
  let sign = select(vec3f(-1.0), vec3f(1.0), d >= vec3f(0.0));
  let safe = select(d, sign * tiny, abs(d) < vec3f(tiny));
  return 1.0 / safe;
}

// Entry distance into the box, or T_MISS when the ray misses it or enters only at or beyond t_best.
// Each slab distance is one fused multiply-add, bmin · inv_dir − origin · inv_dir (measured faster on
// the H200 than (bmin − origin) · inv_dir: docs/perf.md, issue #14); bvh/ray.ts intersectAabb does
// the same.
fn intersect_aabb(origin: vec3f, inv_dir: vec3f, bmin: vec3f, bmax: vec3f, t_best: f32) -> f32 {
  let origin_inv = origin * inv_dir;
  let t0 = fma(bmin, inv_dir, -origin_inv);
  let t1 = fma(bmax, inv_dir, -origin_inv);
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

// The nearer root beyond t_min of a·t² + 2b·t + c = 0, where l = f − (b/a)·d is the closest approach
// of the line to the centre (so b² − a·c = a·(r² − |l|²) keeps its precision: Haines et al. 2019,
// "Precision Improvements for Ray/Sphere Intersection", Ray Tracing Gems ch. 7), and the stable pair
// t = c/q, q/a with q = −b − sign(b)·√(b² − a·c). Returns vec2(nearer valid root or T_MISS, farther root).
fn quadratic_roots(a: f32, b: f32, c: f32, l: vec3f, r: f32) -> vec2f {
  let disc = a * (r * r - dot(l, l));
  if (!(disc >= 0.0)) {
    return vec2f(T_MISS);
  }
  let q = -b - select(-1.0, 1.0, b >= 0.0) * sqrt(disc);
  if (q == 0.0) {
    return vec2f(T_MISS);
  }
  let t0 = c / q;
  let t1 = q / a;
  return vec2f(min(t0, t1), max(t0, t1));
}

// u = longitude / 2π around +y from +z, v = colatitude / π from +y, of direction n (any length).
fn sphere_uv(n: vec3f) -> vec2f {
  let u = atan2(n.x, n.z) * (0.5 * INV_PI);
  return vec2f(select(u, u + 1.0, u < 0.0), atan2(length(n.xz), n.y) * INV_PI);
}

// Ray/sphere (centre prim.v0, radius prim.e1.x): the nearer root in (t_min, t_best), so a ray inside
// (glass) finds the far side. Returns vec3f(t, u, v) with the surface uv, or t = T_MISS. The CPU twin
// is bvh/ray.ts intersectSphere.
fn intersect_sphere(origin: vec3f, direction: vec3f, prim: TriangleHot, t_min: f32, t_best: f32) -> vec3f {
  let f = origin - prim.v0;
  let r = prim.e1.x;
  let a = dot(direction, direction);
  let b = dot(f, direction);
  let roots = quadratic_roots(a, b, dot(f, f) - r * r, f - (b / a) * direction, r);
  let t = select(roots.y, roots.x, roots.x > t_min);
  if (t > t_min && t < t_best) {
    return vec3f(t, sphere_uv(f + t * direction));
  }
  return vec3f(T_MISS, 0.0, 0.0);
}

// Ray/capsule (end a = prim.v0, axis prim.e1 = b − a, radius prim.e2.x): the cylinder's roots with
// their axial coordinate y in [0, L] and the end spheres' roots beyond the ends (y ≤ 0 at a, y ≥ L
// at b) are exactly the capsule's boundary; the nearest in (t_min, t_best) wins. uv: u around the
// axis in the frame orthonormal_basis(axis), v = y / L. The CPU twin is bvh/ray.ts intersectCapsule.
fn intersect_capsule(origin: vec3f, direction: vec3f, prim: TriangleHot, t_min: f32, t_best: f32) -> vec3f {
  let r = prim.e2.x;
  let len = length(prim.e1);
  let w = select(vec3f(0.0, 1.0, 0.0), prim.e1 / len, len > 0.0);
  let f = origin - prim.v0;
  let fw = dot(f, w);
  let dw = dot(direction, w);
  var best = t_best;
  if (len > 0.0) {
    let p = direction - dw * w;
    let g = f - fw * w;
    let a = dot(p, p);
    if (a > 0.0) {
      let b = dot(g, p);
      let roots = quadratic_roots(a, b, dot(g, g) - r * r, g - (b / a) * p, r);
      for (var k = 0u; k < 2u; k++) {
        let t = roots[k];
        let y = fw + t * dw;
        if (t > t_min && t < best && y >= 0.0 && y <= len) {
          best = t;
        }
      }
    }
  }
  let a = dot(direction, direction);
  for (var end = 0u; end < 2u; end++) {
    let s = f - f32(end) * len * w;
    let b = dot(s, direction);
    let roots = quadratic_roots(a, b, dot(s, s) - r * r, s - (b / a) * direction, r);
    for (var k = 0u; k < 2u; k++) {
      let t = roots[k];
      let y = fw + t * dw;
      let beyond = select(y <= 0.0, y >= len, end == 1u);
      if (t > t_min && t < best && beyond) {
        best = t;
      }
    }
  }
  if (!(best < t_best)) {
    return vec3f(T_MISS, 0.0, 0.0);
  }
  let frame = orthonormal_basis(w);
  let h = f + best * direction;
  let u = atan2(dot(h, frame[1]), dot(h, frame[0])) * (0.5 * INV_PI);
  let v = select(0.5, clamp((fw + best * dw) / len, 0.0, 1.0), len > 0.0);
  return vec3f(best, select(u, u + 1.0, u < 0.0), v);
}

// Whether the scene has spheres or capsules. A pipeline constant: a scene of triangles only compiles
// the kind test away and traces exactly as before analytic primitives existed.
override SCENE_HAS_ANALYTIC_PRIMITIVES: bool = true;

// Any primitive: vec3f(t, u, v) as the test of its kind returns, or t = T_MISS.
fn intersect_primitive(origin: vec3f, direction: vec3f, prim: TriangleHot, t_min: f32, t_best: f32) -> vec3f {
  if (SCENE_HAS_ANALYTIC_PRIMITIVES && (prim.flags & PRIMITIVE_ANALYTIC) != 0u) {
    if ((prim.flags & PRIMITIVE_SPHERE) != 0u) {
      return intersect_sphere(origin, direction, prim, t_min, t_best);
    }
    return intersect_capsule(origin, direction, prim, t_min, t_best);
  }
  return intersect_triangle(origin, direction, prim, t_min, t_best);
}
