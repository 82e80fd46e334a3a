// The BSDF of every material kind: bsdf_eval, bsdf_pdf, bsdf_sample, bsdf_albedo in the local shading
// frame (z = the front normal; for glass the front side is outside). Expects the energy tables
// (scene/bsdf-tables, binding 12). Follows glTF 2.0 Appendix B with KHR_materials_specular/_ior/
// _transmission, Walter et al. 2007 (rough refraction), Heitz 2018 (visible normals) and Kulla & Conty
// 2017 (energy compensation). docs/bsdf.md explains the model; this file carries the formulas.

#import lib/constants
#import lib/color
#import lib/sampling
#import lib/fresnel
#import lib/microfacet
#import scene/bsdf-tables

// The closed set of material kinds.
const BSDF_DIFFUSE: u32 = 0u;              // Lambertian, base_color = albedo, two-sided
const BSDF_METALLIC_ROUGHNESS: u32 = 1u;   // the glTF 2.0 metallic-roughness model (with KHR_materials_specular, _ior, _transmission)
const BSDF_DIELECTRIC: u32 = 2u;           // glass: Fresnel reflection + refraction, smooth or rough (Walter et al. 2007)

// What the scene's materials need, one mask of MATERIALS_* bits (a pipeline constant: the host sets
// it per scene, gpu/kernel-variants.ts). MATERIALS_GENERAL: any material is not diffuse (or has a
// normal map, or absorbs); without it the integrator compiles the Lambertian path alone, and scenes
// of diffuse surfaces (the Cornell box, Doom) run as fast as before the BSDF module existed. The kind
// bits say which BSDF kinds occur: where one is absent its branch of bsdf_lobes folds away, and with it
// the lobes only that kind weights. Generic kernels keep both kind bits set; kernels specialised to a
// frozen scene (gpu/specialisation.ts) clear those it lacks.
const MATERIALS_GENERAL: u32 = 1u;
const MATERIALS_METALLIC_ROUGHNESS: u32 = 2u;
const MATERIALS_DIELECTRIC: u32 = 4u;
override SCENE_MATERIALS: u32 = MATERIALS_GENERAL | MATERIALS_METALLIC_ROUGHNESS | MATERIALS_DIELECTRIC;
// The mask's bits by name, for the code that folds on them (derived: never set by the host).
override SCENE_HAS_GENERAL_MATERIALS: bool = (SCENE_MATERIALS & MATERIALS_GENERAL) != 0u;
override SCENE_HAS_METALLIC_ROUGHNESS: bool = (SCENE_MATERIALS & MATERIALS_METALLIC_ROUGHNESS) != 0u;
override SCENE_HAS_DIELECTRIC: bool = (SCENE_MATERIALS & MATERIALS_DIELECTRIC) != 0u;

// Below this GGX alpha (roughness ≈ 0.032) a microfacet lobe is treated as a perfect mirror or
// refraction (a delta lobe): its width (~α radians, < 0.06°) is below any pixel's footprint, and
// D ∝ 1/α² would overflow the f32 range of the pdf long before α reaches 0.
const BSDF_ALPHA_DELTA: f32 = 1e-3;
// Directions this close to the surface plane (|cos θ|) carry nothing: every lobe has a cos or 1/cos
// factor that degenerates there.
const BSDF_COS_MIN: f32 = 1e-6;
// Guard for divisions by 1 − E_avg (a lobe that already keeps all its energy needs no compensation).
const BSDF_ENERGY_EPSILON: f32 = 1e-4;
// Schlick's Fresnel averaged over the cosine-weighted hemisphere: 2∫(1 − μ)⁵ μ dμ = 1/21.
const SCHLICK_AVERAGE_TAIL: f32 = 1.0 / 21.0;

// A material resolved at one shading point (textures already applied by the caller).
struct BsdfParams {
  kind: u32,
  base_color: vec3f,     // linear RGB. DIFFUSE: albedo. METALLIC_ROUGHNESS: glTF baseColor (metal F0, diffuse albedo, transmission tint). DIELECTRIC: transmission tint (1 = clear)
  metallic: f32,         // [0,1]
  roughness: f32,        // perceptual roughness [0,1] as glTF defines it; GGX alpha = roughness²
  ior: f32,              // index of refraction of the material; outside is 1
  transmission: f32,     // KHR_materials_transmission factor [0,1] (METALLIC_ROUGHNESS only)
  specular: f32,         // KHR_materials_specular specularFactor (default 1)
  specular_color: vec3f, // KHR_materials_specular specularColorFactor (default 1,1,1)
  thin_walled: u32,      // 1: transmission does not bend the ray (glTF transmission without KHR_materials_volume); 0: a real interface that refracts
}

