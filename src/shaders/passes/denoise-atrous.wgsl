// One iteration of the real-time denoiser's edge-avoiding à-trous wavelet filter (Dammertz et al.
// 2010) as SVGF uses it (Schied et al. 2017, §4.3): a 5×5 B3-spline kernel with holes of `step`
// pixels, weighted by edge-stopping functions of normal, depth (relative to the local depth slope)
// and luminance (relative to the noise), filtering the demodulated illumination and carrying its
// variance through with squared weights; applied as a flow of light between pairs of pixels, so that
// the filter keeps the image's energy (docs/denoise.md, "Energy").
//
// SVGF normalises each pixel's weights by their sum, out_p = Σ_q w_pq·c_q / W_p with W_p = Σ_q w_pq:
// every pixel is a weighted mean of its taps, but nothing makes a pixel give away what its neighbours
// take from it. A bright pixel (a sample that found the light) that its dark neighbours refuse
// (luminance edge-stopping) has a small W_p, so it divides itself into them, and the light it loses
// goes nowhere: the Cornell box at 4 spp held 0.963 of its energy away from the light (issue #27).
// Here instead
//
//   out_p = c_p + Σ_q k_pq·(c_q − c_p),   k_pq = w_pq / max(W_p, W_q),
//
// with every edge-stopping factor of w symmetric in p and q (the luminance difference against both
// pixels' noise, the depth difference against both pixels' slopes, the distance between the normals):
// k_pq = k_qp, so what p takes from q, q gives to p, and Σ_p out_p = Σ_p c_p exactly. As W_p ≥ w_pp +
// Σ_q w_pq, Σ_q k_pq < 1: each out_p is a convex combination of its taps. Where the weights around p
// and q agree (W_p = W_q) this is SVGF's normalised mean itself; a pixel whose taps refuse it keeps its
// light instead of being averaged away. W needs the taps' own sums: in the first two iterations a
// dispatch before the filter (ATROUS_WEIGHTS) writes every pixel's W; the later ones take the sums
// the previous iteration's filter found at its own step (W of another step is still one number per
// pixel, so k stays symmetric), and cap each k_pq at h_pq / (1 − h_pp), so that Σ_q k_pq ≤ 1 whatever
// the sums. Measured (docs/denoise.md, "Energy"): the same error as exact sums in all five
// iterations, for two weights dispatches instead of five; exact sums in the first iteration only, or
// the cap with exact sums, raised it 7–10 %.
//
// Both frame recipes filter with it. The guide is the pixel-centre surface record, and source and
// result are illumination pairs (two words: f16 rgb, f16 σ, denoise/gbuffer) that live in one of two
// bound word arrays at a stride and offset the host chooses per iteration. So the real-time chain's
// iterations ping-pong inside the frame scratch (words 0–1 and 2–3 of each pixel), the colour history
// and the moments the temporal pass has finished with (passes/denoise-passes.ts atrousSchedule), and
// the last iteration remodulates and writes the frame's linear output (vec4f) over the frame scratch;
// the hybrid recipe's GI filter ping-pongs between its two GI buffers (PING_PONG), on a view of the GI
// target's size, with its own slopes and sums. The depth slopes (ATROUS_SLOPES, once before the iterations)
// and the weight sums live in the previous frame's surface records, which the temporal pass has
// finished with and the next frame's G-buffer overwrites. Expects the view (group 1) and denoise/gbuffer.

#import lib/workgroup
#import lib/color
#import view/bindings
#import denoise/gbuffer

// What an iteration writes besides its filtered pair.
const ATROUS_PLAIN: u32 = 0u;
// Also copies the source's own pair to other_words (stride 2; the source is in the frame scratch, the
// colour history bound as other_words): the unfiltered history when feedback is off.
const ATROUS_COPY_HISTORY: u32 = 1u;
// Instead of a pair: remodulates (albedo) and adds the emission, writing the output vec4f into the
// result array (the frame scratch), 16 bytes a pixel.
const ATROUS_OUTPUT: u32 = 2u;
// No filtering: writes the pixel's depth slopes (the frame's, once before the iterations).
const ATROUS_SLOPES: u32 = 3u;
// No filtering: writes the sum W of the pixel's weights at this iteration's step (before its filter).
const ATROUS_WEIGHTS: u32 = 4u;

