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

// The level of detail of texture lookups at the current hit, before the texture's own size: log2 of
// the ray cone's footprint in uv units (integrator/path.wgsl sets it per hit from the ray cone; 0
// elsewhere, e.g. alpha tests during traversal: the sharpest level). A texture of w × h texels then
// reads level texture_lod + log2(sqrt(w·h)) (Akenine-Möller et al. 2021, "Improved Shader and Texture
// Level of Detail Using Ray Cones", JCGT 10(1)).
var<private> texture_lod: f32 = -1e30;

// The second uv set at the current hit (integrator/path.wgsl sets it for scenes that have one).
var<private> surface_uv1: vec2f;

// Texel k of triangle `triangle`'s per-vertex attributes, as f32.
fn triangle_attribute(triangle: u32, k: u32) -> vec4f {
  let row = triangle / TRIANGLE_ATTRIBUTE_TRIANGLES_PER_ROW;
  let column = (triangle % TRIANGLE_ATTRIBUTE_TRIANGLES_PER_ROW) * TRIANGLE_ATTRIBUTE_TEXELS + k;
  return bitcast<vec4f>(textureLoad(triangle_attributes, vec2u(column, row), 0));
}

// The second uv set at barycentrics (u, v) of v1 and v2.
fn triangle_uv1(triangle: u32, bary: vec2f) -> vec2f {
  let a = triangle_attribute(triangle, 3u);
  let b = triangle_attribute(triangle, 4u);
  return (1.0 - bary.x - bary.y) * a.xy + bary.x * a.zw + bary.y * b.xy;
}

// Level k of a mip-mapped texture reference (gpu/pack/mip-chain.ts lays the levels out).
fn texture_level(t: TextureRef, level: u32) -> TextureRef {
  if (level == 0u) {
    return t;
  }
  var r = t;
  var y = 0u;
  for (var j = 1u; j < level; j++) {
    y += max(1u, t.size.y >> j);
  }
  r.origin = t.origin + vec2u(t.size.x, y);
  r.size = max(vec2u(1u), t.size >> vec2u(level));
  return r;
}

// Bilinear filtering inside one level: texel centres sit at half-integers.
fn texture_bilinear(t: TextureRef, st: vec2f) -> vec4f {
  let p = st * vec2f(t.size) - 0.5;
  let p0 = floor(p);
  let f = p - p0;
  let i0 = vec2i(p0);
  let top = mix(texture_fetch(t, i0), texture_fetch(t, i0 + vec2i(1, 0)), f.x);
  let bottom = mix(texture_fetch(t, i0 + vec2i(0, 1)), texture_fetch(t, i0 + vec2i(1, 1)), f.x);
  return mix(top, bottom, f.y);
}

// The texture of reference `index` at uv ((0, 0) top left, 1 = the whole texture), wrapped; linear
// colour. Nearest textures read level 0; filtered ones blend the two mip levels around the ray
// cone's level of detail (trilinear).
fn texture_texel(index: u32, uv: vec2f) -> vec4f {
  let t = scene_texture_ref(index);
  let coords = select(uv, surface_uv1, (t.flags & TEXTURE_UV1) != 0u);
  let st = vec2f(dot(t.transform_u, vec3f(coords, 1.0)), dot(t.transform_v, vec3f(coords, 1.0)));
  if ((t.flags & TEXTURE_BILINEAR) == 0u) {
    // floor keeps negative coordinates wrapping the same way as positive ones.
    return texture_fetch(t, vec2i(floor(st * vec2f(t.size))));
  }
  let lod = clamp(texture_lod + 0.5 * log2(f32(t.size.x) * f32(t.size.y)), 0.0, f32(t.levels - 1u));
  let level = u32(lod);
  let f = lod - f32(level);
  let fine = texture_bilinear(texture_level(t, level), st);
  if (f <= 0.0 || level + 1u >= t.levels) {
    return fine;
  }
  return mix(fine, texture_bilinear(texture_level(t, level + 1u), st), f);
}

// The coverage (alpha) of the colour texture at uv for the alpha test, which runs inside traversal:
// level 0 only and the first uv set, so that traversal keeps few registers (the mip and uv-set logic
// of texture_texel cost E1M1 a sixth of its speed there). 1 without a texture.
fn coverage_texel(index: u32, uv: vec2f) -> f32 {
  if (index == NO_TEXTURE) {
    return 1.0;
  }
  let t = scene_texture_ref(index);
  let st = vec2f(dot(t.transform_u, vec3f(uv, 1.0)), dot(t.transform_v, vec3f(uv, 1.0)));
  if ((t.flags & TEXTURE_BILINEAR) == 0u) {
    return texture_fetch(t, vec2i(floor(st * vec2f(t.size)))).a;
  }
  return texture_bilinear(t, st).a;
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
  let s = scene_triangle_shading(triangle);
  return (1.0 - bary.x - bary.y) * s.uv0 + bary.x * s.uv1 + bary.y * s.uv2;
}

// A cheap hash of a hit, for stochastic transparency: different rays through the same point draw
// different numbers, so alpha blending converges to the blend instead of a fixed dither.
fn coverage_random(triangle: u32, bary: vec2f, salt: u32) -> f32 {
  let h = pcg_hash(triangle ^ pcg_hash(bitcast<u32>(bary.x) ^ pcg_hash(bitcast<u32>(bary.y) ^ salt)));
  return f32(h >> 8u) * (1.0 / 16777216.0);
}

// Whether a triangle with a hit filter (alpha mask or blend) is really there at these barycentrics,
// for a ray identified by `salt`, when it shows `material_index` (its own, or its instance's).
fn alpha_test_passes(material_index: u32, triangle: u32, bary: vec2f, salt: u32) -> bool {
  let material = scene_material(material_index);
  if ((material.flags & (MATERIAL_ALPHA_MASK | MATERIAL_ALPHA_BLEND)) == 0u) {
    return true;
  }
  let coverage = material.opacity * coverage_texel(material.base_color_texture, triangle_uv(triangle, bary));
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
