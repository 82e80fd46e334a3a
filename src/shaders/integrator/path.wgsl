// The path integrator as a library: trace_path follows one camera path, adding emission met along the
// way, next-event estimation on every light (scene/lights.wgsl) and on the torch, combined with
// BSDF sampling (scene/bsdf.wgsl) by multiple importance sampling (power heuristic), with Russian
// roulette from the fourth bounce on and Beer–Lambert absorption inside glass. A path's radiance and
// throughput are four channels: RGB (and a spare 0) in RGB mode, four wavelengths in spectral mode
// (lib/spectrum: hero wavelength + three companions; RGB values are lifted where they enter, and a
// dispersive interface keeps only the hero). The entry points
// (passes/path-trace, passes/path-trace-frame) call it; a new material kind is a case of the BSDF
// module, not a change here. Follows Veach 1997, ch. 9, and pbrt-v4's PathIntegrator (§13.4).
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

// The closed set of light-sampling strategies; the host's names live in renderer/settings.ts.
const LIGHT_SAMPLING_BSDF: u32 = 0u;
const LIGHT_SAMPLING_MIS: u32 = 1u;

// Russian roulette starts once a path has this many bounces.
const ROULETTE_START_BOUNCE: u32 = 3u;
// Shadow rays stop this fraction short of the light so they do not hit the light itself.
const SHADOW_RAY_SHORTEN: f32 = 1e-4;

// Whether any material is not diffuse (or has a normal map or absorbs). A pipeline constant: scenes
// of diffuse surfaces only (the Cornell box, Doom) compile the Lambertian path alone, as fast as
// before the BSDF module existed; the general path calls bsdf_* for every kind.
override SCENE_HAS_GENERAL_MATERIALS: bool = true;

// Set only by the real-time frame kernel (passes/path-trace-frame): trace_path then records its first
// hit's albedo and emission in `primary`, for demodulation. path_trace leaves it false, so the
// branch is constant-folded away and the progressive kernel is unchanged.
override CAPTURE_PRIMARY: bool = false;

// What a camera ray's first hit contributes, for demodulation: the albedo there (1 for a miss) and the
// emission seen there (radiance that needs no filtering).
struct PrimaryHit {
  albedo: vec3f,
  emission: vec3f,
}
var<private> primary: PrimaryHit;

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

