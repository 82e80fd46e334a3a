// Material evaluation at a hit: textures from the atlases (nearest texel for Doom's pixels, bilinear
// for glTF; wrapping; KHR_texture_transform), coverage (alpha), emitted radiance by uv or, for sky
// panoramas, by viewing direction, and the BsdfParams of scene/bsdf.wgsl with every texture applied.
// Expects the scene bindings.

#import lib/constants
#import lib/color
#import lib/random
#import scene/bindings
#import scene/bsdf

// Texel (x, y) of a texture, wrapped into its rectangle; linear colour from either atlas.
fn texture_fetch(t: TextureRef, texel: vec2i) -> vec4f {
  let size = vec2i(t.size);
  let wrapped = vec2u(((texel % size) + size) % size);
  if ((t.flags & TEXTURE_LINEAR) != 0u) {
    return textureLoad(texture_atlas_linear, t.origin + wrapped, t.page, 0);
  }
  return textureLoad(texture_atlas, t.origin + wrapped, t.page, 0);
}

// The texture of reference `index` at uv ((0, 0) top left, 1 = the whole texture), wrapped; linear colour.
fn texture_texel(index: u32, uv: vec2f) -> vec4f {
  let t = texture_refs[index];
  let st = vec2f(dot(t.transform_u, vec3f(uv, 1.0)), dot(t.transform_v, vec3f(uv, 1.0)));
  let size = vec2f(t.size);
  if ((t.flags & TEXTURE_BILINEAR) == 0u) {
    // floor keeps negative coordinates wrapping the same way as positive ones.
    return texture_fetch(t, vec2i(floor(st * size)));
  }
  // Texel centres sit at half-integers: interpolate between the four around st.
  let p = st * size - 0.5;
  let p0 = floor(p);
  let f = p - p0;
  let i0 = vec2i(p0);
  let top = mix(texture_fetch(t, i0), texture_fetch(t, i0 + vec2i(1, 0)), f.x);
  let bottom = mix(texture_fetch(t, i0 + vec2i(0, 1)), texture_fetch(t, i0 + vec2i(1, 1)), f.x);
  return mix(top, bottom, f.y);
}

// Base colour (rgb: diffuse albedo, glTF base colour or glass tint) and coverage (a) at uv.
fn material_albedo(material: Material, uv: vec2f) -> vec4f {
  if (material.base_color_texture == NO_TEXTURE) {
    return vec4f(material.base_color, material.opacity);
  }
  let texel = texture_texel(material.base_color_texture, uv);
  return vec4f(material.base_color * texel.rgb, material.opacity * texel.a);
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

// A cheap hash of a hit, for stochastic transparency: different rays through the same point draw
// different numbers, so alpha blending converges to the blend instead of a fixed dither.
fn coverage_random(triangle: u32, bary: vec2f, salt: u32) -> f32 {
  let h = pcg_hash(triangle ^ pcg_hash(bitcast<u32>(bary.x) ^ pcg_hash(bitcast<u32>(bary.y) ^ salt)));
  return f32(h >> 8u) * (1.0 / 16777216.0);
}

// Whether a triangle with a hit filter (alpha mask or blend) is really there at these barycentrics,
// for a ray identified by `salt`.
fn alpha_test_passes(triangle: u32, bary: vec2f, salt: u32) -> bool {
  let material = materials[triangles_shading[triangle].material];
  let coverage = material_albedo(material, triangle_uv(triangle, bary)).a;
  if ((material.flags & MATERIAL_ALPHA_BLEND) != 0u) {
    return coverage > coverage_random(triangle, bary, salt);
  }
  return coverage >= material.alpha_cutoff;
}

// The BSDF at uv with every texture applied. Emissive-only materials resolve to black diffuse.
fn material_bsdf(material: Material, uv: vec2f) -> BsdfParams {
  var p: BsdfParams;
  p.kind = select(material.kind, BSDF_DIFFUSE, material.kind == MATERIAL_KIND_EMISSIVE);
  p.base_color = material_albedo(material, uv).rgb;
  p.metallic = material.metallic;
  p.roughness = material.roughness;
  if (material.metallic_roughness_texture != NO_TEXTURE) {
    let mr = texture_texel(material.metallic_roughness_texture, uv);
    p.roughness *= mr.g;
    p.metallic *= mr.b;
  }
  p.ior = material.ior;
  p.transmission = material.transmission;
  if (material.transmission_texture != NO_TEXTURE) {
    p.transmission *= texture_texel(material.transmission_texture, uv).r;
  }
  p.specular = material.specular;
  if (material.specular_texture != NO_TEXTURE) {
    p.specular *= texture_texel(material.specular_texture, uv).a;
  }
  p.specular_color = material.specular_color;
  if (material.specular_color_texture != NO_TEXTURE) {
    p.specular_color *= texture_texel(material.specular_color_texture, uv).rgb;
  }
  p.thin_walled = select(0u, 1u, (material.flags & MATERIAL_THIN_WALLED) != 0u);
  return p;
}

// Whether the BSDF reflects on both sides alike, so the shading frame may be turned toward the
// incoming ray; interfaces (glass, transmission) keep their front side.
fn material_is_two_sided_reflector(material: Material, p: BsdfParams) -> bool {
  return material.kind == MATERIAL_KIND_DIFFUSE || material.kind == MATERIAL_KIND_EMISSIVE ||
    (material.kind == MATERIAL_KIND_METALLIC_ROUGHNESS && p.transmission <= 0.0);
}
