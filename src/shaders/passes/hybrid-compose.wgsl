// The hybrid recipe's image passes, after the ray-traced ones (passes/hybrid):
// - hybrid_compose: the GI target upsampled to the image by a joint bilateral filter (Kopf et al.
//   2007): the 2 × 2 nearest GI texels weighted bilinearly and by how well the surface each was
//   traced from matches this pixel's (normal, relative depth), then
//   L = lit + diffuse_weight · GI;
// - hybrid_taa: temporal anti-aliasing (Karis 2014): the history fetched where the motion vector
//   says the surface was, clamped to the box of this frame's 3 × 3 neighbourhood, blended with
//   this frame by 1 / (frames in the history), no less than `min_blend`.
// Expects the view (group 1) for the image size.

#import lib/workgroup
#import lib/color
#import view/bindings
#import denoise/gbuffer

struct ComposeParams {
  gi_size: vec2u,
  gi_scale: f32,
  // 1: add the GI target; 0: direct light and reflections alone.
  use_gi: u32,
  // Smallest blend of the current frame into the history (TAA); 1 turns TAA off.
  min_blend: f32,
  // 0: no history to reproject (first frame, resize, reset).
  use_history: u32,
}

@group(2) @binding(0) var<uniform> params: ComposeParams;
@group(2) @binding(1) var<storage, read> guide: array<vec4f>;
@group(2) @binding(2) var<storage, read> lit: array<vec4f>;
@group(2) @binding(3) var<storage, read> diffuse_weight: array<vec4f>;
// The GI target (illumination pairs) and the surfaces its texels were traced from (passes/hybrid).
@group(2) @binding(4) var<storage, read> gi: array<vec2u>;
@group(2) @binding(5) var<storage, read> gi_guide: array<SurfaceTexel>;
@group(2) @binding(6) var<storage, read_write> composed: array<vec4f>;
@group(2) @binding(7) var<storage, read> motion: array<vec4f>;
@group(2) @binding(8) var<storage, read> previous_history: array<vec4f>;
@group(2) @binding(9) var<storage, read_write> history: array<vec4f>;
@group(2) @binding(10) var<storage, read_write> output: array<vec4f>;

fn pixel_index(p: vec2u) -> u32 {
  return p.y * view.image_size.x + p.x;
}

// How much a GI texel traced from surface g speaks for a pixel with guide c (normal, linear depth).
fn bilateral_weight(c: vec4f, g: SurfaceTexel) -> f32 {
  if (is_miss_depth(g.linear_depth)) {
    return 0.0;
  }
  let normal = pow(max(dot(c.xyz, unpack_normal(g.normal)), 0.0), 32.0);
  let depth = exp(-abs(c.w - g.linear_depth) / (0.05 * c.w + 1e-6));
  return normal * depth;
}

fn upsampled_gi(pixel: vec2u, c: vec4f) -> vec3f {
  let q = (vec2f(pixel) + 0.5) * params.gi_scale - 0.5;
  let base = vec2i(floor(q));
  let f = q - floor(q);
  let last = vec2i(params.gi_size) - 1;
  var sum = vec3f(0.0);
  var weights = 0.0;
  var fallback = vec3f(0.0);
  var fallback_weight = -1.0;
  for (var dy = 0; dy <= 1; dy++) {
    for (var dx = 0; dx <= 1; dx++) {
      let t = clamp(base + vec2i(dx, dy), vec2i(0), last);
      let k = u32(t.y) * params.gi_size.x + u32(t.x);
      let bilinear = select(1.0 - f.x, f.x, dx == 1) * select(1.0 - f.y, f.y, dy == 1);
      let agrees = bilateral_weight(c, gi_guide[k]);
      let texel = unpack_illumination(gi[k]).rgb;
      let w = bilinear * agrees;
      sum += w * texel;
      weights += w;
      // No neighbour agrees (a thin object, an edge): the one that agrees most.
      let agreement = agrees + 1e-6 * bilinear;
      if (agreement > fallback_weight) {
        fallback_weight = agreement;
        fallback = texel;
      }
    }
  }
  return select(fallback, sum / weights, weights > 1e-4);
}

@compute @workgroup_size(PIXEL_TILE_X, PIXEL_TILE_Y)
fn hybrid_compose(@builtin(global_invocation_id) id: vec3u) {
  let pixel = id.xy;
  if (any(pixel >= view.image_size)) {
    return;
  }
  let index = pixel_index(pixel);
  var radiance = lit[index].rgb;
  let c = guide[index];
  if (params.use_gi != 0u && c.w >= 0.0) {
    radiance += diffuse_weight[index].rgb * upsampled_gi(pixel, c);
  }
  composed[index] = vec4f(radiance, 1.0);
}

// The history at a continuous image point (pixels), bilinear over the texels that lie inside.
fn history_at(point: vec2f) -> vec4f {
  let q = point - 0.5;
  let base = vec2i(floor(q));
  let f = q - floor(q);
  var sum = vec4f(0.0);
  var weights = 0.0;
  for (var dy = 0; dy <= 1; dy++) {
    for (var dx = 0; dx <= 1; dx++) {
      let t = base + vec2i(dx, dy);
      if (all(t >= vec2i(0)) && all(t < vec2i(view.image_size))) {
        let w = select(1.0 - f.x, f.x, dx == 1) * select(1.0 - f.y, f.y, dy == 1);
        sum += w * previous_history[pixel_index(vec2u(t))];
        weights += w;
      }
    }
  }
  return select(vec4f(0.0), sum / weights, weights > 1e-4);
}

@compute @workgroup_size(PIXEL_TILE_X, PIXEL_TILE_Y)
fn hybrid_taa(@builtin(global_invocation_id) id: vec3u) {
  let pixel = id.xy;
  if (any(pixel >= view.image_size)) {
    return;
  }
  let index = pixel_index(pixel);
  let current = composed[index].rgb;
  var result = current;
  var frames = 1.0;
  let m = motion[index];
  let inside = all(m.xy >= vec2f(0.0)) && all(m.xy < vec2f(view.image_size));
  if (params.use_history != 0u && params.min_blend < 1.0 && inside) {
    // The neighbourhood's box (in YCoCg, where it hugs the colours more tightly than in RGB).
    var lo = vec3f(1e30);
    var hi = vec3f(-1e30);
    for (var dy = -1; dy <= 1; dy++) {
      for (var dx = -1; dx <= 1; dx++) {
        let q = clamp(vec2i(pixel) + vec2i(dx, dy), vec2i(0), vec2i(view.image_size) - 1);
        let y = rgb_to_ycocg(composed[pixel_index(vec2u(q))].rgb);
        lo = min(lo, y);
        hi = max(hi, y);
      }
    }
    let previous = history_at(m.xy);
    if (previous.a > 0.0) {
      let clamped = ycocg_to_rgb(clamp(rgb_to_ycocg(previous.rgb), lo, hi));
      frames = previous.a + 1.0;
      let blend = max(1.0 / frames, params.min_blend);
      result = mix(clamped, current, blend);
    }
  }
  frames = min(frames, 1.0 / max(params.min_blend, 1e-3));
  history[index] = vec4f(result, frames);
  output[index] = vec4f(result, 1.0);
}
