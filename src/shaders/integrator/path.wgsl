// The path integrator as a library: trace_path follows one camera path, adding emission met along the
// way, next-event estimation on every light (scene/lights.wgsl) and on the torch, combined with
// BSDF sampling (scene/bsdf.wgsl) by multiple importance sampling (power heuristic), with Russian
// roulette from the fourth bounce on and Beer–Lambert absorption inside glass. A path's radiance and
// throughput are four channels: RGB (and a spare 0) in RGB mode, four wavelengths in spectral mode
// (lib/spectrum: hero wavelength + three companions; RGB values are lifted where they enter, and a
// dispersive interface keeps only the hero). The entry points
// (passes/path-trace, passes/path-trace-frame, passes/hybrid, wavefront/frame) call it; a new
// material kind is a case of the BSDF module, not a change here. Follows Veach 1997, ch. 9, and
// pbrt-v4's PathIntegrator (§13.4).
//
// The integrator does not know who calls it. What a caller wants beyond the radiance comes back in
// a PathRecord, as pbrt-v4's Li fills an optional VisibleSurface: the first hit's albedo and
// emission (demodulation), and, where the caller collects them (the wavefront, which queues them
// for a kernel of its own), the shadow rays each bounce makes; otherwise they are traced where they
// are made. A caller that reads none of it costs nothing: the writes are dead and compiled away.
// (Tracing them after the bounce instead, from the record, kept the requests live through BSDF
// sampling: 5-10 % slower progressive rendering and 18 % slower real-time frames on the H200.)
// Expects the scene (group 0); the caller passes the per-dispatch settings.

#import lib/constants
#import lib/random
#import lib/sampling
#import lib/color
#import lib/spectrum
#import lib/ray-offset
#import scene/bvh
#import scene/surface
#import scene/lights
#import scene/materials
#import scene/environment
#import scene/bsdf
#import scene/dispersion
#import scene/torch
#import restir/reservoir

// The closed set of light-sampling strategies; the host's names live in renderer/settings.ts.
const LIGHT_SAMPLING_BSDF: u32 = 0u;
const LIGHT_SAMPLING_MIS: u32 = 1u;

// Russian roulette starts once a path has this many bounces.
const ROULETTE_START_BOUNCE: u32 = 3u;
// Shadow rays stop this fraction short of the light so they do not hit the light itself.
const SHADOW_RAY_SHORTEN: f32 = 1e-4;

// Whether the kernel's estimator includes ReSTIR direct light: at the first bounce, a path whose hit
// is on the pixel-centre surface's material takes its direct light from the pixel's reservoir (the
// record's `restir`, handed in by the caller) instead of one light sample (restir_direct). A
// property of the estimator, as SPECTRAL is: kernels without it (the progressive one) do not
// compile the reservoir's code, and their estimator is unchanged (gpu/kernel-variants.ts sets it).
override RESTIR: bool = false;

// The pixel's final reservoir and the pixel-centre surface it was made for (restir/restir). valid:
// the frame uses ReSTIR and the centre hit a surface.
struct RestirPixel {
  valid: bool,
  point: LightPoint,
  w: f32,
  position: vec3f,
  normal: vec3f,
  depth: f32,
  id: u32,
}

const NO_RESTIR_PIXEL = RestirPixel(false, LightPoint(0u, false, vec2u(0u)), 0.0, vec3f(0.0), vec3f(0.0, 0.0, 1.0), 0.0, 0xffffffffu);

// What a camera ray's first hit contributes, for demodulation: the albedo there (1 for a miss) and the
// emission seen there (radiance that needs no filtering).
struct PrimaryHit {
  albedo: vec3f,
  emission: vec3f,
  // Material index of the first hit (NO_PRIMARY_ID for a miss): the frame kernel keeps a sample's
  // own emission only where this differs from the pixel-centre surface's.
  id: u32,
}
const NO_PRIMARY_ID: u32 = 0xffffffffu;

// What a path needs to know beyond the scene.
struct PathSettings {
  // Scattering events per path: 0 shows emitters only, 1 adds direct light.
  max_bounces: u32,
  light_sampling: u32,
  torch: TorchLight,
  torch_position: vec3f,
  // Angle (radians) one pixel subtends at the camera: the spread of a camera ray's cone.
  pixel_spread: f32,
}

