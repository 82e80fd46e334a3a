// Light selection behind one interface: every light the scene has — emissive triangles and spheres, punctual
// lights (KHR_lights_punctual), the environment map and the sun — sits in one alias table with a
// probability proportional to its (estimated) power; sample_light picks one and a point or
// direction on it, and reports the solid-angle density of the whole strategy, so a BSDF-sampled ray
// that finds the same light can be weighted by MIS (emitter_pdf, environment_light_pdf). The torch is
// apart (scene/torch.wgsl): it follows the camera and is a per-frame setting, not scene data.
// Expects the scene bindings, lib/sampling, lib/color. Follows pbrt-v4 §12.6 (light samplers).

#import scene/bindings
#import scene/materials
#import scene/surface
#import scene/environment
#import lib/sampling
#import lib/color

// Whether the scene has punctual lights / an environment (map or sun). Pipeline constants: a scene
// without them compiles the cases away (set by gpu/kernel.ts from the packed scene's features).
override SCENE_HAS_PUNCTUAL_LIGHTS: bool = true;
override SCENE_HAS_ENVIRONMENT: bool = true;

// The slots of the light table, inlined into kernels specialised to a frozen scene
// (gpu/specialisation.ts); -1 (the generic kernels): read scene_info.light_count.
override INLINED_LIGHT_COUNT: i32 = -1;

fn scene_light_count() -> u32 {
  return select(scene_info.light_count, u32(INLINED_LIGHT_COUNT), INLINED_LIGHT_COUNT >= 0);
}

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
  let sides = select(1.0, 2.0, (material.flags & MATERIAL_TWO_SIDED_EMISSION) != 0u);
  return luminance(material.emission) * material.emission_texture_mean * area * sides / scene_info.total_light_power;
}

// The cosine between an emitter's front normal and the direction toward the viewer, as emission sees
// it: as is for one-sided emitters (≤ 0: nothing is emitted), its magnitude for two-sided ones.
fn emitter_cosine(material: Material, cos_front: f32) -> f32 {
  return select(cos_front, abs(cos_front), (material.flags & MATERIAL_TWO_SIDED_EMISSION) != 0u);
}

// Solid-angle density with which sample_light finds the emitter point `surface`, hit at distance t
// from `origin` under cosine cos_emitter (> 0): for the MIS weight of a BSDF ray that hit it. A
// triangle is sampled by area; a sphere by the cone it subtends (sample_sphere_light); capsules are
// not in the light table (only BSDF rays find them), so their density is 0.
fn emitter_pdf(surface: Surface, material: Material, origin: vec3f, t: f32, cos_emitter: f32) -> f32 {
  let select_pmf = light_selection_pmf(material, surface.area);
  if (SCENE_HAS_ANALYTIC_PRIMITIVES && surface.kind != 0u) {
    if (surface.kind != PRIMITIVE_SPHERE) {
      return 0.0;
    }
    // The sphere's radius follows from its area; its centre from the surface point and normal.
    let r = sqrt(surface.area / (4.0 * PI));
    let centre = surface.position - r * surface.geometric_normal;
    let d = origin - centre;
    return select_pmf / sphere_cone_solid_angle(r * r / dot(d, d));
  }
  return select_pmf / surface.area * t * t / cos_emitter;
}

