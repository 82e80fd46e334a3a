// The hybrid recipe's ray-traced passes, after the raster pass has filled the visibility buffer
// (hybrid/visibility). Each pixel's surface is the exact hit of its jittered camera ray, and its
// light is split as a real-time renderer splits it (the same BSDF, the same lights, the same
// traversal as the path tracer):
//
//   L = emission + direct + diffuse_weight · GI + specular_weight · reflection
//
// - hybrid_resolve: the surface's normal and depth (the guide of the GI upsampling) and where it was
//   in the previous frame (TAA's motion), per pixel;
// - hybrid_shade: emission, direct light by next-event estimation (`light_samples` light samples per
//   pixel, each with a shadow ray, plus the torch: soft shadows from area lights) combined by MIS with
//   one BSDF-sampled ray that finds emitters and the sky, and the weight of the diffuse lobe;
// - hybrid_reflect (scenes with non-diffuse materials): the reflection, added to hybrid_shade's:
//   one ray from the specular lobes (a mirror direction or a GGX sample of the visible normals, or
//   through the glass), continued by the path tracer for `reflection_bounces`, weighted by the
//   lobes' directional albedo (Fresnel included: no fixed mix);
// - hybrid_gi: diffuse GI in a smaller target (`gi_scale` of the image per axis): each GI texel
//   takes one pixel of its block (a different one every frame), traces `gi_samples` cosine-
//   distributed paths of `gi_bounces` bounces and keeps what they gather beyond their first hit's
//   own emission (direct light was counted by hybrid_shade), i.e. the cosine-weighted mean of the
//   indirect radiance arriving there.
// Emission a GI or glossy reflection ray finds at its first hit is dropped because hybrid_shade's
// direct light (NEE + its own BSDF ray, MIS-weighted) already counted it; a mirror's reflection keeps
// it (neither NEE nor that BSDF ray, which skips delta lobes, can see it). Expects the scene (group 0) and view (group 1); group 2 adds the buffers.

#import lib/workgroup
#import integrator/path
#import integrator/dispatch
#import view/projection
#import denoise/gbuffer
#import hybrid/visibility

struct HybridParams {
  // The camera of the previous frame (motion vectors).
  previous_camera: Camera,
  // This frame's subpixel offset, as the raster pass used it.
  jitter: vec2f,
  // The GI target's size in texels.
  gi_size: vec2u,
  // GI texels per pixel along each axis (0.25–1).
  gi_scale: f32,
  // Frames rendered so far (which pixel of its block a GI texel traces from).
  frame_index: u32,
  light_samples: u32,
  gi_bounces: u32,
  gi_samples: u32,
  // 0: no reflection rays.
  reflections: u32,
  reflection_bounces: u32,
}

@group(2) @binding(3) var<uniform> hybrid: HybridParams;
@group(2) @binding(4) var visibility: texture_2d<u32>;
// Per pixel: xyz = shading normal turned toward the camera, w = linear depth (MISS_DEPTH: a miss).
@group(2) @binding(5) var<storage, read_write> guide: array<vec4f>;
// Per pixel: xy = where the surface was in the previous frame (pixels; OFF_SCREEN: nowhere), z = its
// depth there, w = 1 on a surface, 0 for a miss.
@group(2) @binding(6) var<storage, read_write> motion: array<vec4f>;
// Per pixel: emission + direct + specular_weight · reflection (rgb).
@group(2) @binding(7) var<storage, read_write> lit: array<vec4f>;
// Per pixel: the diffuse lobe's weight (rgb) the upsampled GI is multiplied by.
@group(2) @binding(8) var<storage, read_write> diffuse_weight: array<vec4f>;
// Per GI texel, an illumination pair (denoise/gbuffer pack_illumination): the indirect radiance
// (cosine-weighted mean) and, as its variance, its luminance² (the à-trous filter's guess for a
// one-sample estimate).
@group(2) @binding(9) var<storage, read_write> gi: array<vec2u>;
// Per GI texel: the surface of the pixel it was traced from (normal, linear depth, material), the
// guide of the à-trous filter and of the upsampling.
@group(2) @binding(10) var<storage, read_write> gi_guide: array<SurfaceTexel>;