// The spread a ray cone gets from a non-delta bounce: glossy lobes widen it by about twice the GGX α
// (Akenine-Möller et al. 2021 widen by the surface's curvature; a lobe's width matters more here),
// diffuse by this much — texture detail seen after a diffuse bounce is averaged away anyway.
const DIFFUSE_CONE_SPREAD: f32 = 2.0;

struct PathResult {
  radiance: vec3f,
  extension_rays: u32,
  shadow_rays: u32,
}

// A path between bounces: everything trace_path carries from one bounce to the next.
struct PathState {
  // Radiance gathered so far, in the path's channels (channels_to_rgb turns it into RGB).
  radiance: vec4f,
  throughput: vec4f,
  // Absorption coefficient of the medium the ray travels in (inside glass with a volume).
  absorption: vec4f,
  // The ray to extend the path with (t_min 0, t_max T_MISS).
  ray: Ray,
  // Solid-angle density of the BSDF sample that produced `ray` (unused for the camera ray), and
  // whether it came from a delta lobe (then no light sample could have found what it hits).
  last_bsdf_pdf: f32,
  after_delta: bool,
  // The ray cone (texture level of detail): width at the ray's origin and spread angle.
  cone_width: f32,
  cone_spread: f32,
  // The random number that chose the path's wavelengths (spectral mode; spectrum_begin_path).
  spectrum_u: f32,
}

// A shadow ray and what it adds to the path's radiance if nothing blocks it.
struct ShadowRequest {
  ray: Ray,
  contribution: vec4f,
}
// The shadow rays one path_step may hand back (a collecting record): [SHADOW_LIGHT] and
// [SHADOW_TORCH], each present where its bit (1 << slot) is set in shadow_mask.
const SHADOW_LIGHT: u32 = 0u;
const SHADOW_TORCH: u32 = 1u;

// What a path and its caller exchange besides the path's state: what the caller hands in (the pixel's
// reservoir, RESTIR kernels only; whether it collects the shadow rays) and what path_step hands back
// (the first hit; the shadow rays of the last bounce where it collects them).
struct PathRecord {
  restir: RestirPixel,
  // Whether this path's first bounce took its direct light from the reservoir (then BSDF rays that
  // find a light of the table at the next vertex add nothing: the light strategies cover it all).
  restir_used: bool,
  // The first hit, written at bounce 0 (albedo 1, no emission and NO_PRIMARY_ID until then).
  primary: PrimaryHit,
  // false: path_step traces its shadow rays where it makes them (the megakernels); true: it hands
  // them back in `shadows` for the caller to trace later (the wavefront's shadow queues). Each caller
  // makes its records with a constant here, so the other branch compiles away.
  collect_shadows: bool,
  shadows: array<ShadowRequest, 2>,
  shadow_mask: u32,
}

// A record for a path of the pixel whose reservoir is `restir` (NO_RESTIR_PIXEL: none), whose shadow
// rays path_step traces itself.
fn path_record(restir: RestirPixel) -> PathRecord {
  var r: PathRecord;
  r.restir = restir;
  r.restir_used = false;
  r.primary = PrimaryHit(vec3f(1.0), vec3f(0.0), NO_PRIMARY_ID);
  r.collect_shadows = false;
  r.shadow_mask = 0u;
  return r;
}

// A record that collects the shadow rays instead (no reservoir: the wavefront has no ReSTIR).
fn path_record_collecting() -> PathRecord {
  var r = path_record(NO_RESTIR_PIXEL);
  r.collect_shadows = true;
  return r;
}

// MIS weight of radiance found by a BSDF-sampled ray whose light-sampling density is light_pdf.
fn bsdf_hit_weight(record: ptr<function, PathRecord>, bounce: u32, use_nee: bool, after_delta: bool, bsdf_pdf: f32, light_pdf: f32) -> f32 {
  if (RESTIR && bounce == 1u && (*record).restir_used) {
    return select(1.0, 0.0, light_pdf > 0.0);
  }
  if (bounce == 0u || !use_nee || after_delta) {
    return 1.0;
  }
  return power_heuristic(bsdf_pdf, light_pdf);
}

