// Material evaluation: textures from the atlas (nearest texel, wrapping), albedo with alpha, and
// emitted radiance by uv or, for sky panoramas, by viewing direction. Expects the scene bindings.

#import lib/constants
#import lib/color
#import scene/bindings

// The texel of texture `index` at uv ((0, 0) top left, 1 = the whole texture), wrapped; linear colour.
fn texture_texel(index: u32, uv: vec2f) -> vec4f {
  let rect = texture_rects[index];
  let size = vec2f(rect.size);
  let t = uv * size;
  let wrapped = t - floor(t / size) * size;
  let texel = min(vec2u(wrapped), rect.size - 1u);
  return textureLoad(texture_atlas, rect.origin + texel, rect.page, 0);
}

// Albedo (rgb) and coverage (a) at uv.
fn material_albedo(material: Material, uv: vec2f) -> vec4f {
  if (material.albedo_texture == NO_TEXTURE) {
    return vec4f(material.albedo, 1.0);
  }
  let texel = texture_texel(material.albedo_texture, uv);
  return vec4f(material.albedo * texel.rgb, texel.a);
}

// Texture coordinates of a cylindrical panorama around +y for a viewing direction (unit): the
// angle counter-clockwise from +x seen from above (Doom's angle, with Doom's north = −z) spans
// `repeats` copies of the texture; elevation moves v from the horizon toward the top, clamped.
fn panorama_uv(material: Material, direction: vec3f) -> vec2f {
  let azimuth = atan2(-direction.z, direction.x);
  let elevation = asin(clamp(direction.y, -1.0, 1.0));
  let u = azimuth * (material.panorama_repeats / (2.0 * PI));
  let v = clamp(material.panorama_horizon_v - elevation * material.panorama_v_per_radian, 0.0, 0.9999);
  return vec2f(u, v);
}

// Radiance emitted toward a viewer looking along `direction` at a point with texture coordinates uv
// (one-sidedness is the caller's business).
fn material_emission(material: Material, uv: vec2f, direction: vec3f) -> vec3f {
  if (material.emission_texture == NO_TEXTURE) {
    return material.emission;
  }
  var lookup = uv;
  if ((material.flags & MATERIAL_EMISSION_PANORAMA) != 0u) {
    lookup = panorama_uv(material, direction);
  }
  return material.emission * texture_texel(material.emission_texture, lookup).rgb;
}

// Texture coordinates at barycentrics (u, v) of v1 and v2 of a triangle (leaf order).
fn triangle_uv(triangle: u32, bary: vec2f) -> vec2f {
  let s = triangles_shading[triangle];
  return (1.0 - bary.x - bary.y) * s.uv0 + bary.x * s.uv1 + bary.y * s.uv2;
}

// Whether an alpha-masked triangle is really there at these barycentrics.
fn alpha_test_passes(triangle: u32, bary: vec2f) -> bool {
  let material = materials[triangles_shading[triangle].material];
  return material_albedo(material, triangle_uv(triangle, bary)).a >= 0.5;
}
