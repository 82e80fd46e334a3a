// The selected object's highlight, drawn over the image that is shown (never into the estimate):
// selection_mask traces one pixel-centre primary ray per pixel with scene/bvh.wgsl's own
// trace_closest (alpha tests included) and marks the pixels whose first hit is the selection: the
// part of one instance made of one material (what the material panel edits there); selection_outline copies the shown image, tinted inside the object and with an outline
// around it. Expects the scene (group 0, the mask only) and the view (group 1); its own inputs and
// outputs are group 2.

#import lib/workgroup
#import scene/bvh
#import view/bindings

// Outline width in pixels (a pixel outside the object within this distance of it is drawn).
const OUTLINE_RADIUS: i32 = 1;
// How strongly the object's own pixels are tinted toward the outline colour.
const INSIDE_TINT: f32 = 0.12;

struct SelectionParams {
  // The selected object's source triangles (scene/triangles.ts order): first <= index < end.
  first: u32,
  end: u32,
  // Index into materials: only the instance's triangles of this material are selected.
  material: u32,
  // sRGB-encoded outline colour.
  color: vec3f,
}

@group(2) @binding(0) var<uniform> params: SelectionParams;
// One word per pixel, row-major: 1 where the pixel's primary ray hits the selected object.
@group(2) @binding(1) var<storage, read_write> mask: array<u32>;
// The tone-mapped (or debug) image that is shown, sRGB-encoded.
@group(2) @binding(2) var image: texture_2d<f32>;
@group(2) @binding(3) var output: texture_storage_2d<rgba8unorm, write>;

@compute @workgroup_size(PIXEL_TILE_X, PIXEL_TILE_Y)
fn selection_mask(@builtin(global_invocation_id) id: vec3u) {
  if (any(id.xy >= view.image_size)) {
    return;
  }
  let hit = trace_closest(camera_ray(vec2f(id.xy) + 0.5));
  var selected = 0u;
  if (hit.triangle != NO_TRIANGLE) {
    let shading = world_shading(hit.instance, hit.triangle);
    let source = shading.source_index;
    selected = select(0u, 1u, source >= params.first && source < params.end && shading.material == params.material);
  }
  mask[id.y * view.image_size.x + id.x] = selected;
}

fn masked(p: vec2i) -> bool {
  let size = vec2i(view.image_size);
  if (any(p < vec2i(0)) || any(p >= size)) {
    return false;
  }
  return mask[u32(p.y) * view.image_size.x + u32(p.x)] != 0u;
}

@compute @workgroup_size(PIXEL_TILE_X, PIXEL_TILE_Y)
fn selection_outline(@builtin(global_invocation_id) id: vec3u) {
  if (any(id.xy >= view.image_size)) {
    return;
  }
  let p = vec2i(id.xy);
  var color = textureLoad(image, id.xy, 0).rgb;
  if (masked(p)) {
    color = mix(color, params.color, INSIDE_TINT);
  } else {
    var near = false;
    for (var dy = -OUTLINE_RADIUS; dy <= OUTLINE_RADIUS; dy++) {
      for (var dx = -OUTLINE_RADIUS; dx <= OUTLINE_RADIUS; dx++) {
        near = near || masked(p + vec2i(dx, dy));
      }
    }
    if (near) {
      color = params.color;
    }
  }
  textureStore(output, id.xy, vec4f(color, 1.0));
}