struct BsdfSample {
  wi: vec3f,        // sampled incident direction, local frame, unit length
  weight: vec3f,    // f(wo, wi) · |cos θi| / pdf — what throughput is multiplied by (for a delta lobe: that lobe's reflectance/transmittance over its selection probability)
  pdf: f32,         // solid-angle density of wi under the whole sampling strategy (non-delta lobes); for a delta sample, the discrete probability of having chosen that lobe
  delta: bool,      // wi came from a perfectly specular (delta) lobe: no MIS with light sampling
  transmitted: bool,// wi is on the other side of the surface from wo (wi.z * wo.z < 0)
  valid: bool,      // false: the sample was absorbed/invalid; the path ends
}

// Every material is a weighted sum of (at most) four lobes; each kind switches some off:
//   spec  — GGX reflection, F = metal·Schlick(base_color) + layer·Schlick(layer_f0)      (VNDF sampled)
//   ms    — Kulla–Conty multiple scattering of the metal, ∝ (1 − E1(μo))(1 − E1(μi))     (cosine sampled)
//   base  — Lambert under the specular layer, ∝ (1 − E_layer(μo))(1 − E_layer(μi))      (cosine sampled)
//   glass — rough (or smooth) dielectric interface: reflection + refraction, or thin-walled
//           transmission that does not bend (VNDF sampled, R or T chosen by Fresnel)
// spec, ms and base are opaque and two-sided: they work in the frame flipped to wo's side (`side`).
// BsdfLobes is what eval, pdf and sample share for one (p, wo).
struct BsdfLobes {
  roughness: f32,
  alpha: f32,
  is_delta: bool,          // alpha < BSDF_ALPHA_DELTA: spec and glass are delta lobes
  ior: f32,
  side: f32,              // +1 when wo.z ≥ 0, else −1
  metal: f32,             // weight of the conductor (metallic)
  metal_f0: vec3f,        // base_color
  layer: f32,             // weight of the dielectric specular layer: (1 − metallic)(1 − transmission)·specular
  layer_specular: f32,    // specularFactor: the layer's own strength, which sets what the base loses
  layer_f0: vec3f,        // min(((ior − 1)/(ior + 1))² · specular_color, 1)
  base: f32,              // weight of the diffuse base: (1 − metallic)(1 − transmission)
  albedo: vec3f,          // base_color
  glass: f32,             // weight of the glass lobe: 1 for DIELECTRIC, (1 − metallic)·transmission
  thin: bool,
  tint: vec3f,            // transmission tint (base_color)
  e1_o: f32,              // E1(μo)
  e5_o: f32,              // E5(μo)
  e_layer_o: vec3f,       // the layer's directional albedo at μo
  e_layer_avg: vec3f,     // its cosine-weighted average
  ms_scale: vec3f,        // metal·F_ms·(1 − E1(μo)) / (π (1 − E1avg)); times (1 − E1(μi)) gives f_ms
  glass_compensation: f32,// 1/E of the glass lobe at μo (1 for the delta lobes)
  p_spec: f32,            // lobe-selection probabilities, ∝ each lobe's estimated albedo at μo
  p_cos: f32,
  p_glass: f32,
}

// Relative index across the interface seen from wo's side: entering (wo outside) ior, else 1/ior.
fn bsdf_eta(l: BsdfLobes) -> f32 {
  return select(1.0 / l.ior, l.ior, l.side > 0.0);
}

// Directional albedo of the dielectric layer at cosine mu: specular·(F0·E1 + (1 − F0)·E5).
fn bsdf_layer_albedo(l: BsdfLobes, mu: f32) -> vec3f {
  if (l.layer_specular <= 0.0) {
    return vec3f(0.0); // no layer (DIFFUSE, or specular 0): skip the table reads
  }
  let e1 = bsdf_table_e1(l.roughness, mu);
  let e5 = bsdf_table_e5(l.roughness, mu);
  return l.layer_specular * (l.layer_f0 * e1 + (vec3f(1.0) - l.layer_f0) * e5);
}