fn pixel_ray(pixel: vec2u) -> Ray {
  return camera_ray(vec2f(pixel) + 0.5 + hybrid.jitter);
}

fn pixel_hit(pixel: vec2u, ray: Ray) -> Hit {
  return visible_hit(ray, textureLoad(visibility, pixel, 0).xy);
}

// The surface's frame as the path tracer builds it at a camera hit: normals turned toward the ray
// for opaque reflectors (diffuse, metal, plastics), the front kept for interfaces.
struct Shading {
  surface: Surface,
  material: Material,
  // Geometric and shading normal (normal-mapped), both turned as described.
  ng: vec3f,
  ns: vec3f,
  bsdf: BsdfParams,
}

fn shading_at(hit: Hit, ray: Ray) -> Shading {
  let surface = surface_at(hit, ray);
  let material = scene_material(surface.material);
  if (SCENE_HAS_GENERAL_MATERIALS) {
    texture_lod = texture_lod_at(surface, hit.triangle, path_settings().pixel_spread * hit.t, ray.direction);
  }
  var ng = surface.geometric_normal;
  var ns = surface.shading_normal;
  var bsdf = material_bsdf(material, surface.uv);
  let front = dot(ng, ray.direction) < 0.0;
  if (!SCENE_HAS_GENERAL_MATERIALS) {
    let facing = select(-1.0, 1.0, front);
    return Shading(surface, material, facing * ng, facing * ns, bsdf);
  }
  ns = normal_mapped(surface, hit, material);
  if (!front && material_is_two_sided_reflector(material, bsdf)) {
    ng = -ng;
    ns = -ns;
  }
  return Shading(surface, material, ng, ns, bsdf);
}

fn to_local(frame: mat3x3f, v: vec3f) -> vec3f {
  return vec3f(dot(v, frame[0]), dot(v, frame[1]), dot(v, frame[2]));
}

// f · |cos| for light arriving along wi_world (the Lambertian path for diffuse-only scenes), or 0
// where the geometric and shading normals disagree about the side.
fn bsdf_cos(s: Shading, wo_world: vec3f, wi_world: vec3f) -> vec3f {
  if (!SCENE_HAS_GENERAL_MATERIALS) {
    let cos_s = dot(s.ns, wi_world);
    if (cos_s <= 0.0 || dot(s.ng, wi_world) <= 0.0) {
      return vec3f(0.0);
    }
    return s.bsdf.base_color * INV_PI * cos_s;
  }
  let frame = orthonormal_basis(s.ns);
  let wo = to_local(frame, wo_world);
  let wi = to_local(frame, wi_world);
  if (dot(s.ng, wi_world) * wi.z <= 0.0) {
    return vec3f(0.0);
  }
  return bsdf_eval(s.bsdf, wo, wi) * abs(wi.z);
}

// The solid-angle density with which bsdf_ray (below) picks wi_world (its non-delta lobes).
fn bsdf_density(s: Shading, wo_world: vec3f, wi_world: vec3f) -> f32 {
  if (!SCENE_HAS_GENERAL_MATERIALS) {
    return cosine_hemisphere_pdf(dot(s.ns, wi_world));
  }
  let frame = orthonormal_basis(s.ns);
  return bsdf_pdf(s.bsdf, to_local(frame, wo_world), to_local(frame, wi_world));
}

// The power heuristic for `count` light samples against one BSDF sample (Veach 1997, §9.2.4):
// the weight of a light sample of density light_pdf, or (swapped) of the BSDF sample.
fn light_weight(count: u32, light_pdf: f32, bsdf_pdf: f32) -> f32 {
  let n = f32(count) * light_pdf;
  return select(0.0, n * n / (n * n + bsdf_pdf * bsdf_pdf), n > 0.0);
}

// Light a pass gathered, and the rays it took.
struct Gathered {
  radiance: vec3f,
  extension_rays: u32,
  shadow_rays: u32,
}

