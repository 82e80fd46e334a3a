// Spawning rays from a surface without hitting it again. Expects nothing.
// Follows Wächter & Binder 2019, "A Fast and Robust Method for Avoiding Self-Intersection" (Ray
// Tracing Gems, ch. 6): move the origin a few float ULPs along the normal, so the offset scales with
// the magnitude of the coordinates instead of being a scene-dependent epsilon.

// The point p moved off its surface to the side normal n (unit) points to.
fn offset_ray_origin(p: vec3f, n: vec3f) -> vec3f {
  let origin_threshold = 1.0 / 32.0;
  let float_scale = 1.0 / 65536.0;
  let int_scale = 256.0;
  let offset_int = vec3i(int_scale * n);
  let moved = bitcast<vec3f>(bitcast<vec3i>(p) + select(offset_int, -offset_int, p < vec3f(0.0)));
  return select(moved, p + float_scale * n, abs(p) < vec3f(origin_threshold));
}
