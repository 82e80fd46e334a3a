// The end of the real-time chain without the spatial filter (or with a debug view, which skips it):
// remodulates the temporal pass's illumination by the frame's albedo and adds the first-hit emission
// back, giving linear radiance for the tone mapper, or shows one of the denoiser's debug views
// instead; and keeps that illumination as the colour history (with the filter on, its first
// iteration writes the history: passes/denoise-atrous). The closed set of views is DENOISE_VIEW_*,
// mirrored by position in renderer/settings.ts.
// Expects the view (group 1) and denoise/gbuffer.

#import lib/workgroup
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
@group(2) @binding(1) var<storage, read> surface_records: array<SurfaceTexel>;
@group(2) @binding(2) var<storage, read> frame_records: array<FrameTexel>;
@group(2) @binding(3) var<storage, read> moments: array<MomentsTexel>;
// In: this pixel's temporal output (FRAME_TEMPORAL) and motion; out: linear radiance (vec4f, a = 1)
// over the same four words, like the accumulation buffer, so the tone mapper reads either.
@group(2) @binding(4) var<storage, read_write> frame_scratch: array<u32>;
// The colour history (illumination pairs): without the spatial filter, the temporal output itself.
@group(2) @binding(5) var<storage, read_write> history: array<vec2u>;

// A stable pseudo-random colour per id.
fn id_colour(id: u32) -> vec3f {
  if (id == NO_ID) {
    return vec3f(0.0);
  }
  var h = id * 747796405u + 2891336453u;
  h = ((h >> ((h >> 28u) + 4u)) ^ h) * 277803737u;
  return vec3f(f32(h & 255u), f32((h >> 8u) & 255u), f32((h >> 16u) & 255u)) / 255.0;
}

@compute @workgroup_size(PIXEL_TILE_X, PIXEL_TILE_Y)
fn denoise_output(@builtin(global_invocation_id) id: vec3u) {
  if (any(id.xy >= view.image_size)) {
    return;
  }
  let i = id.y * view.image_size.x + id.x;
  let g = unpack_surface(surface_records[i]);
  let f = frame_records[i];
  let base = FRAME_WORDS * i;
  let pair = vec2u(frame_scratch[base + FRAME_TEMPORAL], frame_scratch[base + FRAME_TEMPORAL + 1u]);
  let temporal = unpack_illumination(pair);
  let motion = unpack_motion(frame_scratch[base + FRAME_MOTION]);
  history[i] = pair;
  var c = vec3f(0.0);
  switch params.view_mode {
    case DENOISE_VIEW_HISTORY_LENGTH: {
      c = vec3f(min(moments[i].length / params.full_history, 1.0));
    }
    case DENOISE_VIEW_VARIANCE: {
      // Standard deviation relative to the luminance it belongs to, so dark and bright regions compare.
      c = vec3f(sqrt(temporal.a) / max(dot(temporal.rgb, vec3f(0.2126, 0.7152, 0.0722)), 1e-4));
    }
    case DENOISE_VIEW_NORMAL: {
      c = g.normal * 0.5 + 0.5;
    }
    case DENOISE_VIEW_DEPTH: {
      c = select(vec3f(g.linear_depth / (g.linear_depth + params.depth_scale)), vec3f(1.0, 0.0, 1.0), is_miss_depth(g.linear_depth));
    }
    case DENOISE_VIEW_ALBEDO: {
      c = frame_albedo(f);
    }
    case DENOISE_VIEW_MOTION: {
      // Pixels moved since the previous frame, ±16 px across the range; blue marks off-screen.
      c = select(vec3f(clamp(motion / 32.0 + 0.5, vec2f(0.0), vec2f(1.0)), 0.0), vec3f(0.0, 0.0, 1.0), is_off_screen_motion(motion));
    }
    case DENOISE_VIEW_ID: {
      c = id_colour(g.id);
    }
    default: {
      c = frame_emission(f) + temporal.rgb * demodulation(frame_albedo(f));
    }
  }
  frame_scratch[base] = bitcast<u32>(c.r);
  frame_scratch[base + 1u] = bitcast<u32>(c.g);
  frame_scratch[base + 2u] = bitcast<u32>(c.b);
  frame_scratch[base + 3u] = bitcast<u32>(1.0);
}
