// Temporal accumulation of the frame's demodulated radiance. Each pixel is reprojected into the
// previous frame (the path tracer's motion); the four bilinear taps there are kept only where the
// previous surface record agrees (same side of the sky, same material, depth within a relative
// tolerance, normals within an angle) and inside the image, else the history is rejected
// (disocclusion). Accepted history is clamped in YCoCg to the current 3×3 neighbourhood's mean ± k·σ
// (Karis 2014), a large overshoot counts as a change of the pixel and shortens its history, and the
// result blends with weight 1/N up to the history cap. Luminance moments are integrated alongside,
// giving SVGF's per-pixel variance (Schied et al. 2017, §4.2), with a spatial 3×3 estimate while the
// history is short.
//
// The colour history is the first à-trous iteration's output of the previous frame (SVGF's feedback,
// §4: it is written into `history` after this pass has read it); the moments and lengths ping-pong.
// The result (illumination, variance) goes to the frame scratch's words FRAME_TEMPORAL, which only
// this pixel reads here: the neighbours read FRAME_RADIANCE. Expects the view (group 1) and
// denoise/gbuffer.

#import lib/workgroup
#import lib/color
#import view/bindings
#import denoise/gbuffer

struct TemporalParams {
  // Largest history length N (the blend weight never falls below 1/N).
  history_cap: f32,
  // Half-width of the clamp box in standard deviations; ≤ 0: no clamping (a still camera converging without limit).
  clamp_k: f32,
  // 0: ignore the history (temporal accumulation off, or the first frame): pass the frame through.
  use_history: u32,
}

// Reprojection tests: relative depth difference and cosine between normals.
const DEPTH_TOLERANCE: f32 = 0.05;
const NORMAL_COS_TOLERANCE: f32 = 0.9;
// Below this history length the variance comes from the spatial neighbourhood (SVGF uses 4 frames).
const SHORT_HISTORY: f32 = 4.0;
// History further outside the clamp box than this many box half-widths marks a changed pixel, whose
// history is cut to CHANGED_HISTORY frames so that the new value takes over within a few frames.
const CHANGE_OVERSHOOT: f32 = 1.0;
const CHANGED_HISTORY: f32 = 2.0;

@group(2) @binding(0) var<uniform> params: TemporalParams;
@group(2) @binding(1) var<storage, read_write> frame_scratch: array<u32>;
@group(2) @binding(2) var<storage, read> surface_records: array<SurfaceTexel>;
@group(2) @binding(3) var<storage, read> previous_surface_records: array<SurfaceTexel>;
// Illumination pairs (f16 rgb, σ): the previous frame's filtered (or, unfiltered, accumulated) colour.
@group(2) @binding(4) var<storage, read> history: array<vec2u>;
@group(2) @binding(5) var<storage, read> previous_moments: array<MomentsTexel>;
@group(2) @binding(6) var<storage, read_write> moments: array<MomentsTexel>;

struct History {
  illumination: vec3f,
  length: f32,
  moments: vec2f,
}

// Whether the previous frame's record `p` shows the same surface as the current `g` (seen from the
// previous camera at `previous_depth`).
fn same_surface(g: PixelSurface, previous_depth: f32, p: SurfaceTexel) -> bool {
  let g_miss = is_miss_depth(g.linear_depth);
  let p_miss = is_miss_depth(p.linear_depth);
  if (g_miss || p_miss) {
    return g_miss && p_miss;
  }
  return p.id == g.id
    && abs(p.linear_depth - previous_depth) <= DEPTH_TOLERANCE * previous_depth
    && dot(unpack_normal(p.normal), g.normal) >= NORMAL_COS_TOLERANCE;
}

// The history at the reprojected point: bilinear over the taps that pass same_surface. length 0: rejected.
fn reprojected_history(g: PixelSurface, previous_depth: f32, previous_position: vec2f) -> History {
  var sum = History(vec3f(0.0), 0.0, vec2f(0.0));
  let size = vec2i(view.image_size);
  let point = previous_position - 0.5;
  let base = vec2i(floor(point));
  let f = point - floor(point);
  var weight_sum = 0.0;
  for (var tap = 0u; tap < 4u; tap++) {
    let offset = vec2i(i32(tap & 1u), i32(tap >> 1u));
    let q = base + offset;
    if (any(q < vec2i(0)) || any(q >= size)) {
      continue;
    }
    let qi = u32(q.y) * view.image_size.x + u32(q.x);
    if (!same_surface(g, previous_depth, previous_surface_records[qi])) {
      continue;
    }
    let m = previous_moments[qi];
    let w = select(1.0 - f.x, f.x, offset.x == 1) * select(1.0 - f.y, f.y, offset.y == 1);
    sum.illumination += w * unpack_illumination(history[qi]).rgb;
    sum.length += w * m.length;
    sum.moments += w * unpack_moments(m.moments);
    weight_sum += w;
  }
  if (weight_sum < 1e-3) {
    return History(vec3f(0.0), 0.0, vec2f(0.0));
  }
  return History(sum.illumination / weight_sum, sum.length / weight_sum, sum.moments / weight_sum);
}

