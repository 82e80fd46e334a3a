// The dispatch parameters every path tracer reads (the progressive kernel, the real-time frame's,
// the wavefront's, the hybrid's traced passes, ReSTIR's, and the fragment tracer): tile, sample
// index, bounces, seed, light sampling, sampler, torch (passes/path-trace-pass.ts writes them from
// renderer/frame.ts pathDispatch), and the integrator's settings made from them. Group 2, binding 0.
// No storage buffers: the fragment tracer (passes/path-trace-fragment) imports this module, not
// integrator/dispatch. Expects the view (group 1).

#import lib/constants
#import lib/random
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

@group(2) @binding(0) var<uniform> params: PathTraceParams;

// Settings inlined into a kernel specialised to a frozen scene (gpu/specialisation.ts): the value the
// params uniform holds, fixed while the kernel is in use (any change drops back to the generic kernel),
// so loops and branches on it are known to the compiler. INLINED_FROM_PARAMS: read the uniform.
const INLINED_FROM_PARAMS: i32 = -1;
override INLINED_MAX_BOUNCES: i32 = INLINED_FROM_PARAMS;
override INLINED_LIGHT_SAMPLING: i32 = INLINED_FROM_PARAMS;

// The pixel that invocation `id` of a tile dispatch shades, and whether it shades one (inside both the
// tile and the image).
fn tile_pixel(id: vec3u) -> vec2u {
  return params.tile_origin + id.xy;
}

fn shades_tile_pixel(id: vec3u) -> bool {
  return all(id.xy < params.tile_size) && all(tile_pixel(id) < view.image_size);
}

// The integrator's settings for this dispatch.
fn path_settings() -> PathSettings {
  let max_bounces = select(params.max_bounces, u32(INLINED_MAX_BOUNCES), INLINED_MAX_BOUNCES != INLINED_FROM_PARAMS);
  let light_sampling = select(params.light_sampling, u32(INLINED_LIGHT_SAMPLING), INLINED_LIGHT_SAMPLING != INLINED_FROM_PARAMS);
  return PathSettings(max_bounces, light_sampling, params.torch, view.camera.position, 2.0 * length(view.camera.up) / f32(view.image_size.y));
}
