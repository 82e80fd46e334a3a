// INTERIM (replaced by the bsdf branch): the BSDF interface with the Lambertian case only.
#import lib/constants
#import lib/sampling

const BSDF_DIFFUSE: u32 = 0u;
const BSDF_METALLIC_ROUGHNESS: u32 = 1u;
const BSDF_DIELECTRIC: u32 = 2u;

struct BsdfParams {
  kind: u32,
  base_color: vec3f,
  metallic: f32,
  roughness: f32,
  ior: f32,
  transmission: f32,
  specular: f32,
  specular_color: vec3f,
  thin_walled: u32,
}

struct BsdfSample {
  wi: vec3f,
  weight: vec3f,
  pdf: f32,
  delta: bool,
  transmitted: bool,
  valid: bool,
}

fn bsdf_eval(p: BsdfParams, wo: vec3f, wi: vec3f) -> vec3f {
  return select(vec3f(0.0), p.base_color * INV_PI, wi.z > 0.0 && wo.z > 0.0);
}

fn bsdf_pdf(p: BsdfParams, wo: vec3f, wi: vec3f) -> f32 {
  return cosine_hemisphere_pdf(wi.z);
}

fn bsdf_sample(p: BsdfParams, wo: vec3f, u: vec3f) -> BsdfSample {
  let wi = sample_cosine_hemisphere(u.xy);
  return BsdfSample(wi, p.base_color, cosine_hemisphere_pdf(wi.z), false, false, wi.z > 0.0);
}

fn bsdf_has_non_delta(p: BsdfParams) -> bool {
  return true;
}

fn bsdf_albedo(p: BsdfParams, wo: vec3f) -> vec3f {
  return p.base_color;
}