struct DenoiseAtrousParams {
  // Distance between taps in pixels: 1, 2, 4, 8, 16 over the five iterations.
  step: i32,
  // Edge-stopping strengths (SVGF: σ_l = 4, σ_n = 128, σ_z = 1).
  sigma_luminance: f32,
  sigma_normal: f32,
  sigma_depth: f32,
  // Where the source pair of pixel i is in `source_words`: words stride · i + offset.
  source_stride: u32,
  source_offset: u32,
  // Where the result pair goes: the array (0: source_words, 1: other_words), words stride · i + offset.
  result_array: u32,
  result_stride: u32,
  result_offset: u32,
  // ATROUS_*.
  mode: u32,
  // The weight sums' regions of filter_scratch (1 or 2) this dispatch reads and writes (0: none).
  weights_read: u32,
  weights_write: u32,
  // 1: the sums read are the previous iteration's (another step), so each pair's coefficient is capped
  // to keep the pixel a convex combination.
  capped: u32,
}

@group(2) @binding(0) var<uniform> params: DenoiseAtrousParams;
@group(2) @binding(1) var<storage, read> surface_records: array<SurfaceTexel>;
@group(2) @binding(2) var<storage, read> frame_records: array<FrameTexel>;
// The buffer that holds the source pairs, and the other of the two (the frame scratch, and the colour
// history or the previous moments: the host binds each iteration's source buffer as source_words, so
// that no tap chooses between arrays). Both read_write: a pass may read one pixel's words of an array
// while writing others' (WebGPU forbids two bindings of one buffer when either is writable). Bound as
// word pairs (every stride and offset is even), so that a tap's pair is one 8-byte load.
@group(2) @binding(3) var<storage, read_write> source_words: array<vec2u>;
@group(2) @binding(4) var<storage, read_write> other_words: array<vec2u>;
// The previous frame's surface records (12 bytes a pixel), free once the temporal pass has read them:
// word i holds pixel i's depth slopes along x and y (f16 pair), words n + i and 2n + i its weight
// sums (f32) in two regions that the iterations alternate between (read one, write the other), n the
// number of pixels.
@group(2) @binding(5) var<storage, read_write> filter_scratch: array<u32>;

const LOG2_E: f32 = 1.4426950408889634;
// 1 / (1 − (6/16)²): the B3 kernel's taps off the centre, scaled to sum to 1.
const OFF_CENTRE_SHARE: f32 = 1.1636363636363636;
// 1/(2·ln 2): pow(cos θ, σ) ≈ exp(−σ·θ²/2) = exp2(−σ·θ²/(2·ln 2)).
const NORMAL_EXPONENT: f32 = 0.7213475204444817;

fn texel_index(q: vec2i) -> u32 {
  return u32(q.y) * view.image_size.x + u32(q.x);
}

fn inside(q: vec2i) -> bool {
  return all(q >= vec2i(0)) && all(q < vec2i(view.image_size));
}

// rgb: illumination, a: variance of the source at pixel i.
fn source(i: u32) -> vec4f {
  return unpack_illumination(source_words[(params.source_stride * i + params.source_offset) >> 1u]);
}

// Writes pair k of the array params.result_array names.
fn store_pair(k: u32, p: vec2u) {
  if (params.result_array == 0u) {
    source_words[k] = p;
  } else {
    other_words[k] = p;
  }
}

fn source_depth(q: vec2i) -> f32 {
  return surface_records[texel_index(q)].linear_depth;
}