// Direct light: `count` samples of the scene's lights (area, punctual, environment) and one of the
// torch, each with a shadow ray, combined by multiple importance sampling with one BSDF-sampled ray
// that counts the emitters and the sky it meets (bsdf_ray). Without the BSDF ray a point beside a
// small, bright emitter (E1M1's lamps) would see rare huge light samples: fireflies.
fn direct_light(s: Shading, wo_world: vec3f, count: u32, rng: ptr<function, Rng>) -> Gathered {
  var result = Gathered(vec3f(0.0), 0u, 0u);
  let settings = path_settings();
  if (scene_light_count() > 0u) {
    var sum = vec3f(0.0);
    for (var k = 0u; k < count; k++) {
      let light = sample_light(s.surface.position, rng_next_2d(rng), rng_next_2d(rng));
      if (light.pdf <= 0.0) {
        continue;
      }
      let f = bsdf_cos(s, wo_world, light.direction);
      if (all(f <= vec3f(0.0))) {
        continue;
      }
      let origin = spawn_point(s.surface, select(-s.ng, s.ng, dot(s.ng, light.direction) > 0.0));
      result.shadow_rays += 1u;
      if (!trace_any(Ray(origin, 0.0, light.direction, light.distance * (1.0 - SHADOW_RAY_SHORTEN)))) {
        let weight = select(light_weight(count, light.pdf, bsdf_density(s, wo_world, light.direction)), 1.0, light.delta);
        sum += f * light.radiance * (weight / light.pdf);
      }
    }
    result.radiance += sum / f32(max(count, 1u));
  }
  let found = bsdf_ray(s, wo_world, count, rng);
  result.radiance += found.radiance;
  result.extension_rays += found.extension_rays;
  let torch = sample_torch(settings.torch, settings.torch_position, s.surface.position, rng_next_2d(rng));
  if (torch.pdf > 0.0) {
    let f = bsdf_cos(s, wo_world, torch.direction);
    if (any(f > vec3f(0.0))) {
      let origin = spawn_point(s.surface, select(-s.ng, s.ng, dot(s.ng, torch.direction) > 0.0));
      result.shadow_rays += 1u;
      if (!trace_any(Ray(origin, 0.0, torch.direction, torch.distance * (1.0 - SHADOW_RAY_SHORTEN)))) {
        result.radiance += f * torch.radiance / torch.pdf;
      }
    }
  }
  return result;
}

// The BSDF half of direct light: one direction from the BSDF's non-delta lobes, traced to what it
// meets first; an emitter seen from its emitting side, or the sky, counts with the MIS weight that
// complements the light samples'. A delta lobe's sample is left to the reflection ray.
fn bsdf_ray(s: Shading, wo_world: vec3f, count: u32, rng: ptr<function, Rng>) -> Gathered {
  var result = Gathered(vec3f(0.0), 0u, 0u);
  var wi: vec3f;
  var weight: vec3f;
  var pdf: f32;
  if (!SCENE_HAS_GENERAL_MATERIALS) {
    wi = orthonormal_basis(s.ns) * sample_cosine_hemisphere(rng_next_2d(rng));
    pdf = cosine_hemisphere_pdf(dot(wi, s.ns));
    weight = s.bsdf.base_color;
    if (dot(wi, s.ng) <= 0.0 || pdf <= 0.0) {
      return result;
    }
  } else {
    let frame = orthonormal_basis(s.ns);
    let u3 = vec3f(rng_next_2d(rng), rng_next_f32(rng));
    let b = bsdf_sample(s.bsdf, to_local(frame, wo_world), u3);
    if (!b.valid || b.delta) {
      return result;
    }
    wi = frame * b.wi;
    if (dot(s.ng, wi) * b.wi.z <= 0.0) {
      return result;
    }
    pdf = b.pdf;
    weight = b.weight;
  }
  let origin = spawn_point(s.surface, select(-s.ng, s.ng, dot(s.ng, wi) > 0.0));
  let ray = Ray(origin, 0.0, wi, T_MISS);
  let hit = trace_closest(ray);
  result.extension_rays = 1u;
  if (hit.triangle == NO_TRIANGLE) {
    if (SCENE_HAS_ENVIRONMENT) {
      let seen = environment_radiance(wi) + sun_radiance(wi);
      result.radiance = weight * seen * light_weight(1u, pdf, f32(count) * environment_light_pdf(wi));
    }
    return result;
  }
  let surface = surface_at(hit, ray);
  let material = scene_material(surface.material);
  let cos_emitter = emitter_cosine(material, -dot(surface.geometric_normal, wi));
  if (cos_emitter > 0.0 && any(material.emission > vec3f(0.0))) {
    let light_pdf = emitter_pdf(surface, material, origin, hit.t, cos_emitter);
    result.radiance = weight * material_emission(material, surface.uv, wi) * light_weight(1u, pdf, f32(count) * light_pdf);
  }
  return result;
}

