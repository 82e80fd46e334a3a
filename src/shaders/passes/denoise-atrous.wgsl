// One iteration of the real-time denoiser's edge-avoiding à-trous wavelet filter (Dammertz et al.
// 2010) as SVGF uses it (Schied et al. 2017, §4.3): a 5×5 B3-spline kernel with holes of `step`
// pixels, weighted by edge-stopping functions of normal, depth (relative to the local depth gradient)
// and luminance (relative to the standard deviation of the 3×3-blurred variance). Filters the
// demodulated illumination and carries its variance through with squared weights.
//
// The packed twin of passes/atrous (which the hybrid recipe keeps for its vec4f buffers): the guide is
// the pixel-centre surface record, and source and result are illumination pairs (two words: f16 rgb,
// f16 σ, denoise/gbuffer) that live in one of two bound word arrays at a stride and offset the host
// chooses per iteration. So the iterations ping-pong inside the frame scratch (words 0–1 and 2–3 of
// each pixel), the colour history and the moments the temporal pass has finished with (renderer/
// denoiser.ts has the schedule), and the last iteration remodulates and writes the frame's linear
// output (vec4f) over the frame scratch. Expects the view (group 1) and denoise/gbuffer.

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

const LOG2_E: f32 = 1.4426950408889634;
// 1/(2·ln 2): pow(cos θ, σ) ≈ exp(−σ·θ²/2) = exp2(−σ·θ²/(2·ln 2)).
const NORMAL_EXPONENT: f32 = 0.7213475204444817;

// The B3 spline (1, 4, 6, 4, 1) / 16 by distance from the centre (0, 1 or 2 taps).
fn b3(d: i32) -> f32 {
  return select(select(0.0625, 0.25, d == 1), 0.375, d == 0);
}

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

// The variance at p blurred by a 3×3 Gaussian: a steadier guide than one pixel's estimate.
fn blurred_variance(p: vec2i) -> f32 {
  var sum = 0.0;
  var weights = 0.0;
  for (var dy = -1; dy <= 1; dy++) {
    for (var dx = -1; dx <= 1; dx++) {
      let q = p + vec2i(dx, dy);
      if (inside(q)) {
        let w = select(0.5, 1.0, dx == 0) * select(0.5, 1.0, dy == 0);
        sum += w * source(texel_index(q)).a;
        weights += w;
      }
    }
  }
  return sum / weights;
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

@compute @workgroup_size(8, 8)
fn denoise_atrous_step(@builtin(global_invocation_id) id: vec3u) {
  if (any(id.xy >= view.image_size)) {
    return;
  }
  let p = vec2i(id.xy);
  let i = texel_index(p);
  let centre = source(i);
  let g = surface_records[i];
  let g_normal = unpack2x16snorm(g.normal);
  let miss = is_miss_depth(g.linear_depth);
  let l_p = luminance(centre.rgb);
  // The edge-stopping weights are folded into one exp2 per tap (their exponents add): exp(−Δz/s_z) ·
  // w_n · exp(−Δl/s_l). The normal term, dot(n, n_q)^σ_n ≈ exp(−σ_n·θ²/2) for the angle θ between
  // the normals, is taken in the octahedral map the normals are stored in (denoise/gbuffer), where a
  // small angle θ is a distance of θ to √2·θ: w_n = exp2(−σ_n/(2·ln 2)·|e − e_q|²). No normal is
  // decoded, and a tap needs one transcendental call instead of four (decode's normalise, pow's log2
  // and exp2). Across the map's seam (normals near −z) the distance is large and the weight 0: the
  // filter stops there as at an edge (docs/denoise.md, "GPU time").
  let inv_luminance_scale = 1.0 / (params.sigma_luminance * sqrt(max(blurred_variance(p), 0.0)) + 1e-10);
  let slope = vec2f(depth_slope(p, vec2i(1, 0), g.linear_depth), depth_slope(p, vec2i(0, 1), g.linear_depth));

  var colour = vec3f(0.0);
  var variance = 0.0;
  var weights = 0.0;
  for (var dy = -2; dy <= 2; dy++) {
    for (var dx = -2; dx <= 2; dx++) {
      let q = p + params.step * vec2i(dx, dy);
      if (!inside(q)) {
        continue;
      }
      let qi = texel_index(q);
      var s = centre;
      var w = b3(abs(dx)) * b3(abs(dy));
      if (dx != 0 || dy != 0) {
        // Both loads are issued before the test, so that their latencies overlap.
        let gq = surface_records[qi];
        s = source(qi);
        if (miss != is_miss_depth(gq.linear_depth)) {
          continue;
        }
        var exponent = -abs(l_p - luminance(s.rgb)) * inv_luminance_scale * LOG2_E;
        if (!miss) {
          let offset = vec2f(f32(params.step * abs(dx)), f32(params.step * abs(dy)));
          let depth_scale = params.sigma_depth * dot(slope, offset) + 1e-3 * g.linear_depth;
          exponent -= abs(g.linear_depth - gq.linear_depth) / depth_scale * LOG2_E;
          let d = g_normal - unpack2x16snorm(gq.normal);
          exponent -= params.sigma_normal * NORMAL_EXPONENT * dot(d, d);
        }
        w *= exp2(exponent);
      }
      colour += w * s.rgb;
      variance += w * w * s.a;
      weights += w;
    }
  }
  let filtered = vec4f(colour / weights, variance / (weights * weights));
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
