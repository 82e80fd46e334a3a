// Next-event estimation on emissive triangles: pick a triangle in proportion to its emitted power
// (luminance(emission) × mean texture luminance × area) through the alias table, then a point
// uniformly on it; and the same density for MIS when a BSDF-sampled ray happens to hit an emitter.
// Expects the scene bindings and lib/sampling, lib/color.

#import scene/bindings
#import scene/materials
#import lib/sampling
#import lib/color

struct LightSample {
  position: vec3f,
  // Unit geometric normal of the light: it emits on this side only.
  normal: vec3f,
  // Leaf-order triangle and barycentrics of v1, v2 at the sampled point.
  triangle: u32,
  bary: vec2f,
  // Probability density of this point with respect to area: selection pmf / triangle area.
  pdf_area: f32,
}

// Probability of choosing a triangle of this material and area, as the alias table does.
fn light_selection_pmf(material: Material, area: f32) -> f32 {
  return luminance(material.emission) * material.emission_texture_mean * area / scene_info.total_light_power;
}

// Requires scene_info.light_count > 0.
fn sample_light(u_slot: f32, u_keep: f32, u_point: vec2f) -> LightSample {
  let slot_index = min(u32(u_slot * f32(scene_info.light_count)), scene_info.light_count - 1u);
  let slot = light_slots[slot_index];
  let triangle = select(slot.alias_triangle, slot.triangle, u_keep < slot.keep);
  let tri = triangles_hot[triangle];
  let b = sample_triangle_uniform(u_point);
  let cross_e = cross(tri.e1, tri.e2);
  let area = 0.5 * length(cross_e);
  let material = materials[triangles_shading[triangle].material];
  return LightSample(tri.v0 + b.x * tri.e1 + b.y * tri.e2, normalize(cross_e), triangle, b, light_selection_pmf(material, area) / area);
}