// How a surface's reflectance divides between the diffuse lobe (lit by the GI target) and the
// specular lobes (lit by the reflection ray), from the BSDF's own directional albedos at μo.
struct LobeSplit {
  diffuse: vec3f,
  // Metal + dielectric layer (+ the metal's multiple scattering): F-weighted directional albedo.
  specular: vec3f,
  // The glass lobe's weight (reflection and transmission, chosen by Fresnel when traced).
  glass: f32,
  alpha: f32,
  delta: bool,
}

fn lobe_split(p: BsdfParams, wo: vec3f) -> LobeSplit {
  if (!SCENE_HAS_GENERAL_MATERIALS || p.kind == BSDF_DIFFUSE) {
    return LobeSplit(p.base_color, vec3f(0.0), 0.0, 1.0, false);
  }
  let l = bsdf_lobes(p, wo);
  let diffuse = l.base * l.albedo * (vec3f(1.0) - l.e_layer_o);
  let single = l.metal * (l.metal_f0 * l.e1_o + (vec3f(1.0) - l.metal_f0) * l.e5_o) + l.base * l.e_layer_o;
  let multiple = l.ms_scale * PI * (1.0 - bsdf_table_e1_avg(l.roughness));
  return LobeSplit(diffuse, single + multiple, l.glass, l.alpha, l.is_delta);
}

// One ray from the specular lobes, continued by the path tracer. For the glass lobe, reflection or
// transmission is chosen by Fresnel (so each carries its own weight); otherwise the reflected
// direction about a GGX visible normal (the mirror direction when smooth).
fn reflection(s: Shading, split: LobeSplit, ray: Ray, rng: ptr<function, Rng>) -> Gathered {
  var out = Gathered(vec3f(0.0), 0u, 0u);
  let frame = orthonormal_basis(s.ns);
  let wo = to_local(frame, -ray.direction);
  let spec_weight = luminance(split.specular);
  let total = spec_weight + split.glass;
  if (total <= 1e-3 || abs(wo.z) < 1e-6) {
    return out;
  }
  let side = select(-1.0, 1.0, wo.z >= 0.0);
  let o = vec3f(wo.xy, wo.z * side);
  let u = rng_next_2d(rng);
  let choose = rng_next_f32(rng);
  var wi: vec3f;
  var weight: vec3f;
  var delta = split.delta;
  if (choose * total < split.glass) {
    // The glass lobe, smooth: reflect with probability F, else refract (thin glass passes straight).
    let eta = select(1.0 / s.bsdf.ior, s.bsdf.ior, side > 0.0);
    let thin = s.bsdf.thin_walled != 0u;
    let f = fresnel_dielectric(o.z, select(eta, s.bsdf.ior, thin));
    var i: vec3f;
    if (rng_next_f32(rng) < f) {
      i = vec3f(-o.xy, o.z);
      weight = vec3f(1.0);
    } else {
      i = select(refract(-o, vec3f(0.0, 0.0, 1.0), 1.0 / eta), -o, thin);
      weight = s.bsdf.base_color / select(eta * eta, 1.0, thin);
    }
    wi = vec3f(i.xy, i.z * side);
    // The glass lobe's weight over the probability of choosing it (glass / total).
    weight *= total;
    delta = true;
  } else {
    let m = select(ggx_sample_visible_normal(o, split.alpha, u), vec3f(0.0, 0.0, 1.0), split.delta);
    let i = reflect(-o, m);
    if (i.z <= 0.0) {
      return out;
    }
    wi = vec3f(i.xy, i.z * side);
    weight = split.specular * total / spec_weight;
  }
  let wi_world = frame * wi;
  let below = dot(s.ng, wi_world) < 0.0;
  let origin = spawn_point(s.surface, select(s.ng, -s.ng, below));
  var record = path_record(NO_RESTIR_PIXEL);
  var settings = path_settings();
  settings.max_bounces = hybrid.reflection_bounces;
  let path = trace_path(Ray(origin, 0.0, normalize(wi_world), T_MISS), rng, settings, &record);
  // What the ray sees first: counted by next-event estimation unless the lobe is a delta.
  let first = select(record.primary.emission, vec3f(0.0), delta);
  let radiance = max(path.radiance - first, vec3f(0.0));
  out.radiance = select(vec3f(0.0), weight * radiance, is_finite_vec3(radiance));
  out.extension_rays = path.extension_rays;
  out.shadow_rays = path.shadow_rays;
  return out;
}

