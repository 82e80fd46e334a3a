// The progressive path tracer as a fragment shader (issue #30): one fragment a pixel of a fullscreen
// triangle, `params.samples` paths of integrator/path's trace_path per fragment with the compute
// kernel's (passes/path-trace) sampler streams, added to the previous accumulation, which is read from
// a texture and written to the other of a ping-ponged pair of rgba32float targets. For WebGL2 (no
// compute, no storage buffers, no atomics), translated to GLSL ES 3.00 by naga, and for WebGPU, where
// tests hold it to the compute kernel. Linked with scene/bindings-textures in place of scene/bindings
// and every override frozen (renderer/fragment-tracer-wgsl.ts fragmentTracerWgsl): that exact WGSL
// is what both back ends compile. No ray counters (integrator/dispatch's are atomics). Expects the
// scene (group 0) and view (group 1); its own inputs are group 2: params (binding 0, the compute
// kernel's PathTraceParams: tile_origin and tile_size are ignored, the image is the target) and the
// previous accumulation (binding 1).

#import lib/constants
#import lib/random
#import lib/color
#import integrator/path
#import integrator/dispatch-params
#import view/bindings

// Per pixel: rgb = Σ radiance samples, a = Σ luminance², as passes/path-trace's accumulation (the
// host divides by the sample count; the luminance sum of squares gives the per-pixel variance).
@group(2) @binding(1) var previous_accumulation: texture_2d<f32>;

// One triangle covering the viewport: vertices (-1, -1), (3, -1), (-1, 3).
@vertex
fn vs_fullscreen(@builtin(vertex_index) vertex: u32) -> @builtin(position) vec4f {
  let p = vec2f(f32((vertex << 1u) & 2u), f32(vertex & 2u));
  return vec4f(p * 2.0 - 1.0, 0.0, 1.0);
}

// Framebuffer coordinates have (0, 0) at the top-left pixel's corner, as the compute kernel's pixel
// (x, y) with y down: the fragment at pixel centre (x + 0.5, y + 0.5) traces pixel (x, y).
@fragment
fn fs_path_trace(@builtin(position) position: vec4f) -> @location(0) vec4f {
  let pixel = vec2u(position.xy);
  var sum = vec4f(0.0);
  let pixel_stream = sampler_pixel(params.sampler, pixel, view.image_size, params.seed);
  for (var s = 0u; s < params.samples; s++) {
    var rng = sampler_next_sample(pixel_stream, pixel, view.image_size, params.sample_index + s, params.seed);
    let jitter = rng_next_2d(&rng);
    var record = path_record(NO_RESTIR_PIXEL);
    let path = trace_path(camera_sample_ray(vec2f(pixel) + jitter, &rng), &rng, path_settings(), &record);
    // A non-finite sample is dropped, as the compute kernel drops it.
    let radiance = select(vec3f(0.0), path.radiance, is_finite_vec3(path.radiance));
    let l = luminance(radiance);
    sum += vec4f(radiance, l * l);
  }
  // Added as the compute kernel adds its samples' sum to the accumulation (the same rounding).
  return textureLoad(previous_accumulation, vec2i(pixel), 0) + sum;
}
