// The GGX (Trowbridge–Reitz) microfacet distribution, isotropic: D, Smith Λ, height-correlated G2,
// and sampling of the visible normals. Expects lib/constants. Follows Walter et al. 2007 (D, Λ),
// Heitz 2014 ("Understanding the Masking-Shadowing Function", G2) and Heitz 2018 ("Sampling the GGX
// Distribution of Visible Normals", JCGT 7(4)). Directions are in the local frame, z the normal.

#import lib/constants

// D(m) = α² / (π (cos²θm (α² − 1) + 1)²), for m in the upper hemisphere.
fn ggx_d(m: vec3f, alpha: f32) -> f32 {
  if (m.z <= 0.0) {
    return 0.0;
  }
  // cos²θ (α² − 1) + 1 written as cos²θ α² + sin²θ, with sin²θ from m.xy: no cancellation near the
  // peak, where the first form loses the digits that D (∝ 1/α² there) needs.
  let a2 = alpha * alpha;
  let t = m.z * m.z * a2 + dot(m.xy, m.xy);
  return a2 / (PI * t * t);
}

// Smith Λ(w) = (√(1 + α² tan²θ) − 1)/2, tan²θ = (1 − cos²θ)/cos²θ; symmetric in the side (|cos θ|).
fn ggx_lambda(w: vec3f, alpha: f32) -> f32 {
  let c2 = max(w.z * w.z, 1e-12);
  let tan2 = max(1.0 - c2, 0.0) / c2;
  return 0.5 * (sqrt(1.0 + alpha * alpha * tan2) - 1.0);
}

// Smith masking G1(w) = 1/(1 + Λ(w)).
fn ggx_g1(w: vec3f, alpha: f32) -> f32 {
  return 1.0 / (1.0 + ggx_lambda(w, alpha));
}

// Height-correlated masking-shadowing G2 = 1/(1 + Λ(wo) + Λ(wi)) (Heitz 2014, eq. 99). The caller
// checks that each direction is on the side of m it must be on (reflection: both above m's plane;
// refraction: wi below) — the χ⁺ factors.
fn ggx_g2(wo: vec3f, wi: vec3f, alpha: f32) -> f32 {
  return 1.0 / (1.0 + ggx_lambda(wo, alpha) + ggx_lambda(wi, alpha));
}

// A normal m from the visible normals D_wo(m) = G1(wo) max(0, wo·m) D(m) / wo.z, for wo.z > 0:
// stretch wo to the α = 1 configuration, where the visible normals are the uniform points of the
// hemisphere's projection onto the plane ⟂ wo — a disk whose half away from the view is squashed by
// cos — lift the disk point onto the hemisphere, and unstretch the normal (Heitz 2018, listing 1).
fn ggx_sample_visible_normal(wo: vec3f, alpha: f32, u: vec2f) -> vec3f {
  let vh = normalize(vec3f(alpha * wo.x, alpha * wo.y, wo.z));
  let lensq = vh.x * vh.x + vh.y * vh.y;
  var t1 = vec3f(1.0, 0.0, 0.0);
  if (lensq > 0.0) {
    t1 = vec3f(-vh.y, vh.x, 0.0) * inverseSqrt(lensq);
  }
  let t2 = cross(vh, t1);
  let r = sqrt(u.x);
  let phi = 2.0 * PI * u.y;
  let p1 = r * cos(phi);
  let s = 0.5 * (1.0 + vh.z);
  let p2 = (1.0 - s) * sqrt(max(0.0, 1.0 - p1 * p1)) + s * r * sin(phi);
  let nh = p1 * t1 + p2 * t2 + sqrt(max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
  return normalize(vec3f(alpha * nh.x, alpha * nh.y, max(1e-6, nh.z)));
}

// The density of ggx_sample_visible_normal: G1(wo) max(0, wo·m) D(m) / wo.z (wo.z > 0).
fn ggx_visible_normal_pdf(wo: vec3f, m: vec3f, alpha: f32) -> f32 {
  return ggx_g1(wo, alpha) * max(0.0, dot(wo, m)) * ggx_d(m, alpha) / wo.z;
}
