// Tone mapping: accumulated radiance → mean → exposure → tone curve → sRGB → 8-bit image.
// Expects the view (group 1) for the image size; its own inputs and outputs are group 2.

#import lib/workgroup
#import lib/color
#import lib/exposure
#import view/bindings

struct TonemapParams {
  // 2^exposure_stops; with auto_exposure, multiplies the adapted exposure (1 as the renderer uses it).
  exposure_scale: f32,
  // One of the TONEMAP_* constants of lib/color.
  tone_mapper: u32,
  // 1 / samples accumulated per pixel (0 before the first sample: a black image).
  inv_sample_count: f32,
  // 1: the exposure is passes/exposure's adapted one (exposure.scale), 0: exposure_scale alone.
  auto_exposure: u32,
}

@group(2) @binding(0) var<uniform> params: TonemapParams;
@group(2) @binding(1) var<storage, read> accumulation: array<vec4f>;
@group(2) @binding(2) var output: texture_storage_2d<rgba8unorm, write>;
@group(2) @binding(3) var<storage, read> exposure: ExposureState;

@compute @workgroup_size(PIXEL_TILE_X, PIXEL_TILE_Y)
fn tonemap_image(@builtin(global_invocation_id) id: vec3u) {
  if (any(id.xy >= view.image_size)) {
    return;
  }
  let radiance = accumulation[id.y * view.image_size.x + id.x].rgb * params.inv_sample_count;
  let scale = select(params.exposure_scale, params.exposure_scale * exposure.scale, params.auto_exposure != 0u);
  let mapped = tonemap(radiance * scale, params.tone_mapper);
  let encoded = linear_to_srgb(clamp(mapped, vec3f(0.0), vec3f(1.0)));
  textureStore(output, id.xy, vec4f(encoded, 1.0));
}
