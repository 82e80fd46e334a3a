// Light selection behind one interface: every light the scene has — emissive triangles, punctual
// lights (KHR_lights_punctual), the environment map and the sun — sits in one alias table with a
// probability proportional to its (estimated) power; sample_light picks one and a point or
// direction on it, and reports the solid-angle density of the whole strategy, so a BSDF-sampled ray
// that finds the same light can be weighted by MIS (emitter_pdf, environment_light_pdf). The torch is
// apart (scene/torch.wgsl): it follows the camera and is a per-frame setting, not scene data.
// Expects the scene bindings, lib/sampling, lib/color. Follows pbrt-v4 §12.6 (light samplers).

#import scene/bindings
#import scene/materials
#import scene/environment
#import lib/sampling
#import lib/color

// Whether the scene has punctual lights / an environment (map or sun). Pipeline constants: a scene
// without them compiles the cases away (set by gpu/kernel.ts from the packed scene's features).
override SCENE_HAS_PUNCTUAL_LIGHTS: bool = true;
override SCENE_HAS_ENVIRONMENT: bool = true;

struct LightSample {
  // Unit direction from the shading point toward the light.
  direction: vec3f,
  // Distance to the sampled point; T_MISS for lights at infinity.
  distance: f32,
  // Radiance arriving along `direction` (for a punctual light: its intensity over distance², so
  // that contribution = f · radiance · |cos| / pdf holds for every kind).
  radiance: vec3f,
  // Solid-angle density of `direction` under sample_light, light selection included; for a punctual
  // light (a delta), the probability of having selected it. 0: no contribution.
  pdf: f32,
  // A punctual light: no BSDF ray can find it, so no MIS weight.
  delta: bool,
}

// Probability of choosing a triangle of this material and area, as the alias table does.
fn light_selection_pmf(material: Material, area: f32) -> f32 {
  return luminance(material.emission) * material.emission_texture_mean * area / scene_info.total_light_power;
}

// Solid-angle density with which sample_light finds an emissive triangle's point seen at distance t
// under cosine cos_emitter (> 0) from the shading point: for the MIS weight of a BSDF ray that hit it.
fn emitter_pdf(material: Material, area: f32, t: f32, cos_emitter: f32) -> f32 {
  return light_selection_pmf(material, area) / area * t * t / cos_emitter;
}

// The same for a BSDF ray that left the scene along `direction` (environment map and sun together).
fn environment_light_pdf(direction: vec3f) -> f32 {
  var pdf = 0.0;
  if (SCENE_HAS_ENVIRONMENT) {
    if (scene_info.environment_select_pmf > 0.0) {
      pdf += scene_info.environment_select_pmf * environment_pdf(direction);
    }
    if (scene_info.sun_select_pmf > 0.0) {
      pdf += scene_info.sun_select_pmf * sun_pdf(direction);
    }
  }
  return pdf;
}

fn no_light() -> LightSample {
  return LightSample(vec3f(0.0, 0.0, 1.0), 0.0, vec3f(0.0), 0.0, false);
}

// A point on an emissive triangle (leaf order), uniformly by area.
fn sample_triangle_light(triangle: u32, p: vec3f, u: vec2f) -> LightSample {
  let tri = triangles_hot[triangle];
  let b = sample_triangle_uniform(u);
  let cross_e = cross(tri.e1, tri.e2);
  let area = 0.5 * length(cross_e);
  let material = materials[triangles_shading[triangle].material];
  let to_light = tri.v0 + b.x * tri.e1 + b.y * tri.e2 - p;
  let distance2 = dot(to_light, to_light);
  let distance = sqrt(distance2);
  let wi = to_light / distance;
  // Emission is one-sided: the light faces along e1 × e2.
  let cos_light = -dot(cross_e, wi) / (2.0 * area);
  if (!(cos_light > 0.0) || !(distance > 0.0)) {
    return no_light();
  }
  let emission = material_emission(material, triangle_uv(triangle, b), wi);
  let pdf = light_selection_pmf(material, area) / area * distance2 / cos_light;
  return LightSample(wi, distance, emission, pdf, false);
}

// A punctual light: intensity / d², with glTF's range window and a spot's smooth cone.
fn sample_punctual_light(index: u32, p: vec3f) -> LightSample {
  let light = punctual_lights.lights[index];
  let select_pmf = light.select_pmf;
  if (light.kind == PUNCTUAL_DIRECTIONAL) {
    return LightSample(light.position, T_MISS, light.intensity, select_pmf, true);
  }
  let to_light = light.position - p;
  let distance2 = dot(to_light, to_light);
  let distance = sqrt(distance2);
  if (!(distance > 0.0) || distance >= light.range) {
    return no_light();
  }
  let wi = to_light / distance;
  // glTF's recommended range window: clamp(1 − (d/range)⁴, 0, 1) / d² (KHR_lights_punctual README).
  let x = distance / light.range;
  var falloff = clamp(1.0 - x * x * x * x, 0.0, 1.0);
  if (light.kind == PUNCTUAL_SPOT) {
    let cos_angle = -dot(wi, light.direction);
    let t = clamp((cos_angle - light.cos_outer) * light.cone_scale, 0.0, 1.0);
    falloff *= t * t;
  }
  return LightSample(wi, distance, light.intensity * (falloff / distance2), select_pmf, true);
}

// One light sample for the shading point p: u_select picks the light (slot, keep), u the point.
// Requires scene_info.light_count > 0.
fn sample_light(p: vec3f, u_select: vec2f, u: vec2f) -> LightSample {
  let slot_index = min(u32(u_select.x * f32(scene_info.light_count)), scene_info.light_count - 1u);
  let slot = light_slots[slot_index];
  let code = select(slot.alias_light, slot.light, u_select.y < slot.keep);
  let kind = code >> LIGHT_KIND_SHIFT;
  let index = code & LIGHT_INDEX_MASK;
  if (kind == LIGHT_KIND_TRIANGLE) {
    return sample_triangle_light(index, p, u);
  }
  if (SCENE_HAS_PUNCTUAL_LIGHTS && kind == LIGHT_KIND_PUNCTUAL) {
    return sample_punctual_light(index, p);
  }
  if (SCENE_HAS_ENVIRONMENT && kind == LIGHT_KIND_ENVIRONMENT) {
    let s = sample_environment(u);
    return LightSample(s.direction, T_MISS, s.radiance, s.pdf * scene_info.environment_select_pmf, false);
  }
  if (SCENE_HAS_ENVIRONMENT && kind == LIGHT_KIND_SUN) {
    let s = sample_sun(u);
    return LightSample(s.direction, T_MISS, s.radiance, s.pdf * scene_info.sun_select_pmf, false);
  }
  return no_light();
}