@compute @workgroup_size(PIXEL_TILE_X, PIXEL_TILE_Y)
fn hybrid_resolve(@builtin(global_invocation_id) id: vec3u) {
  let pixel = id.xy;
  if (any(pixel >= view.image_size)) {
    return;
  }
  let index = pixel.y * view.image_size.x + pixel.x;
  let ray = pixel_ray(pixel);
  let hit = pixel_hit(pixel, ray);
  if (hit.triangle == NO_TRIANGLE) {
    let previous = project_offset(hybrid.previous_camera, view.image_size, ray.direction);
    guide[index] = vec4f(-ray.direction, MISS_DEPTH);
    motion[index] = vec4f(select(vec2f(OFF_SCREEN), previous.xy - hybrid.jitter, previous.z > 0.0), MISS_DEPTH, 0.0);
    return;
  }
  let surface = surface_at(hit, ray);
  let normal = select(surface.shading_normal, -surface.shading_normal, dot(surface.shading_normal, ray.direction) > 0.0);
  let depth = dot(surface.position - view.camera.position, view.camera.forward);
  let previous = project_point(hybrid.previous_camera, view.image_size, previous_world_point(hit.instance, surface.position));
  guide[index] = vec4f(normal, depth);
  // The sample sits at the pixel centre + jitter; the history holds pixel centres: take the jitter off,
  // so that a still view fetches its history exactly and is not blurred a little more every frame.
  motion[index] = vec4f(select(vec2f(OFF_SCREEN), previous.xy - hybrid.jitter, previous.z > 0.0), previous.z, 1.0);
}

@compute @workgroup_size(PIXEL_TILE_X, PIXEL_TILE_Y)
fn hybrid_shade(@builtin(global_invocation_id) id: vec3u, @builtin(local_invocation_index) local: u32) {
  begin_ray_count(local);
  let pixel = id.xy;
  if (all(pixel < view.image_size)) {
    let index = pixel.y * view.image_size.x + pixel.x;
    var rng = rng_seed(index, params.sample_index, params.seed);
    let ray = pixel_ray(pixel);
    let hit = pixel_hit(pixel, ray);
    var radiance = vec3f(0.0);
    var weight = vec3f(0.0);
    var extension_rays = 0u;
    var shadow_rays = 0u;
    if (hit.triangle == NO_TRIANGLE) {
      if (SCENE_HAS_ENVIRONMENT) {
        radiance = environment_radiance(ray.direction) + sun_radiance(ray.direction);
      }
    } else {
      let s = shading_at(hit, ray);
      if (emitter_cosine(s.material, -dot(s.surface.geometric_normal, ray.direction)) > 0.0 && any(s.material.emission > vec3f(0.0))) {
        radiance += material_emission(s.material, s.surface.uv, ray.direction);
      }
      if (s.material.kind != MATERIAL_KIND_EMISSIVE && params.max_bounces > 0u) {
        let direct = direct_light(s, -ray.direction, max(hybrid.light_samples, 1u), &rng);
        radiance += direct.radiance;
        extension_rays += direct.extension_rays;
        shadow_rays += direct.shadow_rays;
        weight = lobe_split(s.bsdf, to_local(orthonormal_basis(s.ns), -ray.direction)).diffuse;
      }
    }
    lit[index] = vec4f(select(vec3f(0.0), radiance, is_finite_vec3(radiance)), 1.0);
    diffuse_weight[index] = vec4f(weight, 1.0);
    count_rays(extension_rays, shadow_rays);
  }
  end_ray_count(local);
}

