// Fresnel reflectance: the exact unpolarized dielectric formula (total internal reflection included)
// and Schlick's approximation. Expects nothing. Follows Walter et al. 2007 ("Microfacet Models for
// Refraction through Rough Surfaces", eq. 22) and Schlick 1994; glTF 2.0 Appendix B uses the latter.

// Unpolarized reflectance of a smooth dielectric interface for light arriving at cos θi ≥ 0, with
// eta = n_t / n_i the relative index across it. With sin²θt = (1 − cos²θi)/η² (Snell):
//   r_s = (cos θi − η cos θt)/(cos θi + η cos θt),  r_p = (η cos θi − cos θt)/(η cos θi + cos θt),
//   F = (r_s² + r_p²)/2, and F = 1 when sin²θt ≥ 1 (total internal reflection).
fn fresnel_dielectric(cos_i: f32, eta: f32) -> f32 {
  let c = clamp(cos_i, 0.0, 1.0);
  let sin2_t = (1.0 - c * c) / (eta * eta);
  if (sin2_t >= 1.0) {
    return 1.0;
  }
  let cos_t = sqrt(1.0 - sin2_t);
  let r_s = (c - eta * cos_t) / (c + eta * cos_t);
  let r_p = (eta * c - cos_t) / (eta * c + cos_t);
  return 0.5 * (r_s * r_s + r_p * r_p);
}

// Schlick: F0 + (1 − F0)(1 − cos θ)⁵, per channel.
fn fresnel_schlick(f0: vec3f, cos_theta: f32) -> vec3f {
  let m = 1.0 - clamp(cos_theta, 0.0, 1.0);
  let m2 = m * m;
  return f0 + (vec3f(1.0) - f0) * (m2 * m2 * m);
}

// Reflectance at normal incidence of an interface between ior and 1: ((ior − 1)/(ior + 1))².
fn fresnel_f0_from_ior(ior: f32) -> f32 {
  let r = (ior - 1.0) / (ior + 1.0);
  return r * r;
}