// Moments are stored as (mean, variance) f16 pairs, not (mean, mean square): the difference of two
// f16 numbers near the square of the mean would lose a small variance to rounding.
fn unpack_moments(word: u32) -> vec2f {
  let mv = unpack2x16float(word);
  return vec2f(mv.x, mv.y + mv.x * mv.x);
}

fn pack_moments(m: vec2f) -> u32 {
  return pack_f16_pair(m.x, max(m.y - m.x * m.x, 0.0));
}

fn frame_radiance(i: u32) -> vec3f {
  return unpack_rgb9e5(frame_scratch[FRAME_WORDS * i + FRAME_RADIANCE]);
}

@compute @workgroup_size(PIXEL_TILE_X, PIXEL_TILE_Y)
fn temporal_accumulate(@builtin(global_invocation_id) id: vec3u) {
  if (any(id.xy >= view.image_size)) {
    return;
  }
  let i = id.y * view.image_size.x + id.x;
  let current = frame_radiance(i);
  let g = unpack_surface(surface_records[i]);
  let motion = unpack_motion(frame_scratch[FRAME_WORDS * i + FRAME_MOTION]);
  let previous_depth = unpack2x16float(frame_scratch[FRAME_WORDS * i + FRAME_PREVIOUS_DEPTH]).x;

  // The current 3×3 neighbourhood: YCoCg mean and deviation for the clamp box, luminance moments for
  // the variance of a short history.
  var sum = vec3f(0.0);
  var sum2 = vec3f(0.0);
  var l_sum = 0.0;
  var l_sum2 = 0.0;
  var n = 0.0;
  let size = vec2i(view.image_size);
  for (var dy = -1; dy <= 1; dy++) {
    for (var dx = -1; dx <= 1; dx++) {
      let q = vec2i(id.xy) + vec2i(dx, dy);
      if (any(q < vec2i(0)) || any(q >= size)) {
        continue;
      }
      let c = frame_radiance(u32(q.y) * view.image_size.x + u32(q.x));
      let y = rgb_to_ycocg(c);
      sum += y;
      sum2 += y * y;
      let l = luminance(c);
      l_sum += l;
      l_sum2 += l * l;
      n += 1.0;
    }
  }
  let mean = sum / n;
  let sigma = sqrt(max(sum2 / n - mean * mean, vec3f(0.0)));
  let spatial_variance = max(l_sum2 / n - (l_sum / n) * (l_sum / n), 0.0);

  // Luminance clamped for the moments only (they estimate the variance; f16 holds them).
  let l = min(luminance(current), MOMENT_LUMINANCE_MAX);
  let frame_moments = vec2f(l, l * l);
  var h = History(vec3f(0.0), 0.0, vec2f(0.0));
  if (params.use_history != 0u && !is_off_screen_motion(motion)) {
    h = reprojected_history(g, previous_depth, vec2f(id.xy) + 0.5 + motion);
  }
  var out = History(current, 1.0, frame_moments);
  if (h.length > 0.0) {
    var history_length = min(h.length + 1.0, params.history_cap);
    if (params.clamp_k > 0.0) {
      // The box is widened by the history's own noise estimate: at 1 spp a 3×3 of nine dark samples
      // has σ = 0 and would otherwise clamp a converged history to black.
      let temporal_variance = max(h.moments.y - h.moments.x * h.moments.x, 0.0);
      let half_width = params.clamp_k * sqrt(sigma * sigma + vec3f(temporal_variance / max(h.length, 1.0))) + vec3f(1e-6);
      let y = rgb_to_ycocg(h.illumination);
      let clamped = clamp(y, mean - half_width, mean + half_width);
      let overshoot = max(max(abs(y.x - clamped.x) / half_width.x, abs(y.y - clamped.y) / half_width.y), abs(y.z - clamped.z) / half_width.z);
      if (overshoot > CHANGE_OVERSHOOT) {
        history_length = min(history_length, CHANGED_HISTORY);
      }
      // The box is clamped per YCoCg axis, so its corners may lie outside the RGB cube: no negative light.
      h.illumination = max(ycocg_to_rgb(clamped), vec3f(0.0));
    }
    let alpha = 1.0 / history_length;
    out = History(mix(h.illumination, current, alpha), history_length, mix(h.moments, frame_moments, alpha));
  }
  moments[i] = MomentsTexel(pack_moments(out.moments), out.length);

  // Variance of the accumulated estimate's luminance: the frame-to-frame variance over the history's
  // window divided by its length; the spatial estimate while the history is short.
  let frame_variance = select(spatial_variance, max(out.moments.y - out.moments.x * out.moments.x, 0.0), out.length >= SHORT_HISTORY);
  let pair = pack_illumination(out.illumination, frame_variance / out.length);
  frame_scratch[FRAME_WORDS * i + FRAME_TEMPORAL] = pair.x;
  frame_scratch[FRAME_WORDS * i + FRAME_TEMPORAL + 1u] = pair.y;
}
