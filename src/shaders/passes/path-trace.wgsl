// The progressive path tracer: one invocation per pixel of the current tile, `samples` paths per
// invocation (integrator/path's trace_path), added to the float32 accumulation buffer, with exact
// ray counts (integrator/dispatch). Expects the scene (group 0) and view (group 1); its own inputs
// and outputs are group 2.

#import lib/workgroup
#import lib/constants
#import lib/random
#import lib/color
#import integrator/path
#import integrator/dispatch
#import view/bindings

// Per pixel: rgb = Σ radiance samples, a = Σ luminance² (for the per-pixel variance).
@group(2) @binding(1) var<storage, read_write> accumulation: array<vec4f>;

@compute @workgroup_size(PIXEL_TILE_X, PIXEL_TILE_Y)
fn path_trace(@builtin(global_invocation_id) id: vec3u, @builtin(local_invocation_index) local: u32) {
  begin_ray_count(local);

  let pixel = tile_pixel(id);
  if (shades_tile_pixel(id)) {
    let pixel_index = image_index(pixel);
    var sum = vec4f(0.0);
    var extension_rays = 0u;
    var shadow_rays = 0u;
    let pixel_stream = sampler_pixel(params.sampler, pixel, view.image_size, params.seed);
    for (var s = 0u; s < params.samples; s++) {
      // One stream per sample (not per dispatch), so that an image depends on the seed alone and not on
      // how the dispatch planner batched its samples into submits.
      var rng = sampler_next_sample(pixel_stream, pixel, view.image_size, params.sample_index + s, params.seed);
      let jitter = rng_next_2d(&rng);
      var record = path_record(NO_RESTIR_PIXEL);
      let path = trace_path(camera_sample_ray(vec2f(pixel) + jitter, &rng), &rng, path_settings(), &record);
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
