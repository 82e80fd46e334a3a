// One iteration of the edge-avoiding à-trous wavelet filter (Dammertz et al. 2010) as SVGF uses it
// (Schied et al. 2017, §4.3): a 5×5 B3-spline kernel with holes of `step` pixels, weighted by
// edge-stopping functions of normal, depth (relative to the local depth gradient) and luminance
// (relative to the standard deviation of the 3×3-blurred variance). Filters the demodulated
// illumination (rgb) and carries its variance (a) through with squared weights. Expects the view
// (group 1).

#import lib/workgroup
#import lib/color
#import view/bindings

struct AtrousParams {
  // Distance between taps in pixels: 1, 2, 4, 8, 16 over the five iterations.
  step: i32,
  // Edge-stopping strengths (SVGF: σ_l = 4, σ_n = 128, σ_z = 1).
  sigma_luminance: f32,
  sigma_normal: f32,
  sigma_depth: f32,
}

@group(2) @binding(0) var<uniform> params: AtrousParams;
// Per pixel: xyz = normal, w = linear depth (MISS_DEPTH for a miss), copied from the G-buffer.
@group(2) @binding(1) var<storage, read> guide: array<vec4f>;
@group(2) @binding(2) var<storage, read> filter_source: array<vec4f>;
@group(2) @binding(3) var<storage, read_write> filter_result: array<vec4f>;

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

// The variance at p blurred by a 3×3 Gaussian: a steadier guide than one pixel's estimate.
fn blurred_variance(p: vec2i) -> f32 {
  var sum = 0.0;
  var weights = 0.0;
  for (var dy = -1; dy <= 1; dy++) {
    for (var dx = -1; dx <= 1; dx++) {
      let q = p + vec2i(dx, dy);
      if (inside(q)) {
        let w = select(0.5, 1.0, dx == 0) * select(0.5, 1.0, dy == 0);
        sum += w * filter_source[texel_index(q)].a;
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
      let depth = guide[texel_index(q)].w;
      if (depth >= 0.0) {
        slope = min(slope, abs(depth - z));
      }
    }
  }
  return select(slope, 0.0, slope == 1e30);
}

@compute @workgroup_size(PIXEL_TILE_X, PIXEL_TILE_Y)
fn atrous_step(@builtin(global_invocation_id) id: vec3u) {
  if (any(id.xy >= view.image_size)) {
    return;
  }
  let p = vec2i(id.xy);
  let i = texel_index(p);
  let centre = filter_source[i];
  let g = guide[i];
  let miss = g.w < 0.0;
  let l_p = luminance(centre.rgb);
  let luminance_scale = params.sigma_luminance * sqrt(max(blurred_variance(p), 0.0)) + 1e-10;
  let slope = vec2f(depth_slope(p, vec2i(1, 0), g.w), depth_slope(p, vec2i(0, 1), g.w));

  var colour = vec3f(0.0);
  var variance = 0.0;
  var weights = 0.0;
  for (var dy = -2; dy <= 2; dy++) {
    for (var dx = -2; dx <= 2; dx++) {
      let q = p + params.step * vec2i(dx, dy);
      if (!inside(q)) {
        continue;
      }
      let s = filter_source[texel_index(q)];
      let gq = guide[texel_index(q)];
      var w = b3(abs(dx)) * b3(abs(dy));
      if (dx != 0 || dy != 0) {
        if (miss != (gq.w < 0.0)) {
          continue;
        }
        if (!miss) {
          let offset = vec2f(f32(params.step * abs(dx)), f32(params.step * abs(dy)));
          let depth_scale = params.sigma_depth * dot(slope, offset) + 1e-3 * g.w;
          w *= exp(-abs(g.w - gq.w) / depth_scale);
          w *= pow(max(dot(g.xyz, gq.xyz), 0.0), params.sigma_normal);
        }
        w *= exp(-abs(l_p - luminance(s.rgb)) / luminance_scale);
      }
      colour += w * s.rgb;
      variance += w * w * s.a;
      weights += w;
    }
  }
  filter_result[i] = vec4f(colour / weights, variance / (weights * weights));
}