// The larger of the path's live channels (RGB mode: r, g, b; spectral: the four wavelengths).
fn channels_max(c: vec4f) -> f32 {
  let rgb = max(c.x, max(c.y, c.z));
  return select(rgb, max(rgb, c.w), SPECTRAL);
}

// A camera path before its first bounce (draws the wavelengths in spectral mode).
fn path_begin(first_ray: Ray, rng: ptr<function, Rng>, settings: PathSettings) -> PathState {
  var u = 0.0;
  if (SPECTRAL) {
    u = rng_next_f32(rng);
    spectrum_begin_path(u);
  }
  return PathState(vec4f(0.0), lift(vec3f(1.0)), vec4f(0.0), first_ray, 0.0, false, 0.0, settings.pixel_spread, u);
}

// Next-event estimation against the light table (use_nee) or punctual lights alone.
fn path_uses_nee(settings: PathSettings) -> bool {
  return settings.light_sampling == LIGHT_SAMPLING_MIS && scene_light_count() > 0u;
}

// A shadow ray of path_step: traced now, or handed back in a collecting record.
fn path_shadow(state: ptr<function, PathState>, record: ptr<function, PathRecord>, slot: u32, ray: Ray, contribution: vec4f, result: ptr<function, PathResult>) {
  if ((*record).collect_shadows) {
    (*record).shadows[slot] = ShadowRequest(ray, contribution);
    (*record).shadow_mask |= 1u << slot;
    return;
  }
  (*result).shadow_rays += 1u;
  if (!trace_any(ray)) {
    (*state).radiance += contribution;
  }
}

// Whether this first-bounce hit takes its direct light from the pixel's reservoir.
fn restir_applies(record: ptr<function, PathRecord>, bounce: u32, use_nee: bool, material_id: u32) -> bool {
  return RESTIR && !SPECTRAL && bounce == 0u && use_nee && (*record).restir.valid && material_id == (*record).restir.id;
}

// Direct light at a first hit p (Lambertian: f = brdf) from the pixel's reservoir, unbiased for
// every p, not only the pixel-centre surface c the reservoir was made for. The reservoir's W is an
// unbiased contribution weight over S = {y : p̂_c(y) · V_c(y) > 0} (restir/restir); one more light
// sample, drawn as usual, covers the rest of the light points (those occluded from c, or below its
// horizon: sub-pixel penumbrae and edges), so the two estimate disjoint parts of the same integral.
fn restir_direct(state: ptr<function, PathState>, record: ptr<function, PathRecord>, p: vec3f, origin: vec3f, ng: vec3f, ns: vec3f, brdf: vec3f, rng: ptr<function, Rng>, result: ptr<function, PathResult>) {
  (*record).restir_used = true;
  let pixel = (*record).restir;
  // The shadow rays are gathered and traced in one loop: one call site of the traversal, which
  // every GPU compiler inlines. (Never collected: a collecting record has no reservoir.)
  var rays: array<Ray, 2>;
  var contributions: array<vec4f, 2>;
  var count = 0u;
  let v = view_light_point(pixel.point, p);
  let cos_reservoir = dot(ns, v.direction);
  if (pixel.w > 0.0 && v.pdf > 0.0 && cos_reservoir > 0.0 && dot(ng, v.direction) > 0.0) {
    rays[0] = Ray(origin, 0.0, v.direction, v.distance * (1.0 - SHADOW_RAY_SHORTEN));
    contributions[0] = (*state).throughput * lift(brdf) * lift(v.radiance) * (cos_reservoir * v.geometry * pixel.w);
    count = 1u;
  }
  let point = restir_candidate(p, rng);
  let s = view_light_point(point, p);
  let cos_sample = dot(ns, s.direction);
  if (s.pdf > 0.0 && cos_sample > 0.0 && dot(ng, s.direction) > 0.0 && any(s.radiance > vec3f(0.0))) {
    let c = view_light_point(point, pixel.position);
    var in_reservoir = false;
    if (restir_goal(c, pixel.normal) > 0.0) {
      (*result).shadow_rays += 1u;
      in_reservoir = restir_visible(pixel.position, pixel.normal, pixel.depth, c);
    }
    if (!in_reservoir) {
      rays[count] = Ray(origin, 0.0, s.direction, s.distance * (1.0 - SHADOW_RAY_SHORTEN));
      contributions[count] = (*state).throughput * lift(brdf) * lift(s.radiance) * (cos_sample / s.pdf);
      count += 1u;
    }
  }
  for (var i = 0u; i < count; i++) {
    path_shadow(state, record, SHADOW_LIGHT, rays[i], contributions[i], result);
  }
}