// MIS weight of radiance found by a BSDF-sampled ray whose light-sampling density is light_pdf.
fn bsdf_hit_weight(bounce: u32, use_nee: bool, after_delta: bool, bsdf_pdf: f32, light_pdf: f32) -> f32 {
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

fn trace_path(first_ray: Ray, rng: ptr<function, Rng>, settings: PathSettings) -> PathResult {
  var result = PathResult(vec3f(0.0), 0u, 0u);
  if (SPECTRAL) {
    spectrum_begin_path(rng_next_f32(rng));
  }
  // Radiance gathered so far, in the path's channels (channels_to_rgb turns it into RGB).
  var radiance = vec4f(0.0);
  var ray = first_ray;
  var throughput = lift(vec3f(1.0));
  // Solid-angle density of the BSDF sample that produced `ray` (unused for the camera ray), and
  // whether it came from a delta lobe (then no light sample could have found what it hits).
  var last_bsdf_pdf = 0.0;
  var after_delta = false;
  // Absorption coefficient of the medium the ray travels in (inside glass with a volume).
  var absorption = vec4f(0.0);
  // The ray cone (texture level of detail): width at the ray's origin and spread angle.
  var cone_width = 0.0;
  var cone_spread = settings.pixel_spread;
  let use_nee = settings.light_sampling == LIGHT_SAMPLING_MIS && scene_light_count() > 0u;
  // Punctual lights are not geometry: no BSDF ray finds them, so even BSDF-only sampling samples
  // them. It draws from the whole light table and keeps only punctual picks (dividing by their
  // selection probability keeps it unbiased); other lights are left to BSDF rays, weighted 1.
  let sample_lights = use_nee || (SCENE_HAS_PUNCTUAL_LIGHTS && scene_light_count() > 0u);

  for (var bounce = 0u; bounce <= settings.max_bounces; bounce++) {
    let hit = trace_closest(ray);
    result.extension_rays += 1u;
    if (SCENE_HAS_GENERAL_MATERIALS && any(absorption > vec4f(0.0))) {
      throughput *= exp(-absorption * min(hit.t, 1e30));
    }
    if (hit.triangle == NO_TRIANGLE) {
      if (SCENE_HAS_ENVIRONMENT) {
        var seen = environment_radiance(ray.direction) + sun_radiance(ray.direction);
        let weight = bsdf_hit_weight(bounce, use_nee, after_delta, last_bsdf_pdf, environment_light_pdf(ray.direction));
        radiance += throughput * lift(seen) * weight;
        if (CAPTURE_PRIMARY && bounce == 0u) {
          primary = PrimaryHit(vec3f(1.0), channels_to_rgb(radiance));
        }
      }
      break;
    }
    let surface = surface_at(hit, ray);
    let material = materials[surface.material];
    if (SCENE_HAS_GENERAL_MATERIALS) {
      cone_width += cone_spread * hit.t;
      texture_lod = texture_lod_at(surface, hit.triangle, cone_width, ray.direction);
      if (textureDimensions(triangle_attributes).x > 1u) {
        surface_uv1 = triangle_uv1(hit.triangle, stored_bary(hit));
      }
    }

    // Emission, seen only from the side the geometric normal faces (both, for two-sided emitters).
    let cos_emitter = emitter_cosine(material, -dot(surface.geometric_normal, ray.direction));
    if (cos_emitter > 0.0 && any(material.emission > vec3f(0.0))) {
      let weight = bsdf_hit_weight(bounce, use_nee, after_delta, last_bsdf_pdf, emitter_pdf(surface, material, ray.origin, hit.t, cos_emitter));
      radiance += throughput * lift(material_emission(material, surface.uv, ray.direction)) * weight;
    }
    if (CAPTURE_PRIMARY && bounce == 0u) {
      primary = PrimaryHit(material_albedo(material, surface.uv).rgb, channels_to_rgb(radiance));
    }
    if (bounce == settings.max_bounces || material.kind == MATERIAL_KIND_EMISSIVE) {
      break;
    }

    if (!SCENE_HAS_GENERAL_MATERIALS) {
      // Diffuse surfaces only: reflection on both sides, so turn both normals toward the ray.
      let facing = select(1.0, -1.0, dot(surface.geometric_normal, ray.direction) > 0.0);
      let ng = facing * surface.geometric_normal;
      let ns = facing * surface.shading_normal;
      let origin = spawn_point(surface, ng);
      let albedo = material_albedo(material, surface.uv).rgb;
      let brdf = albedo * INV_PI;

      if (sample_lights) {
        let light = sample_light(origin, rng_next_2d(rng), rng_next_2d(rng));
        let cos_surface = dot(ns, light.direction);
        if (light.pdf > 0.0 && (use_nee || light.delta) && cos_surface > 0.0 && dot(ng, light.direction) > 0.0) {
          result.shadow_rays += 1u;
          if (!trace_any(Ray(origin, 0.0, light.direction, light.distance * (1.0 - SHADOW_RAY_SHORTEN)))) {
            let weight = select(power_heuristic(light.pdf, cosine_hemisphere_pdf(cos_surface)), 1.0, light.delta);
            radiance += throughput * lift(brdf) * lift(light.radiance) * (cos_surface * weight / light.pdf);
          }
        }
      }

      // The torch: next-event estimation only, so no MIS weight (BSDF rays never hit it).
      let torch = sample_torch(settings.torch, settings.torch_position, origin, rng_next_2d(rng));
      if (torch.pdf > 0.0) {
        let cos_surface = dot(ns, torch.direction);
        if (cos_surface > 0.0 && dot(ng, torch.direction) > 0.0) {
          result.shadow_rays += 1u;
          if (!trace_any(Ray(origin, 0.0, torch.direction, torch.distance * (1.0 - SHADOW_RAY_SHORTEN)))) {
            radiance += throughput * lift(brdf) * lift(torch.radiance) * (cos_surface / torch.pdf);
          }
        }
      }

      // BSDF sampling: cosine-weighted, so brdf·cos/pdf is the albedo.
      let wi = orthonormal_basis(ns) * sample_cosine_hemisphere(rng_next_2d(rng));
      if (dot(wi, ng) <= 0.0) {
        break;
      }
      last_bsdf_pdf = cosine_hemisphere_pdf(dot(wi, ns));
      throughput *= lift(albedo);
      ray = Ray(origin, 0.0, wi, T_MISS);
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
      throughput *= lift(material_albedo(material, surface.uv).rgb);
      after_delta = true;
      ray = Ray(spawn_point(surface, ng), 0.0, wi, T_MISS);
    } else {
      var bsdf = material_bsdf(material, surface.uv);
      if (SPECTRAL && material_is_dispersive(material)) {
        // The interface bends each wavelength its own way: trace the hero's (before light sampling,
        // which evaluates the BSDF too).
        bsdf.ior = material_ior_at(material, path_wavelengths.lambda.x);
        throughput = spectrum_terminate_secondary(throughput);
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
        if (sample_lights) {
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
                result.shadow_rays += 1u;
                if (!trace_any(Ray(origin, 0.0, wi_world, light.distance * (1.0 - SHADOW_RAY_SHORTEN)))) {
                  let weight = select(power_heuristic(light.pdf, bsdf_pdf(bsdf, wo, wi)), 1.0, light.delta);
                  radiance += throughput * lift(f) * lift(light.radiance) * (abs(wi.z) * weight / light.pdf);
                }
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
              result.shadow_rays += 1u;
              if (!trace_any(Ray(origin, 0.0, torch.direction, torch.distance * (1.0 - SHADOW_RAY_SHORTEN)))) {
                radiance += throughput * lift(f) * lift(torch.radiance) * (abs(wi.z) / torch.pdf);
              }
            }
          }
        }
      }

      let u3 = vec3f(rng_next_2d(rng), rng_next_f32(rng));
      let s = bsdf_sample(bsdf, wo, u3);
      if (!s.valid) {
        break;
      }
      let wi_world = frame * s.wi;
      let side_g = dot(ng, wi_world);
      if (side_g * s.wi.z <= 0.0) {
        break;
      }
      throughput *= lift(s.weight);
      last_bsdf_pdf = s.pdf;
      after_delta = s.delta;
      if (!s.delta) {
        let alpha = bsdf.roughness * bsdf.roughness;
        cone_spread += select(2.0 * alpha, DIFFUSE_CONE_SPREAD, bsdf.kind == BSDF_DIFFUSE);
      }
      if (s.transmitted && (bsdf.thin_walled == 0u)) {
        // Crossing the interface: entering from the front puts the ray inside the volume.
        absorption = select(vec4f(0.0), lift(material.absorption), side_g < 0.0 && front);
      }
      ray = Ray(spawn_point(surface, select(-ng, ng, side_g > 0.0)), 0.0, wi_world, T_MISS);
    }

    if (bounce + 1u >= ROULETTE_START_BOUNCE) {
      let survive = min(channels_max(throughput), 0.95);
      if (rng_next_f32(rng) >= survive) {
        break;
      }
      throughput /= survive;
    }
  }
  result.radiance = channels_to_rgb(radiance);
  return result;
}
