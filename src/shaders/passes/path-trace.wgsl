// The path tracer: one invocation per pixel of the current tile, `samples` paths per invocation,
// added to the float32 accumulation buffer. Diffuse (textured) surfaces; next-event estimation on
// emissive triangles combined with BSDF sampling by multiple importance sampling (power heuristic),
// plus next-event estimation of the torch at the camera; Russian roulette from the fourth bounce on. Expects the scene (group 0) and view (group 1); its own inputs
// and outputs are group 2. Follows Veach 1997, ch. 9, and pbrt-v4's PathIntegrator (§13.4).

#import lib/constants
#import lib/random
#import lib/sampling
#import lib/color
#import scene/bvh
#import scene/surface
#import lib/ray-offset
#import scene/lights
#import scene/materials
#import scene/torch
#import view/bindings

// The closed set of light-sampling strategies; the host's names live in renderer/settings.ts.
const LIGHT_SAMPLING_BSDF: u32 = 0u;
const LIGHT_SAMPLING_MIS: u32 = 1u;

// Russian roulette starts once a path has this many bounces.
const ROULETTE_START_BOUNCE: u32 = 3u;
// Shadow rays stop this fraction short of the light so they do not hit the light itself.
const SHADOW_RAY_SHORTEN: f32 = 1e-4;

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

struct PathTraceParams {
  // Pixels.
  tile_origin: vec2u,
  tile_size: vec2u,
  // Index of the first sample of this dispatch within the accumulation: seeds the random streams.
  sample_index: u32,
  // Paths per pixel in this dispatch.
  samples: u32,
  // Scattering events per path: 0 shows emitters only, 1 adds direct light.
  max_bounces: u32,
  seed: u32,
  light_sampling: u32,
  // The torch at the camera position (radiance zero: off).
  torch: TorchLight,
}

// 64-bit ray counters as (low, high) word pairs: a 4K image at a few thousand samples overflows 32 bits.
const COUNTER_EXTENSION_RAYS: u32 = 0u;
const COUNTER_SHADOW_RAYS: u32 = 2u;

@group(2) @binding(0) var<uniform> params: PathTraceParams;
// Per pixel: rgb = Σ radiance samples, a = Σ luminance² (for the per-pixel variance).
@group(2) @binding(1) var<storage, read_write> accumulation: array<vec4f>;
// Words: extension rays (low, high), shadow rays (low, high).
@group(2) @binding(2) var<storage, read_write> ray_counters: array<atomic<u32>, 4>;

var<workgroup> workgroup_extension_rays: atomic<u32>;
var<workgroup> workgroup_shadow_rays: atomic<u32>;

struct PathResult {
  radiance: vec3f,
  extension_rays: u32,
  shadow_rays: u32,
}