fn bsdf_lobes(p: BsdfParams, wo: vec3f) -> BsdfLobes {
  var l: BsdfLobes;
  l.roughness = clamp(p.roughness, 0.0, 1.0);
  l.alpha = l.roughness * l.roughness;
  l.is_delta = l.alpha < BSDF_ALPHA_DELTA;
  l.ior = max(p.ior, BSDF_TABLE_IOR_MIN);
  l.side = select(-1.0, 1.0, wo.z >= 0.0);
  l.albedo = p.base_color;
  l.metal_f0 = p.base_color;
  l.tint = p.base_color;
  l.thin = p.thin_walled != 0u;
  if (p.kind == BSDF_DIFFUSE || !(SCENE_HAS_METALLIC_ROUGHNESS || SCENE_HAS_DIELECTRIC)) {
    l.base = 1.0;
  } else if (SCENE_HAS_DIELECTRIC && (p.kind == BSDF_DIELECTRIC || !SCENE_HAS_METALLIC_ROUGHNESS)) {
    l.glass = 1.0;
  } else {
    let metallic = clamp(p.metallic, 0.0, 1.0);
    let transmission = clamp(p.transmission, 0.0, 1.0);
    l.metal = metallic;
    l.base = (1.0 - metallic) * (1.0 - transmission);
    l.layer_specular = clamp(p.specular, 0.0, 1.0);
    l.layer = l.base * l.layer_specular;
    l.layer_f0 = min(vec3f(fresnel_f0_from_ior(l.ior)) * p.specular_color, vec3f(1.0));
    l.glass = (1.0 - metallic) * transmission;
  }

  let mu_o = abs(wo.z);
  l.e1_o = bsdf_table_e1(l.roughness, mu_o);
  l.e5_o = bsdf_table_e5(l.roughness, mu_o);
  l.e_layer_o = bsdf_layer_albedo(l, mu_o);
  if (l.layer_specular > 0.0) {
    l.e_layer_avg = l.layer_specular * (l.layer_f0 * bsdf_table_e1_avg(l.roughness) + (vec3f(1.0) - l.layer_f0) * bsdf_table_e5_avg(l.roughness));
  }

  // Kulla & Conty 2017: the energy a conductor's single scattering misses, 1 − E1(μo), comes back
  // through f_ms = (1 − E1(μo))(1 − E1(μi)) / (π (1 − E1avg)), whose albedo is exactly 1 − E1(μo);
  // for F ≠ 1 it is scaled by F_ms = F_avg² E1avg / (1 − F_avg (1 − E1avg)) (their eq. for the
  // series of bounces), with Schlick's F_avg = F0 + (1 − F0)/21.
  let one_minus_e1_avg = 1.0 - bsdf_table_e1_avg(l.roughness);
  if (!l.is_delta && l.metal > 0.0 && one_minus_e1_avg > BSDF_ENERGY_EPSILON) {
    let f_avg = l.metal_f0 + (vec3f(1.0) - l.metal_f0) * SCHLICK_AVERAGE_TAIL;
    let e_avg = 1.0 - one_minus_e1_avg;
    let f_ms = f_avg * f_avg * e_avg / (vec3f(1.0) - f_avg * one_minus_e1_avg);
    l.ms_scale = l.metal * f_ms * max(0.0, 1.0 - l.e1_o) / (PI * one_minus_e1_avg);
  }

  // Compensation of the glass lobe (in the manner of Turquin 2019): divide by its own directional
  // albedo at μo, so reflection + transmission sum to 1 at every roughness. Thin-walled glass flips
  // reflected directions through the plane, so its albedo is the conductor's E1.
  l.glass_compensation = 1.0;
  if (!l.is_delta && l.glass > 0.0) {
    var e = bsdf_table_glass(l.side > 0.0, l.ior, l.roughness, mu_o);
    if (l.thin) {
      e = l.e1_o;
    }
    l.glass_compensation = 1.0 / max(e, BSDF_ENERGY_EPSILON);
  }

  // Lobe selection ∝ each lobe's albedo at μo (luminance); the glass lobe's is ~1 by construction.
  let spec_albedo = l.metal * (l.metal_f0 * l.e1_o + (vec3f(1.0) - l.metal_f0) * l.e5_o) + l.base * l.e_layer_o;
  let w_spec = luminance(spec_albedo);
  let w_cos = luminance(l.ms_scale) * PI * one_minus_e1_avg + luminance(l.base * l.albedo * (vec3f(1.0) - l.e_layer_o));
  let w_glass = l.glass;
  let total = w_spec + w_cos + w_glass;
  if (total > 0.0) {
    l.p_spec = w_spec / total;
    l.p_cos = w_cos / total;
    l.p_glass = w_glass / total;
  }
  return l;
}

