// Provides the environment: radiance of rays leaving the scene (baked lat-long map, sun excluded), its
// sampling by texel CDFs uniform in solid angle per texel, and the sun as a uniformly sampled cone.
// Expects scene/bindings (group 0, bindings 8–11). Follows pbrt-v4 (Pharr et al. 4th ed. §A.5, §12.5).

#import lib/constants
#import lib/sampling
#import scene/bindings

const TWO_PI_ENV: f32 = 6.28318530717959;

fn environment_has_map() -> bool {
  return (environment_info.flags & ENVIRONMENT_HAS_MAP) != 0u;
}

fn environment_has_sun() -> bool {
  return (environment_info.flags & ENVIRONMENT_HAS_SUN) != 0u;
}

// The map's frame from the world's: turn by −rotation about +y. With (c, s) = (cos ρ, sin ρ),
// world_from_map takes (x, z) to (x c + z s, −x s + z c) (+z toward +x for ρ > 0).
fn environment_map_from_world(d: vec3f) -> vec3f {
  let cs = environment_info.rotation_cos_sin;
  return vec3f(d.x * cs.x - d.z * cs.y, d.y, d.x * cs.y + d.z * cs.x);
}

fn environment_world_from_map(d: vec3f) -> vec3f {
  let cs = environment_info.rotation_cos_sin;
  return vec3f(d.x * cs.x + d.z * cs.y, d.y, -d.x * cs.y + d.z * cs.x);
}

// Lat-long coordinates of a unit map-space direction: u = 0.5 + atan2(x, −z) / 2π (the image centre
// looks down −z, u grows toward +x), v = θ / π with θ the angle from +y (top row = zenith).
fn environment_uv(d: vec3f) -> vec2f {
  let u = 0.5 + atan2(d.x, -d.z) / TWO_PI_ENV;
  let v = acos(clamp(d.y, -1.0, 1.0)) * INV_PI;
  return vec2f(u - floor(u), v);
}

// One texel (f32 radiance stored as u32 bits, see bindings.wgsl): columns wrap around (φ is periodic), rows clamp at the poles.
fn environment_texel(x: i32, y: i32) -> vec3f {
  let size = vec2i(environment_info.map_size);
  let xw = ((x % size.x) + size.x) % size.x;
  let yc = clamp(y, 0, size.y - 1);
  return bitcast<vec4f>(textureLoad(environment_map, vec2i(xw, yc), 0)).rgb;
}

// Bilinear between the four texel centres around uv (texel centres at (i + ½, j + ½) / size).
fn environment_map_bilinear(uv: vec2f) -> vec3f {
  let p = uv * vec2f(environment_info.map_size) - vec2f(0.5);
  let f = floor(p);
  let t = p - f;
  let x = i32(f.x);
  let y = i32(f.y);
  let top = mix(environment_texel(x, y), environment_texel(x + 1, y), t.x);
  let bottom = mix(environment_texel(x, y + 1), environment_texel(x + 1, y + 1), t.x);
  return mix(top, bottom, t.y);
}

// What a ray leaving the scene in world direction `direction` (unit) sees, excluding the sun's disk.
fn environment_radiance(direction: vec3f) -> vec3f {
  if (environment_info.kind == ENVIRONMENT_KIND_NONE) {
    return vec3f(0.0);
  }
  let uv = environment_uv(environment_map_from_world(direction));
  return environment_info.intensity * environment_map_bilinear(uv);
}

// Solid angle of one texel of row j: (2π / width) (cos θ_j − cos θ_{j+1}), written as
// 2 sin(θ_mid) sin(Δθ / 2) so that rows at the poles keep their precision in f32.
fn environment_texel_solid_angle(j: u32) -> f32 {
  let size = environment_info.map_size;
  let dtheta = PI / f32(size.y);
  let theta_mid = (f32(j) + 0.5) * dtheta;
  return (TWO_PI_ENV / f32(size.x)) * 2.0 * sin(theta_mid) * sin(0.5 * dtheta);
}

// The sampling CDFs, from environment_cdf (see scene/bindings.wgsl): row j < height holds entries
// 1..width of row j's conditional CDF, row height entries 1..height of the marginal CDF; entry 0 of
// each is 0 and not stored.
fn environment_marginal(j: u32) -> f32 {
  if (j == 0u) {
    return 0.0;
  }
  return bitcast<f32>(textureLoad(environment_cdf, vec2u(j - 1u, environment_info.map_size.y), 0).r);
}

fn environment_conditional(row: u32, i: u32) -> f32 {
  if (i == 0u) {
    return 0.0;
  }
  return bitcast<f32>(textureLoad(environment_cdf, vec2u(i - 1u, row), 0).r);
}

// Largest row j in [0, height) with marginal_cdf[j] ≤ u (binary search; cdf[0] = 0, cdf[height] = 1).
// Taking the largest skips rows of zero probability, whose CDF entries repeat.
fn environment_find_row(u: f32) -> u32 {
  var lo = 0u;
  var hi = environment_info.map_size.y;
  while (hi - lo > 1u) {
    let mid = (lo + hi) / 2u;
    if (environment_marginal(mid) <= u) { lo = mid; } else { hi = mid; }
  }
  return lo;
}