// One bounce of a path whose ray (*state).ray has found `hit`: emission met there, light sampling
// (shadow rays through path_shadow: traced, or handed back in a collecting record), the BSDF sample
// that sets the next ray, Russian roulette. Returns whether the path goes on. trace_path's loop
// body, shared with the wavefront's shade kernel.
fn path_step(state: ptr<function, PathState>, record: ptr<function, PathRecord>, hit: Hit, bounce: u32, rng: ptr<function, Rng>, settings: PathSettings, result: ptr<function, PathResult>) -> bool {
  (*record).shadow_mask = 0u;
  let ray = (*state).ray;
  let use_nee = path_uses_nee(settings);
  // Punctual lights are not geometry: no BSDF ray finds them, so even BSDF-only sampling samples
  // them. It draws from the whole light table and keeps only punctual picks (dividing by their
  // selection probability keeps it unbiased); other lights are left to BSDF rays, weighted 1.
  let sample_lights = use_nee || (SCENE_HAS_PUNCTUAL_LIGHTS && scene_light_count() > 0u);

  if (SCENE_HAS_GENERAL_MATERIALS && any((*state).absorption > vec4f(0.0))) {
    (*state).throughput *= exp(-(*state).absorption * min(hit.t, 1e30));
  }
  if (hit.triangle == NO_TRIANGLE) {
    if (SCENE_HAS_ENVIRONMENT) {
      var seen = environment_radiance(ray.direction) + sun_radiance(ray.direction);
      let weight = bsdf_hit_weight(record, bounce, use_nee, (*state).after_delta, (*state).last_bsdf_pdf, environment_light_pdf(ray.direction));
      (*state).radiance += (*state).throughput * lift(seen) * weight;
      if (bounce == 0u) {
        (*record).primary = PrimaryHit(vec3f(1.0), channels_to_rgb((*state).radiance), NO_PRIMARY_ID);
      }
    }
    return false;
  }
  let surface = surface_at(hit, ray);
  let material = scene_material(surface.material);
  if (SCENE_HAS_GENERAL_MATERIALS) {
    (*state).cone_width += (*state).cone_spread * hit.t;
    texture_lod = texture_lod_at(surface, hit.triangle, (*state).cone_width, ray.direction);
    if (textureDimensions(triangle_attributes).x > 1u) {
      surface_uv1 = triangle_uv1(hit.triangle, stored_bary(hit));
    }
  }

  // Emission, seen only from the side the geometric normal faces (both, for two-sided emitters).
  let cos_emitter = emitter_cosine(material, -dot(surface.geometric_normal, ray.direction));
  if (cos_emitter > 0.0 && any(material.emission > vec3f(0.0))) {
    let weight = bsdf_hit_weight(record, bounce, use_nee, (*state).after_delta, (*state).last_bsdf_pdf, emitter_pdf(surface, material, ray.origin, hit.t, cos_emitter));
    (*state).radiance += (*state).throughput * lift(material_emission(material, surface.uv, ray.direction)) * weight;
  }
  if (bounce == 0u) {
    (*record).primary = PrimaryHit(material_albedo(material, surface.uv).rgb, channels_to_rgb((*state).radiance), surface.material);
  }
  if (bounce == settings.max_bounces || material.kind == MATERIAL_KIND_EMISSIVE) {
    return false;
  }

  if (!SCENE_HAS_GENERAL_MATERIALS) {
    // Diffuse surfaces only: reflection on both sides, so turn both normals toward the ray.
    let facing = select(1.0, -1.0, dot(surface.geometric_normal, ray.direction) > 0.0);
    let ng = facing * surface.geometric_normal;
    let ns = facing * surface.shading_normal;
    let origin = spawn_point(surface, ng);
    let albedo = material_albedo(material, surface.uv).rgb;
    let brdf = albedo * INV_PI;

    if (restir_applies(record, bounce, use_nee, surface.material)) {
      restir_direct(state, record, surface.position, origin, ng, ns, brdf, rng, result);
    } else if (sample_lights) {
      let light = sample_light(origin, rng_next_2d(rng), rng_next_2d(rng));
      let cos_surface = dot(ns, light.direction);
      if (light.pdf > 0.0 && (use_nee || light.delta) && cos_surface > 0.0 && dot(ng, light.direction) > 0.0) {
        let weight = select(power_heuristic(light.pdf, cosine_hemisphere_pdf(cos_surface)), 1.0, light.delta);
        path_shadow(state, record, SHADOW_LIGHT, Ray(origin, 0.0, light.direction, light.distance * (1.0 - SHADOW_RAY_SHORTEN)),
          (*state).throughput * lift(brdf) * lift(light.radiance) * (cos_surface * weight / light.pdf), result);
      }
    }

    // The torch: next-event estimation only, so no MIS weight (BSDF rays never hit it).
    let torch = sample_torch(settings.torch, settings.torch_position, origin, rng_next_2d(rng));
    if (torch.pdf > 0.0) {
      let cos_surface = dot(ns, torch.direction);
      if (cos_surface > 0.0 && dot(ng, torch.direction) > 0.0) {
        path_shadow(state, record, SHADOW_TORCH, Ray(origin, 0.0, torch.direction, torch.distance * (1.0 - SHADOW_RAY_SHORTEN)),
          (*state).throughput * lift(brdf) * lift(torch.radiance) * (cos_surface / torch.pdf), result);
      }
    }

    // BSDF sampling: cosine-weighted, so brdf·cos/pdf is the albedo.
    let wi = orthonormal_basis(ns) * sample_cosine_hemisphere(rng_next_2d(rng));
    if (dot(wi, ng) <= 0.0) {
      return false;
    }
    (*state).last_bsdf_pdf = cosine_hemisphere_pdf(dot(wi, ns));
    (*state).throughput *= lift(albedo);
    (*state).ray = Ray(origin, 0.0, wi, T_MISS);
  } else if ((material.flags & MATERIAL_SCATTER_IN_PLANE) != 0u) {
    // In-plane scattering (the prism's screen): f = albedo/2 per radian on the half circle of the
    // plane ⟂ p facing the ray, sampled ∝ cos φ (pdf cos φ / 2), so the weight is the albedo. A delta
    // across the plane: no light sampling, and emitters it finds count in full.
    let facing = select(1.0, -1.0, dot(surface.geometric_normal, ray.direction) > 0.0);
    let ng = facing * surface.geometric_normal;
    let p = material.scatter_plane_normal;
    let n_in = normalize(ng - dot(ng, p) * p);
    let phi = asin(2.0 * rng_next_f32(rng) - 1.0);
    let wi = cos(phi) * n_in + sin(phi) * cross(p, n_in);
    (*state).throughput *= lift(material_albedo(material, surface.uv).rgb);
    (*state).after_delta = true;
    (*state).ray = Ray(spawn_point(surface, ng), 0.0, wi, T_MISS);
  } else {
    var bsdf = material_bsdf(material, surface.uv);
    if (SPECTRAL && material_is_dispersive(material)) {
      // The interface bends each wavelength its own way: trace the hero's (before light sampling,
      // which evaluates the BSDF too).
      bsdf.ior = material_ior_at(material, path_wavelengths.lambda.x);
      (*state).throughput = spectrum_terminate_secondary((*state).throughput);
    }
    let front = dot(surface.geometric_normal, ray.direction) < 0.0;
    var ng = surface.geometric_normal;
    var ns = normal_mapped(surface, hit, material);
    // Opaque reflectors are two-sided: their frame turns toward the ray. Interfaces keep their
    // front (outside) side, and the BSDF sees wo.z < 0 from inside.
    if (!front && material_is_two_sided_reflector(material, bsdf)) {
      ng = -ng;
      ns = -ns;
    }
    let frame = orthonormal_basis(ns);
    let wo_world = -ray.direction;
    let wo = vec3f(dot(wo_world, frame[0]), dot(wo_world, frame[1]), dot(wo_world, frame[2]));

    if (bsdf_has_non_delta(bsdf)) {
      if (bsdf.kind == BSDF_DIFFUSE && restir_applies(record, bounce, use_nee, surface.material)) {
        restir_direct(state, record, surface.position, spawn_point(surface, ng), ng, ns, bsdf.base_color * INV_PI, rng, result);
      } else if (sample_lights) {
        let light = sample_light(surface.position, rng_next_2d(rng), rng_next_2d(rng));
        if (light.pdf > 0.0 && (use_nee || light.delta)) {
          let wi_world = light.direction;
          let wi = vec3f(dot(wi_world, frame[0]), dot(wi_world, frame[1]), dot(wi_world, frame[2]));
          let side_g = dot(ng, wi_world);
          // The shading and geometric normals must agree on the side of the light (no leaks).
          if (side_g * wi.z > 0.0) {
            let f = bsdf_eval(bsdf, wo, wi);
            if (any(f > vec3f(0.0))) {
              let origin = spawn_point(surface, select(-ng, ng, side_g > 0.0));
              let weight = select(power_heuristic(light.pdf, bsdf_pdf(bsdf, wo, wi)), 1.0, light.delta);
              path_shadow(state, record, SHADOW_LIGHT, Ray(origin, 0.0, wi_world, light.distance * (1.0 - SHADOW_RAY_SHORTEN)),
                (*state).throughput * lift(f) * lift(light.radiance) * (abs(wi.z) * weight / light.pdf), result);
            }
          }
        }
      }
      let torch = sample_torch(settings.torch, settings.torch_position, surface.position, rng_next_2d(rng));
      if (torch.pdf > 0.0) {
        let wi = vec3f(dot(torch.direction, frame[0]), dot(torch.direction, frame[1]), dot(torch.direction, frame[2]));
        let side_g = dot(ng, torch.direction);
        if (side_g * wi.z > 0.0) {
          let f = bsdf_eval(bsdf, wo, wi);
          if (any(f > vec3f(0.0))) {
            let origin = spawn_point(surface, select(-ng, ng, side_g > 0.0));
            path_shadow(state, record, SHADOW_TORCH, Ray(origin, 0.0, torch.direction, torch.distance * (1.0 - SHADOW_RAY_SHORTEN)),
              (*state).throughput * lift(f) * lift(torch.radiance) * (abs(wi.z) / torch.pdf), result);
          }
        }
      }
    }

    let u3 = vec3f(rng_next_2d(rng), rng_next_f32(rng));
    let s = bsdf_sample(bsdf, wo, u3);
    if (!s.valid) {
      return false;
    }
    let wi_world = frame * s.wi;
    let side_g = dot(ng, wi_world);
    if (side_g * s.wi.z <= 0.0) {
      return false;
    }
    (*state).throughput *= lift(s.weight);
    (*state).last_bsdf_pdf = s.pdf;
    (*state).after_delta = s.delta;
    if (!s.delta) {
      let alpha = bsdf.roughness * bsdf.roughness;
      (*state).cone_spread += select(2.0 * alpha, DIFFUSE_CONE_SPREAD, bsdf.kind == BSDF_DIFFUSE);
    }
    if (s.transmitted && (bsdf.thin_walled == 0u)) {
      // Crossing the interface: entering from the front puts the ray inside the volume.
      (*state).absorption = select(vec4f(0.0), lift(material.absorption), side_g < 0.0 && front);
    }
    (*state).ray = Ray(spawn_point(surface, select(-ng, ng, side_g > 0.0)), 0.0, wi_world, T_MISS);
  }

  if (bounce + 1u >= ROULETTE_START_BOUNCE) {
    let survive = min(channels_max((*state).throughput), 0.95);
    if (rng_next_f32(rng) >= survive) {
      return false;
    }
    (*state).throughput /= survive;
  }
  return true;
}

// Follows a camera path to its end; `record` (path_record: not collecting) hands in the pixel's
// reservoir and hands back the first hit.
fn trace_path(first_ray: Ray, rng: ptr<function, Rng>, settings: PathSettings, record: ptr<function, PathRecord>) -> PathResult {
  var result = PathResult(vec3f(0.0), 0u, 0u);
  var state = path_begin(first_ray, rng, settings);
  for (var bounce = 0u; bounce <= settings.max_bounces; bounce++) {
    let hit = trace_closest(state.ray);
    result.extension_rays += 1u;
    if (!path_step(&state, record, hit, bounce, rng, settings, &result)) {
      break;
    }
  }
  result.radiance = channels_to_rgb(state.radiance);
  return result;
}