// ---- the glass lobe, in the frame flipped to wo's side (o.z > 0) ----

// f of the rough glass lobe (without its weight l.glass), compensated. Refraction carries pbrt's
// radiance scaling: camera paths transport radiance, and radiance crossing into a medium of index
// n_i from n_o scales by (n_o/n_i)²; with η = n_i/n_o (wi's side over wo's) f_t is divided by η², so
// a camera ray entering glass (wo outside, wi inside) is weighted 1/ior², and leaving ior².
fn bsdf_glass_eval(l: BsdfLobes, o: vec3f, i: vec3f) -> vec3f {
  let eta = bsdf_eta(l);
  if (i.z > 0.0) {
    let m = normalize(o + i);
    let f = fresnel_dielectric(dot(o, m), select(eta, l.ior, l.thin));
    return vec3f(f * ggx_d(m, l.alpha) * ggx_g2(o, i, l.alpha) / (4.0 * o.z * i.z) * l.glass_compensation);
  }
  if (l.thin) {
    // Thin-walled: the transmitted direction is the reflected one mirrored through the plane.
    let r = vec3f(i.xy, -i.z);
    let m = normalize(o + r);
    let f = fresnel_dielectric(dot(o, m), l.ior);
    return l.tint * ((1.0 - f) * ggx_d(m, l.alpha) * ggx_g2(o, r, l.alpha) / (4.0 * o.z * r.z) * l.glass_compensation);
  }
  // Walter et al. 2007, eq. 21: generalized half vector m ∝ o + η i (turned up), and
  // f_t = |i·m| |o·m| (1 − F) D G2 / (|i.z| o.z (i·m + o·m/η)²), here already divided by η².
  var m = normalize(o + eta * i);
  m = select(m, -m, m.z < 0.0);
  let co = dot(o, m);
  let ci = dot(i, m);
  if (co <= 0.0 || ci >= 0.0) {
    return vec3f(0.0);
  }
  let f = fresnel_dielectric(co, eta);
  let denom = ci + co / eta;
  let value = ggx_d(m, l.alpha) * ggx_g2(o, i, l.alpha) * (1.0 - f) * abs(ci) * co / (o.z * abs(i.z) * denom * denom);
  return l.tint * (value / (eta * eta) * l.glass_compensation);
}

// The density with which the glass lobe samples i: visible normal m, then R with probability F.
// Reflection: dωi/dωm = 4 o·m; refraction: dωm/dωi = |i·m| / (i·m + o·m/η)².
fn bsdf_glass_pdf(l: BsdfLobes, o: vec3f, i: vec3f) -> f32 {
  let eta = bsdf_eta(l);
  if (i.z > 0.0) {
    let m = normalize(o + i);
    let c = dot(o, m);
    let f = fresnel_dielectric(c, select(eta, l.ior, l.thin));
    return ggx_visible_normal_pdf(o, m, l.alpha) * f / (4.0 * c);
  }
  if (l.thin) {
    let m = normalize(o + vec3f(i.xy, -i.z));
    let c = dot(o, m);
    let f = fresnel_dielectric(c, l.ior);
    return ggx_visible_normal_pdf(o, m, l.alpha) * (1.0 - f) / (4.0 * c);
  }
  var m = normalize(o + eta * i);
  m = select(m, -m, m.z < 0.0);
  let co = dot(o, m);
  let ci = dot(i, m);
  if (co <= 0.0 || ci >= 0.0) {
    return 0.0;
  }
  let f = fresnel_dielectric(co, eta);
  let denom = ci + co / eta;
  return ggx_visible_normal_pdf(o, m, l.alpha) * (1.0 - f) * abs(ci) / (denom * denom);
}

// ---- the whole mixture, given the shared lobe data ----