// The smaller one-sided difference of linear depth along one axis (the smaller side does not cross an edge).
fn depth_slope(p: vec2i, axis: vec2i, z: f32) -> f32 {
  var slope = 1e30;
  for (var s = -1; s <= 1; s += 2) {
    let q = p + s * axis;
    if (inside(q)) {
      let depth = source_depth(q);
      if (depth >= 0.0) {
        slope = min(slope, abs(depth - z));
      }
    }
  }
  return select(slope, 0.0, slope == 1e30);
}

fn weights_index(region: u32, i: u32) -> u32 {
  return region * view.image_size.x * view.image_size.y + i;
}

// Pixel i's depth slopes (x, y) and the weight sum this dispatch reads (z; 1 where it reads none).
fn filter_record(i: u32) -> vec3f {
  let w = select(bitcast<f32>(filter_scratch[weights_index(params.weights_read, i)]), 1.0, params.weights_read == 0u);
  return vec3f(unpack2x16float(filter_scratch[i]), w);
}

// The B3 spline (1, 4, 6, 4, 1) / 16 by distance from the centre (0, 1 or 2 taps).
fn b3(d: i32) -> f32 {
  return select(select(0.0625, 0.25, d == 1), 0.375, d == 0);
}

// The pixel p the filter is at: its pair, surface and depth slopes.
struct FilterCentre {
  colour: vec4f,
  luminance: f32,
  surface: SurfaceTexel,
  normal_code: vec2f,
  miss: bool,
  slope: vec2f,
}

// The weight w_pq of tap q, (dx, dy) kernel taps from p: the B3 kernel times exp2 of the edge-stopping
// exponents, each symmetric in p and q, so that w_pq = w_qp. 0: the tap is outside or across the sky's
// edge. The exponents are folded into one exp2 per tap (they add):
// - luminance: the difference against σ_l times the standard deviation of a difference of two such
//   pixels, from both variances (σ_l·√((v_p + v_q)/2); SVGF's σ_l·√v_p where the two agree);
// - depth: the difference against σ_z times the larger of the two pixels' slopes along the offset,
//   plus a thousandth of the nearer depth;
// - normal: dot(n, n_q)^σ_n ≈ exp(−σ_n·θ²/2) for the angle θ between the normals, taken in the
//   octahedral map the normals are stored in (denoise/gbuffer), where a small angle θ is a distance of
//   θ to √2·θ: w_n = exp2(−σ_n/(2·ln 2)·|e − e_q|²). No normal is decoded, and a tap needs one
//   transcendental call instead of four (decode's normalise, pow's log2 and exp2). Across the map's
//   seam (normals near −z) the distance is large and the weight 0: the filter stops there as at an
//   edge (docs/denoise.md, "GPU time").
struct Tap {
  colour: vec4f,
  weight: f32,
  // The tap's weight sum W_q (the filter dispatch's; stale in the weights dispatch, which writes it).
  weight_sum: f32,
}

fn tap(c: FilterCentre, p: vec2i, dx: i32, dy: i32) -> Tap {
  let q = p + params.step * vec2i(dx, dy);
  if (!inside(q)) {
    return Tap(vec4f(0.0), 0.0, 1.0);
  }
  let qi = texel_index(q);
  // The loads are issued before the test, so that their latencies overlap.
  let gq = surface_records[qi];
  let s = source(qi);
  let record_q = filter_record(qi);
  let slope_q = record_q.xy;
  if (c.miss != is_miss_depth(gq.linear_depth)) {
    return Tap(s, 0.0, record_q.z);
  }
  var exponent = -LOG2_E / params.sigma_luminance * abs(c.luminance - luminance(s.rgb)) * inverseSqrt(max(0.5 * (c.colour.a + s.a), 1e-30));
  if (!c.miss) {
    let offset = vec2f(f32(params.step * abs(dx)), f32(params.step * abs(dy)));
    let depth_scale = params.sigma_depth * dot(max(c.slope, slope_q), offset) + 1e-3 * min(c.surface.linear_depth, gq.linear_depth);
    exponent -= LOG2_E * abs(c.surface.linear_depth - gq.linear_depth) / depth_scale;
    let d = c.normal_code - unpack2x16snorm(gq.normal);
    exponent -= params.sigma_normal * NORMAL_EXPONENT * dot(d, d);
  }
  return Tap(s, b3(abs(dx)) * b3(abs(dy)) * exp2(exponent), record_q.z);
}

