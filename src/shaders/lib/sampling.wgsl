// Sampling routines: cosine-weighted hemisphere (Malley's method over Shirley & Chiu's concentric
// disk map), uniform triangle points, an orthonormal basis around a normal (Duff et al. 2017,
// "Building an Orthonormal Basis, Revisited", JCGT 6(1)), and the power heuristic for multiple
// importance sampling (Veach 1997, §9.2). Expects lib/constants.

#import lib/constants

// Tangent-space to world: columns t, b, n with n the given unit normal.
fn orthonormal_basis(n: vec3f) -> mat3x3f {
  let s = select(-1.0, 1.0, n.z >= 0.0);
  let a = -1.0 / (s + n.z);
  let b = n.x * n.y * a;
  let t = vec3f(1.0 + s * n.x * n.x * a, s * b, -s * n.x);
  let bt = vec3f(b, s + n.y * n.y * a, -n.y);
  return mat3x3f(t, bt, n);
}

// Maps the unit square to the unit disk with low distortion (Shirley & Chiu 1997).
fn concentric_disk(u: vec2f) -> vec2f {
  let p = 2.0 * u - vec2f(1.0);
  if (p.x == 0.0 && p.y == 0.0) {
    return vec2f(0.0);
  }
  var r: f32;
  var phi: f32;
  if (abs(p.x) > abs(p.y)) {
    r = p.x;
    phi = (PI / 4.0) * (p.y / p.x);
  } else {
    r = p.y;
    phi = (PI / 2.0) - (PI / 4.0) * (p.x / p.y);
  }
  return r * vec2f(cos(phi), sin(phi));
}

// A direction in the hemisphere around +z with density cos(θ)/π (tangent space).
fn sample_cosine_hemisphere(u: vec2f) -> vec3f {
  let d = concentric_disk(u);
  let z = sqrt(max(0.0, 1.0 - dot(d, d)));
  return vec3f(d, z);
}

fn cosine_hemisphere_pdf(cos_theta: f32) -> f32 {
  return max(cos_theta, 0.0) * INV_PI;
}

// Barycentric weights (of v1, v2) of a point uniformly distributed over a triangle.
fn sample_triangle_uniform(u: vec2f) -> vec2f {
  let su = sqrt(u.x);
  return vec2f(su * (1.0 - u.y), su * u.y);
}

// A direction uniformly distributed on the unit sphere.
fn sample_sphere_uniform(u: vec2f) -> vec3f {
  let z = 1.0 - 2.0 * u.x;
  let r = sqrt(max(0.0, 1.0 - z * z));
  let phi = 2.0 * PI * u.y;
  return vec3f(r * cos(phi), r * sin(phi), z);
}

// Power heuristic with β = 2 for two strategies with one sample each.
fn power_heuristic(pdf_a: f32, pdf_b: f32) -> f32 {
  let a2 = pdf_a * pdf_a;
  let b2 = pdf_b * pdf_b;
  return select(0.0, a2 / (a2 + b2), a2 > 0.0);
}
