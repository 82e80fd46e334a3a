// Debug views, second half: colours passes/debug-view's raw values (scalar views through the colour
// scale of renderer/debug-legend.ts, the same stops the legend shows) and the wireframe lines of
// passes/bvh-wireframe, and composes the result with the tone-mapped image: instead of it, beside it
// (two panes, each the whole frame at half size) or over it. Colours are sRGB-encoded throughout,
// as the image is. Expects the view (group 1) for the image size; its own inputs and outputs are group 2.

#import lib/workgroup
#import lib/debug-views
#import lib/color
#import lib/random
#import view/bindings

// Entries of the colour scale (renderer/debug-legend.ts COLOR_SCALE_STOPS has as many).
const COLOR_SCALE_STOP_COUNT: u32 = 9u;
// How strongly a debug view covers the image in the overlay layout (wireframe lines cover fully).
const OVERLAY_OPACITY: f32 = 0.6;
// Where a surface view's ray hit nothing.
const MISS_COLOR: vec3f = vec3f(0.05, 0.05, 0.05);

struct DebugComposeParams {
  // One of the DEBUG_VIEW_* constants of lib/debug-views.
  view_kind: u32,
  // One of the DEBUG_LAYOUT_* constants.
  composition: u32,
  // Scalar views: the value at the top of the colour scale; 0 takes the image's maximum (debug_range).
  scale_max: f32,
  // sRGB-encoded colours at evenly spaced positions 0, 1/(n-1), ..., 1 of the scale.
  scale_stops: array<vec4f, COLOR_SCALE_STOP_COUNT>,
}

@group(2) @binding(0) var<uniform> params: DebugComposeParams;
@group(2) @binding(1) var<storage, read> debug_values: array<vec4f>;
@group(2) @binding(2) var<storage, read> debug_range: array<u32, 2>;
// The tone-mapped image (sRGB-encoded).
@group(2) @binding(3) var image: texture_2d<f32>;
// The wireframe lines; alpha 1 where a line was drawn.
@group(2) @binding(4) var wireframe: texture_2d<f32>;
@group(2) @binding(5) var output: texture_storage_2d<rgba8unorm, write>;

fn color_scale(t: f32) -> vec3f {
  let x = clamp(t, 0.0, 1.0) * f32(COLOR_SCALE_STOP_COUNT - 1u);
  let i = min(u32(x), COLOR_SCALE_STOP_COUNT - 2u);
  return mix(params.scale_stops[i].rgb, params.scale_stops[i + 1u].rgb, x - f32(i));
}

// A stable, well spread colour per triangle index.
fn id_color(id: u32) -> vec3f {
  let h = pcg_hash(id);
  return 0.2 + 0.8 * vec3f(f32(h & 255u), f32((h >> 8u) & 255u), f32((h >> 16u) & 255u)) / 255.0;
}

// The debug view's colour at a pixel (sRGB-encoded) and how much of the image it covers (alpha).
fn debug_color(pixel: vec2u) -> vec4f {
  let v = debug_values[pixel.y * view.image_size.x + pixel.x];
  let hit = v.w > 0.5;
  let kind = params.view_kind;
  if (kind == DEBUG_VIEW_HEAT_NODES || kind == DEBUG_VIEW_HEAT_TRIANGLES) {
    let top = select(params.scale_max, max(f32(debug_range[0]), 1.0), params.scale_max <= 0.0);
    return vec4f(color_scale(v.x / top), 1.0);
  }
  if (kind == DEBUG_VIEW_WIREFRAME) {
    let backdrop = select(MISS_COLOR, vec3f(0.1 + 0.45 * v.x), hit);
    let line = textureLoad(wireframe, pixel, 0);
    return vec4f(mix(backdrop, line.rgb, line.a), line.a);
  }
  if (!hit) {
    return vec4f(MISS_COLOR, 0.0);
  }
  switch kind {
    case DEBUG_VIEW_LEAF_SIZE, DEBUG_VIEW_BVH_DEPTH: {
      return vec4f(color_scale(v.x / max(params.scale_max, 1.0)), 1.0);
    }
    case DEBUG_VIEW_NORMALS: {
      return vec4f(0.5 * v.xyz + 0.5, 1.0);
    }
    case DEBUG_VIEW_ALBEDO: {
      return vec4f(linear_to_srgb(clamp(v.rgb, vec3f(0.0), vec3f(1.0))), 1.0);
    }
    case DEBUG_VIEW_TRIANGLE_ID: {
      return vec4f(id_color(u32(v.x)), 1.0);
    }
    default: {
      return vec4f(clamp(v.rgb, vec3f(0.0), vec3f(1.0)), 1.0);
    }
  }
}

fn image_color(pixel: vec2u) -> vec3f {
  return textureLoad(image, pixel, 0).rgb;
}

// One pane of the side-by-side layout at `local` (pane pixels): the whole frame at half size, a 2×2
// box filter, centred vertically.
fn pane_color(local: vec2i, debug: bool) -> vec3f {
  let size = vec2i(view.image_size);
  let top = (size.y - size.y / 2) / 2;
  let source = 2 * vec2i(local.x, local.y - top);
  if (source.y < 0 || source.y >= size.y) {
    return vec3f(0.0);
  }
  var sum = vec3f(0.0);
  for (var k = 0; k < 4; k++) {
    let p = vec2u(min(source + vec2i(k & 1, k >> 1u), size - 1));
    sum += select(image_color(p), debug_color(p).rgb, debug);
  }
  return 0.25 * sum;
}

@compute @workgroup_size(PIXEL_TILE_X, PIXEL_TILE_Y)
fn debug_compose(@builtin(global_invocation_id) id: vec3u) {
  if (any(id.xy >= view.image_size)) {
    return;
  }
  // if/else rather than switch: wgsl_reflect finds the resources a function uses only outside switches.
  var color = vec3f(0.0);
  if (params.composition == DEBUG_LAYOUT_SIDE_BY_SIDE) {
    let pane_width = i32(view.image_size.x / 2u);
    let x = i32(id.x);
    if (x < 2 * pane_width) {
      color = pane_color(vec2i(x % pane_width, i32(id.y)), x >= pane_width);
    }
  } else if (params.composition == DEBUG_LAYOUT_OVERLAY) {
    let d = debug_color(id.xy);
    let opacity = select(OVERLAY_OPACITY, 1.0, params.view_kind == DEBUG_VIEW_WIREFRAME);
    color = mix(image_color(id.xy), d.rgb, d.a * opacity);
  } else {
    color = debug_color(id.xy).rgb;
  }
  textureStore(output, id.xy, vec4f(color, 1.0));
}