// Largest column i in [0, width) with conditional_cdf[row][i] ≤ u.
fn environment_find_column(row: u32, u: f32) -> u32 {
  var lo = 0u;
  var hi = environment_info.map_size.x;
  while (hi - lo > 1u) {
    let mid = (lo + hi) / 2u;
    if (environment_conditional(row, mid) <= u) { lo = mid; } else { hi = mid; }
  }
  return lo;
}

// Probability of texel (i, j): P(row j) · P(column i | row j), both differences of the CDFs.
fn environment_texel_probability(i: u32, j: u32) -> f32 {
  let p_row = environment_marginal(j + 1u) - environment_marginal(j);
  let p_column = environment_conditional(j, i + 1u) - environment_conditional(j, i);
  return p_row * p_column;
}

// Draws a direction with density ∝ the sampling weight of its texel, uniform in solid angle inside
// the texel (φ uniform, cos θ uniform between the row's edges): pdf(ω) = P(texel) / Ω(texel).
// u.y picks the row and then, rescaled, cos θ within it; u.x the column, then φ within it.
fn sample_environment(u: vec2f) -> EnvironmentSample {
  var s: EnvironmentSample;
  if (!environment_has_map()) {
    s.pdf = 0.0;
    return s;
  }
  let size = environment_info.map_size;
  let j = environment_find_row(u.y);
  let m0 = environment_marginal(j);
  let p_row = environment_marginal(j + 1u) - m0;
  let t = clamp((u.y - m0) / p_row, 0.0, 1.0);
  let i = environment_find_column(j, u.x);
  let c0 = environment_conditional(j, i);
  let p_column = environment_conditional(j, i + 1u) - c0;
  let f = clamp((u.x - c0) / p_column, 0.0, 1.0);

  let dtheta = PI / f32(size.y);
  let cos_top = cos(f32(j) * dtheta);
  let cos_bottom = cos(f32(j + 1u) * dtheta);
  let cos_theta = mix(cos_top, cos_bottom, t);
  let sin_theta = sqrt(max(0.0, 1.0 - cos_theta * cos_theta));
  let phi = TWO_PI_ENV * ((f32(i) + f) / f32(size.x) - 0.5);
  let d_map = vec3f(sin_theta * sin(phi), cos_theta, -sin_theta * cos(phi));

  s.direction = environment_world_from_map(d_map);
  s.radiance = environment_radiance(s.direction);
  s.pdf = p_row * p_column / environment_texel_solid_angle(j);
  return s;
}

// The solid-angle density with which sample_environment draws `direction` (unit, world space).
fn environment_pdf(direction: vec3f) -> f32 {
  if (!environment_has_map()) {
    return 0.0;
  }
  let size = environment_info.map_size;
  let uv = environment_uv(environment_map_from_world(direction));
  let i = min(u32(uv.x * f32(size.x)), size.x - 1u);
  let j = min(u32(uv.y * f32(size.y)), size.y - 1u);
  return environment_texel_probability(i, j) / environment_texel_solid_angle(j);
}

// Whether a unit direction lies inside the sun's disk: |d − s|² = 2 (1 − cos) ≤ 2 (1 − cos_max),
// computed from the difference vector, which keeps its precision where 1 − dot(d, s) would not.
// SUN_RIM_SLACK absorbs the rounding of sample_sun's directions at the rim (|d − s|² is off by
// ~1e-9 against 2 (1 − cos_max) ≈ 2.2e-5), so every sampled direction counts as inside; it widens
// the disk's radius by 0.01 %.
const SUN_RIM_SLACK: f32 = 1.000244; // 1 + 2^-12
fn environment_in_sun(direction: vec3f) -> bool {
  let delta = direction - environment_info.sun_direction;
  return dot(delta, delta) <= 2.0 * environment_info.sun_one_minus_cos_max * SUN_RIM_SLACK;
}

// Radiance of the sun's disk along `direction` (unit); zero outside it or without a sun.
fn sun_radiance(direction: vec3f) -> vec3f {
  if (!environment_has_sun() || !environment_in_sun(direction)) {
    return vec3f(0.0);
  }
  return environment_info.sun_radiance;
}

// Uniform over the sun's cone: 1 − cos θ = u.x (1 − cos θ_max), φ = 2π u.y; pdf = 1 / Ω_sun.
fn sample_sun(u: vec2f) -> EnvironmentSample {
  var s: EnvironmentSample;
  if (!environment_has_sun()) {
    s.pdf = 0.0;
    return s;
  }
  let one_minus_cos = u.x * environment_info.sun_one_minus_cos_max;
  let cos_theta = 1.0 - one_minus_cos;
  // sin²θ = (1 − cos)(1 + cos), exact for small angles.
  let sin_theta = sqrt(max(0.0, one_minus_cos * (2.0 - one_minus_cos)));
  let phi = TWO_PI_ENV * u.y;
  let local = vec3f(sin_theta * cos(phi), sin_theta * sin(phi), cos_theta);
  s.direction = normalize(orthonormal_basis(environment_info.sun_direction) * local);
  s.radiance = environment_info.sun_radiance;
  s.pdf = environment_info.sun_pdf;
  return s;
}

// The solid-angle density of sample_sun at `direction`.
fn sun_pdf(direction: vec3f) -> f32 {
  if (!environment_has_sun() || !environment_in_sun(direction)) {
    return 0.0;
  }
  return environment_info.sun_pdf;
}