// Reflections, a pass of their own after hybrid_shade (scenes with glossy, mirror or glass
// materials, reflections on): kept apart so that neither kernel grows too large for the shader
// compilers of software adapters.
@compute @workgroup_size(PIXEL_TILE_X, PIXEL_TILE_Y)
fn hybrid_reflect(@builtin(global_invocation_id) id: vec3u, @builtin(local_invocation_index) local: u32) {
  begin_ray_count(local);
  let pixel = id.xy;
  if (all(pixel < view.image_size)) {
    let index = pixel.y * view.image_size.x + pixel.x;
    let ray = pixel_ray(pixel);
    let hit = pixel_hit(pixel, ray);
    var extension_rays = 0u;
    var shadow_rays = 0u;
    if (hit.triangle != NO_TRIANGLE) {
      let s = shading_at(hit, ray);
      if (s.material.kind != MATERIAL_KIND_EMISSIVE && params.max_bounces > 0u) {
        var rng = rng_seed(index, params.sample_index, params.seed ^ 0xbb67ae85u);
        let split = lobe_split(s.bsdf, to_local(orthonormal_basis(s.ns), -ray.direction));
        let r = reflection(s, split, ray, &rng);
        lit[index] += vec4f(r.radiance, 0.0);
        extension_rays += r.extension_rays;
        shadow_rays += r.shadow_rays;
      }
    }
    count_rays(extension_rays, shadow_rays);
  }
  end_ray_count(local);
}

// The pixel a GI texel traces from this frame: one of its block's, in an order that covers the block.
fn gi_source_pixel(texel: vec2u) -> vec2u {
  let side = max(u32(round(1.0 / hybrid.gi_scale)), 1u);
  let cells = side * side;
  let mixed = texel.x * 3u + texel.y * 5u;
  let k = (hybrid.frame_index * 7u + mixed) % cells;
  let offset = vec2u(k % side, k / side);
  let p = texel * side + offset;
  return min(p, view.image_size - 1u);
}

@compute @workgroup_size(PIXEL_TILE_X, PIXEL_TILE_Y)
fn hybrid_gi(@builtin(global_invocation_id) id: vec3u, @builtin(local_invocation_index) local: u32) {
  begin_ray_count(local);
  let texel = id.xy;
  if (all(texel < hybrid.gi_size)) {
    let index = texel.y * hybrid.gi_size.x + texel.x;
    let pixel = gi_source_pixel(texel);
    let ray = pixel_ray(pixel);
    let hit = pixel_hit(pixel, ray);
    var sum = vec3f(0.0);
    var extension_rays = 0u;
    var shadow_rays = 0u;
    var guide_value = pack_surface(-ray.direction, MISS_DEPTH, NO_ID);
    if (hit.triangle != NO_TRIANGLE) {
      let s = shading_at(hit, ray);
      let depth = dot(s.surface.position - view.camera.position, view.camera.forward);
      let facing = select(1.0, -1.0, dot(s.ns, ray.direction) > 0.0);
      guide_value = pack_surface(facing * s.ns, depth, s.surface.material);
      if (s.material.kind != MATERIAL_KIND_EMISSIVE && params.max_bounces > 0u) {
        var rng = rng_seed(pixel.y * view.image_size.x + pixel.x, params.sample_index, params.seed ^ 0x6a09e667u);
        let n = facing * s.ns;
        let g = facing * s.ng;
        let basis = orthonormal_basis(n);
        var settings = path_settings();
        settings.max_bounces = hybrid.gi_bounces;
        for (var k = 0u; k < hybrid.gi_samples; k++) {
          let wi = basis * sample_cosine_hemisphere(rng_next_2d(&rng));
          if (dot(wi, g) <= 0.0) {
            continue;
          }
          var record = path_record(NO_RESTIR_PIXEL);
          let path = trace_path(Ray(spawn_point(s.surface, g), 0.0, wi, T_MISS), &rng, settings, &record);
          let indirect = max(path.radiance - record.primary.emission, vec3f(0.0));
          sum += select(vec3f(0.0), indirect, is_finite_vec3(indirect));
          extension_rays += path.extension_rays;
          shadow_rays += path.shadow_rays;
        }
        sum /= f32(max(hybrid.gi_samples, 1u));
      }
    }
    let l = luminance(sum);
    gi[index] = pack_illumination(sum, l * l);
    gi_guide[index] = guide_value;
    count_rays(extension_rays, shadow_rays);
  }
  end_ray_count(local);
}