fn trace_path(first_ray: Ray, rng: ptr<function, Rng>) -> PathResult {
  var result = PathResult(vec3f(0.0), 0u, 0u);
  var ray = first_ray;
  var throughput = vec3f(1.0);
  // Solid-angle density of the BSDF sample that produced `ray` (unused for the camera ray).
  var bsdf_pdf = 0.0;
  let use_nee = params.light_sampling == LIGHT_SAMPLING_MIS && scene_info.light_count > 0u;

  for (var bounce = 0u; bounce <= params.max_bounces; bounce++) {
    let hit = trace_closest(ray);
    result.extension_rays += 1u;
    if (hit.triangle == NO_TRIANGLE) {
      break;
    }
    let surface = surface_at(hit);
    let material = materials[surface.material];

    // Emission, seen only from the side the geometric normal faces.
    let cos_emitter = -dot(surface.geometric_normal, ray.direction);
    if (cos_emitter > 0.0 && any(material.emission > vec3f(0.0))) {
      var weight = 1.0;
      if (bounce > 0u && use_nee) {
        let light_pdf = light_selection_pmf(material, surface.area) / surface.area * hit.t * hit.t / cos_emitter;
        weight = power_heuristic(bsdf_pdf, light_pdf);
      }
      result.radiance += throughput * material_emission(material, surface.uv, ray.direction) * weight;
    }
    if (CAPTURE_PRIMARY && bounce == 0u) {
      primary = PrimaryHit(material_albedo(material, surface.uv).rgb, result.radiance);
    }
    if (bounce == params.max_bounces) {
      break;
    }

    // Diffuse reflection happens on both sides: turn both normals toward the incoming ray.
    let facing = select(1.0, -1.0, dot(surface.geometric_normal, ray.direction) > 0.0);
    let ng = facing * surface.geometric_normal;
    let ns = facing * surface.shading_normal;
    let origin = offset_ray_origin(surface.position, ng);
    let albedo = material_albedo(material, surface.uv).rgb;
    let brdf = albedo * INV_PI;

    // Next-event estimation: one point on one emissive triangle.
    if (use_nee) {
      let u_slot = rng_next_f32(rng);
      let u_keep = rng_next_f32(rng);
      let light = sample_light(u_slot, u_keep, rng_next_2d(rng));
      let to_light = light.position - origin;
      let distance2 = dot(to_light, to_light);
      let distance = sqrt(distance2);
      let wi = to_light / distance;
      let cos_light = -dot(light.normal, wi);
      let cos_surface = dot(ns, wi);
      if (cos_light > 0.0 && cos_surface > 0.0 && dot(ng, wi) > 0.0) {
        result.shadow_rays += 1u;
        let shadow = Ray(origin, 0.0, wi, distance * (1.0 - SHADOW_RAY_SHORTEN));
        if (!trace_any(shadow)) {
          let light_material = materials[triangles_shading[light.triangle].material];
          let emission = material_emission(light_material, triangle_uv(light.triangle, light.bary), wi);
          let light_pdf = light.pdf_area * distance2 / cos_light;
          let weight = power_heuristic(light_pdf, cosine_hemisphere_pdf(cos_surface));
          result.radiance += throughput * brdf * emission * (cos_surface * weight / light_pdf);
        }
      }
    }

    // The torch: next-event estimation only, so no MIS weight (BSDF rays never hit it).
    let torch = sample_torch(params.torch, view.camera.position, origin, rng_next_2d(rng));
    if (torch.pdf > 0.0) {
      let cos_surface = dot(ns, torch.direction);
      if (cos_surface > 0.0 && dot(ng, torch.direction) > 0.0) {
        result.shadow_rays += 1u;
        if (!trace_any(Ray(origin, 0.0, torch.direction, torch.distance * (1.0 - SHADOW_RAY_SHORTEN)))) {
          result.radiance += throughput * brdf * torch.radiance * (cos_surface / torch.pdf);
        }
      }
    }

    // BSDF sampling: cosine-weighted, so brdf·cos/pdf is the albedo.
    let wi = orthonormal_basis(ns) * sample_cosine_hemisphere(rng_next_2d(rng));
    if (dot(wi, ng) <= 0.0) {
      break;
    }
    bsdf_pdf = cosine_hemisphere_pdf(dot(wi, ns));
    throughput *= albedo;

    if (bounce + 1u >= ROULETTE_START_BOUNCE) {
      let survive = min(max(throughput.x, max(throughput.y, throughput.z)), 0.95);
      if (rng_next_f32(rng) >= survive) {
        break;
      }
      throughput /= survive;
    }
    ray = Ray(origin, 0.0, wi, T_MISS);
  }
  return result;
}

// Adds n to the counter whose low word is ray_counters[low]; n < 2³², so at most one carry.
fn add_to_counter(low: u32, n: u32) {
  let before = atomicAdd(&ray_counters[low], n);
  if (before + n < before) {
    atomicAdd(&ray_counters[low + 1u], 1u);
  }
}

// Ray counting per workgroup (one global atomic per workgroup and counter): every invocation calls
// begin first and end last, in uniform control flow; count in between.
fn begin_ray_count(local: u32) {
  if (local == 0u) {
    atomicStore(&workgroup_extension_rays, 0u);
    atomicStore(&workgroup_shadow_rays, 0u);
  }
  workgroupBarrier();
}

fn count_rays(extension_rays: u32, shadow_rays: u32) {
  atomicAdd(&workgroup_extension_rays, extension_rays);
  atomicAdd(&workgroup_shadow_rays, shadow_rays);
}

fn end_ray_count(local: u32) {
  workgroupBarrier();
  if (local == 0u) {
    add_to_counter(COUNTER_EXTENSION_RAYS, atomicLoad(&workgroup_extension_rays));
    add_to_counter(COUNTER_SHADOW_RAYS, atomicLoad(&workgroup_shadow_rays));
  }
}

@compute @workgroup_size(8, 8)
fn path_trace(@builtin(global_invocation_id) id: vec3u, @builtin(local_invocation_index) local: u32) {
  begin_ray_count(local);

  let pixel = params.tile_origin + id.xy;
  if (all(id.xy < params.tile_size) && all(pixel < view.image_size)) {
    let pixel_index = pixel.y * view.image_size.x + pixel.x;
    var rng = rng_seed(pixel_index, params.sample_index, params.seed);
    var sum = vec4f(0.0);
    var extension_rays = 0u;
    var shadow_rays = 0u;
    for (var s = 0u; s < params.samples; s++) {
      let jitter = rng_next_2d(&rng);
      let path = trace_path(camera_ray(vec2f(pixel) + jitter), &rng);
      // A non-finite sample (a numerical accident) is dropped rather than poisoning the pixel forever.
      let radiance = select(vec3f(0.0), path.radiance, is_finite_vec3(path.radiance));
      let l = luminance(radiance);
      sum += vec4f(radiance, l * l);
      extension_rays += path.extension_rays;
      shadow_rays += path.shadow_rays;
    }
    accumulation[pixel_index] += sum;
    count_rays(extension_rays, shadow_rays);
  }
  end_ray_count(local);
}
