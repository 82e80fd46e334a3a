// The end of the real-time chain: remodulates the (filtered) illumination by the G-buffer albedo and
// adds the (temporally accumulated) first-hit emission back, giving linear radiance for the tone mapper, or shows one of the denoiser's debug views instead. The
// closed set of views is DENOISE_VIEW_*, mirrored by position in renderer/settings.ts.
// Expects the view (group 1) and denoise/gbuffer.

#import view/bindings
#import denoise/gbuffer

const DENOISE_VIEW_OUTPUT: u32 = 0u;
const DENOISE_VIEW_HISTORY_LENGTH: u32 = 1u;
const DENOISE_VIEW_VARIANCE: u32 = 2u;
const DENOISE_VIEW_NORMAL: u32 = 3u;
const DENOISE_VIEW_DEPTH: u32 = 4u;
const DENOISE_VIEW_ALBEDO: u32 = 5u;
const DENOISE_VIEW_MOTION: u32 = 6u;
const DENOISE_VIEW_ID: u32 = 7u;

struct DenoiseOutputParams {
  // One of DENOISE_VIEW_*.
  view_mode: u32,
  // History length shown as white (history-length view).
  full_history: f32,
  // Depth shown as mid grey (depth view), scene units.
  depth_scale: f32,
}

@group(2) @binding(0) var<uniform> params: DenoiseOutputParams;
@group(2) @binding(1) var<storage, read> gbuffer: array<GBufferTexel>;
@group(2) @binding(2) var<storage, read> history: array<HistoryTexel>;
// rgb: the accumulated illumination before spatial filtering; a: its variance.
@group(2) @binding(3) var<storage, read> filter_input: array<vec4f>;
// rgb: the illumination to remodulate (spatial filter's output, or filter_input when it is off).
@group(2) @binding(4) var<storage, read> illumination: array<vec4f>;
// Linear radiance, vec4f like the accumulation buffer (a = 1) so the tone mapper reads either.
@group(2) @binding(5) var<storage, read_write> output: array<vec4f>;

// A stable pseudo-random colour per id.
fn id_colour(id: u32) -> vec3f {
  if (id == NO_ID) {
    return vec3f(0.0);
  }
  var h = id * 747796405u + 2891336453u;
  h = ((h >> ((h >> 28u) + 4u)) ^ h) * 277803737u;
  return vec3f(f32(h & 255u), f32((h >> 8u) & 255u), f32((h >> 16u) & 255u)) / 255.0;
}

@compute @workgroup_size(8, 8)
fn denoise_output(@builtin(global_invocation_id) id: vec3u) {
  if (any(id.xy >= view.image_size)) {
    return;
  }
  let i = id.y * view.image_size.x + id.x;
  let g = gbuffer[i];
  var c = vec3f(0.0);
  switch params.view_mode {
    case DENOISE_VIEW_HISTORY_LENGTH: {
      c = vec3f(min(history[i].length / params.full_history, 1.0));
    }
    case DENOISE_VIEW_VARIANCE: {
      // Standard deviation relative to the luminance it belongs to, so dark and bright regions compare.
      let f = filter_input[i];
      c = vec3f(sqrt(f.a) / max(dot(f.rgb, vec3f(0.2126, 0.7152, 0.0722)), 1e-4));
    }
    case DENOISE_VIEW_NORMAL: {
      c = g.normal * 0.5 + 0.5;
    }
    case DENOISE_VIEW_DEPTH: {
      c = select(vec3f(g.linear_depth / (g.linear_depth + params.depth_scale)), vec3f(1.0, 0.0, 1.0), is_miss(g));
    }
    case DENOISE_VIEW_ALBEDO: {
      c = g.albedo;
    }
    case DENOISE_VIEW_MOTION: {
      // Pixels moved since the previous frame, ±16 px across the range; blue marks off-screen.
      let motion = g.previous_position - (vec2f(id.xy) + 0.5);
      c = select(vec3f(clamp(motion / 32.0 + 0.5, vec2f(0.0), vec2f(1.0)), 0.0), vec3f(0.0, 0.0, 1.0), g.previous_position.x == OFF_SCREEN);
    }
    case DENOISE_VIEW_ID: {
      c = id_colour(g.id);
    }
    default: {
      c = history[i].emission + illumination[i].rgb * demodulation(g.albedo);
    }
  }
  output[i] = vec4f(c, 1.0);
}