// Solid angle 2π(1 − cos θmax) of a sphere seen from outside, given sin²θmax = r²/d² (< 1). For tiny
// spheres 1 − cos θmax is formed as sin² / (1 + cos), without cancellation (pbrt-v4 §6.2.4 uses a
// series there for the same reason).
fn sphere_cone_solid_angle(sin2_max: f32) -> f32 {
  let cos_max = sqrt(max(0.0, 1.0 - sin2_max));
  return 2.0 * PI * sin2_max / (1.0 + cos_max);
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

// A point on an emissive triangle (leaf order) of `instance`, uniformly by area.
fn sample_triangle_light(triangle: u32, instance: u32, p: vec3f, u: vec2f) -> LightSample {
  return triangle_light_point(triangle, instance, p, u).sample;
}

// A triangle light's point as sample_triangle_light draws it from u, and its measure factor
// g = cos θlight / d² (0 where it sends nothing to p); restir/reservoir names points by u.
struct TriangleLightPoint {
  sample: LightSample,
  geometry: f32,
}

fn triangle_light_point(triangle: u32, instance: u32, p: vec3f, u: vec2f) -> TriangleLightPoint {
  let tri = world_primitive(instance, triangle);
  let shading = world_shading(instance, triangle);
  let b = sample_triangle_uniform(u);
  let cross_e = cross(tri.e1, tri.e2);
  let area = 0.5 * length(cross_e);
  let material = scene_material(shading.material);
  let to_light = tri.v0 + b.x * tri.e1 + b.y * tri.e2 - p;
  let distance2 = dot(to_light, to_light);
  let distance = sqrt(distance2);
  let wi = to_light / distance;
  // Emission is one-sided: the light faces along e1 × e2 (unless both faces emit).
  let cos_light = emitter_cosine(material, -dot(cross_e, wi) / (2.0 * area));
  if (!(cos_light > 0.0) || !(distance > 0.0)) {
    return TriangleLightPoint(no_light(), 0.0);
  }
  let emission = material_emission(material, shading_uv(shading, b), wi);
  let pdf = light_selection_pmf(material, area) / area * distance2 / cos_light;
  return TriangleLightPoint(LightSample(wi, distance, emission, pdf, false), cos_light / distance2);
}

// A point of an emissive sphere (leaf order), by the cone of directions it subtends from p (pbrt-v4
// §6.2.4): uniform in that cone, so the density is 1 / its solid angle. The sphere emits outward
// only, so a point inside it receives nothing from it.
fn sample_sphere_light(sphere: u32, instance: u32, p: vec3f, u: vec2f) -> LightSample {
  let prim = world_primitive(instance, sphere);
  let r = prim.e1.x;
  let material = scene_material(instance_material(instance, sphere));
  let to_centre = prim.v0 - p;
  let d2 = dot(to_centre, to_centre);
  let sin2_max = r * r / d2;
  if (!(sin2_max < 1.0)) {
    return no_light();
  }
  let cos_max = sqrt(1.0 - sin2_max);
  // cos θ uniform in [cos θmax, 1], with 1 − cos θ formed without cancellation.
  let one_minus_cos = u.x * sin2_max / (1.0 + cos_max);
  let cos_theta = 1.0 - one_minus_cos;
  let sin_theta = sqrt(max(0.0, one_minus_cos * (2.0 - one_minus_cos)));
  let phi = 2.0 * PI * u.y;
  let d = sqrt(d2);
  let axis = to_centre / d;
  let wi = orthonormal_basis(axis) * vec3f(sin_theta * cos(phi), sin_theta * sin(phi), cos_theta);
  // Distance to the sphere along wi, by the same test the shadow ray will run: the closed form
  // d·cos θ − √(r² − d²·sin² θ) is ill-conditioned near the silhouette, and GPU sin/cos are only
  // accurate to ~2⁻¹¹ (the Vulkan limit), so wi itself may lie a little off the sampled cone (then it
  // grazes past and the tangent distance stands in).
  let hit = intersect_sphere(p, wi, prim, 0.0, T_MISS);
  let distance = select(d * cos_theta, hit.x, hit.x < T_MISS);
  let point = p + distance * wi;
  let emission = material_emission(material, sphere_uv(point - prim.v0), wi);
  let area = 4.0 * PI * r * r;
  let pdf = light_selection_pmf(material, area) / sphere_cone_solid_angle(sin2_max);
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
// Requires scene_light_count() > 0.
fn sample_light(p: vec3f, u_select: vec2f, u: vec2f) -> LightSample {
  let light_count = scene_light_count();
  let slot_index = min(u32(u_select.x * f32(light_count)), light_count - 1u);
  let slot = scene_light_slot(slot_index);
  let keep = u_select.y < slot.keep;
  let code = select(slot.alias_light, slot.light, keep);
  let kind = code >> LIGHT_KIND_SHIFT;
  let index = code & LIGHT_INDEX_MASK;
  if (kind == LIGHT_KIND_TRIANGLE) {
    let instance = select(0u, select(slot.alias_instance, slot.instance, keep), SCENE_HAS_INSTANCES);
    if (SCENE_HAS_ANALYTIC_PRIMITIVES && (scene_triangle_flags(index) & PRIMITIVE_SPHERE) != 0u) {
      return sample_sphere_light(index, instance, p, u);
    }
    return sample_triangle_light(index, instance, p, u);
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
