// The torch: a small sphere of uniform radiance carried at the camera, sampled by next-event
// estimation only (it is not geometry). Directions are drawn uniformly in the cone the sphere
// subtends (pbrt-v4 §6.2.4, Sphere::Sample by solid angle), so shadows are soft and the estimate
// has no 1/d² spike near the light. Radiance L = I / (π r²) gives radiant intensity I far away.
// A smooth window (1 − (d/range)⁴)² fades it to zero at `range` (as Karis 2013, "Real Shading in
// Unreal Engine 4"): not physical, but it keeps a torch from lighting the whole level.
// Expects lib/constants and lib/sampling.

#import lib/constants
#import lib/sampling

struct TorchLight {
  // Radiance of the sphere's surface: colour × intensity / (π radius²). Zero when the torch is off.
  radiance: vec3f,
  radius: f32,
  range: f32,
}

struct TorchSample {
  // Unit direction from the shading point toward the sampled point of the sphere.
  direction: vec3f,
  // Distance to that point.
  distance: f32,
  // Radiance arriving along `direction`, windowed by range.
  radiance: vec3f,
  // Solid-angle density of `direction`.
  pdf: f32,
}

fn torch_window(distance: f32, range: f32) -> f32 {
  let x = clamp(distance / range, 0.0, 1.0);
  let x2 = x * x;
  let f = 1.0 - x2 * x2;
  return f * f;
}

// pdf = 0 when the torch contributes nothing here (off, out of range, or p inside the sphere).
fn sample_torch(torch: TorchLight, center: vec3f, p: vec3f, u: vec2f) -> TorchSample {
  var s = TorchSample(vec3f(0.0, 0.0, 1.0), 0.0, vec3f(0.0), 0.0);
  let to_center = center - p;
  let d2 = dot(to_center, to_center);
  let r2 = torch.radius * torch.radius;
  if (all(torch.radiance == vec3f(0.0)) || d2 <= r2 || d2 >= torch.range * torch.range) {
    return s;
  }
  let d = sqrt(d2);
  let sin2_max = r2 / d2;
  let cos_max = sqrt(max(0.0, 1.0 - sin2_max));
  // 1 − cos θmax without cancellation for small, distant spheres.
  let one_minus_cos_max = sin2_max / (1.0 + cos_max);
  let cos_theta = 1.0 - u.x * one_minus_cos_max;
  let sin2_theta = max(0.0, 1.0 - cos_theta * cos_theta);
  let phi = 2.0 * PI * u.y;
  let local = vec3f(cos(phi) * sqrt(sin2_theta), sin(phi) * sqrt(sin2_theta), cos_theta);
  s.direction = orthonormal_basis(to_center / d) * local;
  // Nearest intersection of that direction with the sphere.
  s.distance = d * cos_theta - sqrt(max(0.0, r2 - d2 * sin2_theta));
  s.radiance = torch.radiance * torch_window(d, torch.range);
  s.pdf = 1.0 / (2.0 * PI * one_minus_cos_max);
  return s;
}
