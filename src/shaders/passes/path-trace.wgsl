// The progressive path tracer: one invocation per pixel of the current tile, `samples` paths per
// invocation (integrator/path's trace_path), added to the float32 accumulation buffer, with exact
// ray counts. Expects the scene (group 0) and view (group 1); its own inputs and outputs are group 2.
// passes/path-trace-frame imports this module for its parameters and ray counters.

#import lib/constants
#import lib/random
#import lib/color
#import integrator/path
#import view/bindings

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
  // The random numbers' sampler: SAMPLER_* of lib/random (a kernel compiled for one, lib/random's
  // SAMPLER, uses that one).
  sampler: u32,
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

// Settings inlined into a kernel specialised to a frozen scene (gpu/specialisation.ts): the value the
// params uniform holds, fixed while the kernel is in use (any change drops back to the generic kernel),
// so loops and branches on it are known to the compiler. INLINED_FROM_PARAMS: read the uniform.
const INLINED_FROM_PARAMS: i32 = -1;
override INLINED_MAX_BOUNCES: i32 = INLINED_FROM_PARAMS;
override INLINED_LIGHT_SAMPLING: i32 = INLINED_FROM_PARAMS;

// The integrator's settings for this dispatch.
fn path_settings() -> PathSettings {
  let max_bounces = select(params.max_bounces, u32(INLINED_MAX_BOUNCES), INLINED_MAX_BOUNCES != INLINED_FROM_PARAMS);
  let light_sampling = select(params.light_sampling, u32(INLINED_LIGHT_SAMPLING), INLINED_LIGHT_SAMPLING != INLINED_FROM_PARAMS);
  return PathSettings(max_bounces, light_sampling, params.torch, view.camera.position, 2.0 * length(view.camera.up) / f32(view.image_size.y));
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
    var sum = vec4f(0.0);
    var extension_rays = 0u;
    var shadow_rays = 0u;
    let pixel_stream = sampler_pixel(params.sampler, pixel, view.image_size, params.seed);
    for (var s = 0u; s < params.samples; s++) {
      // One stream per sample (not per dispatch), so that an image depends on the seed alone and not on
      // how the dispatch planner batched its samples into submits.
      var rng = sampler_next_sample(pixel_stream, pixel, view.image_size, params.sample_index + s, params.seed);
      let jitter = rng_next_2d(&rng);
      let path = trace_path(camera_sample_ray(vec2f(pixel) + jitter, &rng), &rng, path_settings());
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