fn bsdf_eval_lobes(l: BsdfLobes, wo: vec3f, wi: vec3f) -> vec3f {
  let o = vec3f(wo.xy, wo.z * l.side);
  let i = vec3f(wi.xy, wi.z * l.side);
  if (o.z < BSDF_COS_MIN || abs(i.z) < BSDF_COS_MIN) {
    return vec3f(0.0);
  }
  var f = vec3f(0.0);
  if (i.z > 0.0) {
    if (!l.is_delta && l.metal + l.layer > 0.0) {
      // Microfacet reflection: D G2 F / (4 μo μi).
      let m = normalize(o + i);
      let c = dot(o, m);
      let fr = l.metal * fresnel_schlick(l.metal_f0, c) + l.layer * fresnel_schlick(l.layer_f0, c);
      f += fr * (ggx_d(m, l.alpha) * ggx_g2(o, i, l.alpha) / (4.0 * o.z * i.z));
    }
    if (any(l.ms_scale > vec3f(0.0))) {
      f += l.ms_scale * max(0.0, 1.0 - bsdf_table_e1(l.roughness, i.z));
    }
    if (l.base > 0.0) {
      // Albedo scaling (Kelemen & Szirmay-Kalos 2001; Kulla & Conty 2017): Lambert scaled by what
      // the layer lets through on both ways, normalized so its albedo is exactly 1 − E_layer(μo).
      let e_i = bsdf_layer_albedo(l, i.z);
      let through = (vec3f(1.0) - l.e_layer_o) * (vec3f(1.0) - e_i) / max(vec3f(1.0) - l.e_layer_avg, vec3f(BSDF_ENERGY_EPSILON));
      f += l.base * l.albedo * INV_PI * through;
    }
  }
  if (!l.is_delta && l.glass > 0.0) {
    f += l.glass * bsdf_glass_eval(l, o, i);
  }
  return f;
}

fn bsdf_pdf_lobes(l: BsdfLobes, wo: vec3f, wi: vec3f) -> f32 {
  let o = vec3f(wo.xy, wo.z * l.side);
  let i = vec3f(wi.xy, wi.z * l.side);
  if (o.z < BSDF_COS_MIN || abs(i.z) < BSDF_COS_MIN) {
    return 0.0;
  }
  var pdf = 0.0;
  if (i.z > 0.0) {
    if (!l.is_delta && l.p_spec > 0.0) {
      let m = normalize(o + i);
      pdf += l.p_spec * ggx_visible_normal_pdf(o, m, l.alpha) / (4.0 * dot(o, m));
    }
    pdf += l.p_cos * i.z * INV_PI;
  }
  if (!l.is_delta && l.p_glass > 0.0) {
    pdf += l.p_glass * bsdf_glass_pdf(l, o, i);
  }
  return pdf;
}

// ---- the public interface ----

// f(wo, wi) without the cosine, summed over the non-delta lobes (0 for delta-only materials).
fn bsdf_eval(p: BsdfParams, wo: vec3f, wi: vec3f) -> vec3f {
  return bsdf_eval_lobes(bsdf_lobes(p, wo), wo, wi);
}

// The solid-angle density with which bsdf_sample returns wi through its non-delta lobes.
fn bsdf_pdf(p: BsdfParams, wo: vec3f, wi: vec3f) -> f32 {
  return bsdf_pdf_lobes(bsdf_lobes(p, wo), wo, wi);
}

fn bsdf_invalid_sample() -> BsdfSample {
  return BsdfSample(vec3f(0.0, 0.0, 1.0), vec3f(0.0), 0.0, false, false, false);
}

// A delta sample in the flipped frame, turned back to the caller's frame.
fn bsdf_delta_sample(l: BsdfLobes, wo: vec3f, i: vec3f, weight: vec3f, pdf: f32) -> BsdfSample {
  let wi = vec3f(i.xy, i.z * l.side);
  return BsdfSample(wi, weight, pdf, true, (wi.z * wo.z) < 0.0, pdf > 0.0);
}