@compute @workgroup_size(PIXEL_TILE_X, PIXEL_TILE_Y)
fn denoise_atrous_step(@builtin(global_invocation_id) id: vec3u) {
  if (any(id.xy >= view.image_size)) {
    return;
  }
  let p = vec2i(id.xy);
  let i = texel_index(p);
  if (params.mode == ATROUS_SLOPES) {
    let z = source_depth(p);
    let slope = select(vec2f(depth_slope(p, vec2i(1, 0), z), depth_slope(p, vec2i(0, 1), z)), vec2f(0.0), is_miss_depth(z));
    filter_scratch[i] = pack_f16_pair(slope.x, slope.y);
    return;
  }
  let g = surface_records[i];
  let centre = source(i);
  let record = filter_record(i);
  let c = FilterCentre(centre, luminance(centre.rgb), g, unpack2x16snorm(g.normal), is_miss_depth(g.linear_depth), record.xy);
  if (params.mode == ATROUS_WEIGHTS) {
    var sum = b3(0) * b3(0);
    for (var dy = -2; dy <= 2; dy++) {
      for (var dx = -2; dx <= 2; dx++) {
        if (dx != 0 || dy != 0) {
          sum += tap(c, p, dx, dy).weight;
        }
      }
    }
    filter_scratch[weights_index(params.weights_write, i)] = bitcast<u32>(sum);
    return;
  }
  // Light moves between pairs: the pixel keeps what its taps do not take.
  let w_p = record.z;
  var flow = vec3f(0.0);
  var kept = 1.0;
  var variance = 0.0;
  var sum = b3(0) * b3(0);
  for (var dy = -2; dy <= 2; dy++) {
    for (var dx = -2; dx <= 2; dx++) {
      if (dx == 0 && dy == 0) {
        continue;
      }
      let t = tap(c, p, dx, dy);
      if (t.weight == 0.0) {
        continue;
      }
      sum += t.weight;
      let h = b3(abs(dx)) * b3(abs(dy));
      // Capped at h / (1 − h_centre), the taps' coefficients sum to at most 1.
      let normalised = t.weight / max(w_p, t.weight_sum);
      let k = select(normalised, min(normalised, h * OFF_CENTRE_SHARE), params.capped != 0u);
      flow += k * (t.colour.rgb - centre.rgb);
      kept -= k;
      variance += k * k * t.colour.a;
    }
  }
  // This iteration's own sums normalise the next one where no weights dispatch runs (their steps
  // differ, so the next iteration caps its coefficients).
  if (params.weights_write != 0u) {
    filter_scratch[weights_index(params.weights_write, i)] = bitcast<u32>(sum);
  }
  let filtered = vec4f(centre.rgb + flow, kept * kept * centre.a + variance);
  if (params.mode == ATROUS_OUTPUT) {
    let f = frame_records[i];
    let c = frame_emission(f) + filtered.rgb * demodulation(frame_albedo(f));
    let k = (FRAME_WORDS / 2u) * i;
    store_pair(k, bitcast<vec2u>(c.rg));
    store_pair(k + 1u, bitcast<vec2u>(vec2f(c.b, 1.0)));
    return;
  }
  if (params.mode == ATROUS_COPY_HISTORY) {
    other_words[i] = pack_illumination(centre.rgb, centre.a);
  }
  store_pair((params.result_stride * i + params.result_offset) >> 1u, pack_illumination(filtered.rgb, filtered.a));
}
