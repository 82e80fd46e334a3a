// Tone mapping as a fragment pass, for the WebGL2 backend (src/webgl2/, no compute there): one
// fragment per image pixel reads the accumulated sum from a float texture, takes the mean, applies
// the exposure and the tone curve of lib/color, encodes sRGB and writes an 8-bit target of the
// image's size, which present draws to the canvas. The arithmetic is passes/tonemap's (manual
// exposure only: the adapted exposure is a compute reduction). Expects nothing; its own group 0.

#import lib/color

struct TonemapFragmentParams {
  // 2^exposure_stops.
  exposure_scale: f32,
  // One of the TONEMAP_* constants of lib/color.
  tone_mapper: u32,
  // 1 / samples accumulated per pixel (0 before the first sample: a black image).
  inv_sample_count: f32,
}

@group(0) @binding(0) var<uniform> params: TonemapFragmentParams;
// Per-pixel sums of radiance (rgb) as the fragment path tracer accumulates them; row 0 is the top row.
@group(0) @binding(1) var accumulation: texture_2d<f32>;

// A triangle covering clip space, (-1,-1), (3,-1), (-1,3): every pixel of the target once.
@vertex
fn vs_tonemap(@builtin(vertex_index) index: u32) -> @builtin(position) vec4f {
  let xy = vec2f(f32((index << 1u) & 2u), f32(index & 2u));
  return vec4f(xy * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn fs_tonemap(@builtin(position) position: vec4f) -> @location(0) vec4f {
  let radiance = textureLoad(accumulation, vec2i(position.xy), 0).rgb * params.inv_sample_count;
  let mapped = tonemap(radiance * params.exposure_scale, params.tone_mapper);
  return vec4f(linear_to_srgb(clamp(mapped, vec3f(0.0), vec3f(1.0))), 1.0);
}