// Picks a lobe with u.z (∝ the lobe weights), then a direction with u.xy; u.z, rescaled to [0, 1)
// inside the chosen lobe's interval, then picks reflection or transmission in the glass lobe.
fn bsdf_sample(p: BsdfParams, wo: vec3f, u: vec3f) -> BsdfSample {
  let l = bsdf_lobes(p, wo);
  let o = vec3f(wo.xy, wo.z * l.side);
  if (o.z < BSDF_COS_MIN) {
    return bsdf_invalid_sample();
  }
  // i, in the flipped frame; `reflected` says which side of the surface the lobe must send it to (a
  // microfacet can send a direction to the wrong side: that sample is lost, as the pdf says).
  var i: vec3f;
  var reflected = true;
  if (u.z < l.p_spec) {
    if (l.is_delta) {
      // Mirror: reflectance F(μo) of the spec lobe, chosen with probability p_spec.
      let fr = l.metal * fresnel_schlick(l.metal_f0, o.z) + l.layer * fresnel_schlick(l.layer_f0, o.z);
      return bsdf_delta_sample(l, wo, vec3f(-o.xy, o.z), fr / l.p_spec, l.p_spec);
    }
    let m = ggx_sample_visible_normal(o, l.alpha, u.xy);
    i = reflect(-o, m);
  } else if (u.z < l.p_spec + l.p_cos) {
    i = sample_cosine_hemisphere(u.xy);
  } else if (l.p_glass > 0.0) {
    let u_rt = clamp((u.z - l.p_spec - l.p_cos) / l.p_glass, 0.0, 1.0);
    let eta = bsdf_eta(l);
    let fresnel_eta = select(eta, l.ior, l.thin);
    if (l.is_delta) {
      let f = fresnel_dielectric(o.z, fresnel_eta);
      if (u_rt < f) {
        return bsdf_delta_sample(l, wo, vec3f(-o.xy, o.z), vec3f(l.glass / l.p_glass), l.p_glass * f);
      }
      if (l.thin) {
        return bsdf_delta_sample(l, wo, -o, l.tint * (l.glass / l.p_glass), l.p_glass * (1.0 - f));
      }
      let t = refract(-o, vec3f(0.0, 0.0, 1.0), 1.0 / eta);
      return bsdf_delta_sample(l, wo, t, l.tint * (l.glass / (l.p_glass * eta * eta)), l.p_glass * (1.0 - f));
    }
    let m = ggx_sample_visible_normal(o, l.alpha, u.xy);
    let f = fresnel_dielectric(dot(o, m), fresnel_eta);
    i = reflect(-o, m);
    if (u_rt >= f) {
      reflected = false;
      if (l.thin) {
        // Thin-walled transmission: the reflected direction mirrored through the plane.
        if (i.z <= 0.0) {
          return bsdf_invalid_sample();
        }
        i = vec3f(i.xy, -i.z);
      } else {
        i = refract(-o, m, 1.0 / eta);
      }
    }
  } else {
    return bsdf_invalid_sample();
  }
  if ((i.z > 0.0) != reflected) {
    return bsdf_invalid_sample();
  }
  // refract returns 0 under total internal reflection (only reachable through rounding of u_rt).
  if (dot(i, i) == 0.0) {
    return bsdf_invalid_sample();
  }
  let wi = normalize(vec3f(i.xy, i.z * l.side));
  let pdf = bsdf_pdf_lobes(l, wo, wi);
  if (pdf <= 0.0) {
    return bsdf_invalid_sample();
  }
  let f = bsdf_eval_lobes(l, wo, wi);
  return BsdfSample(wi, f * abs(wi.z) / pdf, pdf, false, (wi.z * wo.z) < 0.0, true);
}

// False when every lobe is a delta: next-event estimation can then never contribute.
fn bsdf_has_non_delta(p: BsdfParams) -> bool {
  if (p.kind == BSDF_DIFFUSE) {
    return true;
  }
  let roughness = clamp(p.roughness, 0.0, 1.0);
  if (roughness * roughness >= BSDF_ALPHA_DELTA) {
    return true;
  }
  // Smooth: only the diffuse base of a metallic-roughness material is left.
  return p.kind == BSDF_METALLIC_ROUGHNESS && (1.0 - clamp(p.metallic, 0.0, 1.0)) * (1.0 - clamp(p.transmission, 0.0, 1.0)) > 0.0;
}

// Directional albedo at wo, estimated from the tables (for the denoiser's demodulation): spec and
// multiple scattering, the base under the layer, and the glass lobe as F + (1 − F)·tint at μo.
fn bsdf_albedo(p: BsdfParams, wo: vec3f) -> vec3f {
  if (p.kind == BSDF_DIFFUSE) {
    return p.base_color;
  }
  let l = bsdf_lobes(p, wo);
  let mu_o = max(abs(wo.z), BSDF_COS_MIN);
  let spec = l.metal * (l.metal_f0 * l.e1_o + (vec3f(1.0) - l.metal_f0) * l.e5_o) + l.base * l.e_layer_o;
  let ms = l.ms_scale * PI * (1.0 - bsdf_table_e1_avg(l.roughness));
  let base = l.base * l.albedo * (vec3f(1.0) - l.e_layer_o);
  let f = fresnel_dielectric(mu_o, select(bsdf_eta(l), l.ior, l.thin));
  let glass = l.glass * (vec3f(f) + (1.0 - f) * l.tint);
  return spec + ms + base + glass;
}
