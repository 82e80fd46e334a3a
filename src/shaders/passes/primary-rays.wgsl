// Coherent primary rays through pixel centres, for the traversal benchmark; with a thin lens each
// pixel's ray leaves its own random point of the aperture (as the path tracer's do), so they are
// less coherent. The rays are stored in the order the benchmark traces them, a workgroup of
// trace-rays at a time: by the per-pixel passes' tiles (tinybvh's speed test: one workgroup per 8 × 8
// tile; gpu/kernel-variants.ts keeps RAY_GROUP = PIXEL_TILE_X × PIXEL_TILE_Y) or by image rows.
// Expects the view (group 1); its parameters and output are group 2.

#import lib/workgroup
#import view/bindings

// Ray orders: the host's names live in renderer/benchmark.ts.
const RAY_ORDER_TILES: u32 = 0u;
const RAY_ORDER_SCANLINE: u32 = 1u;

struct PrimaryRaysParams {
  order: u32,
}

@group(2) @binding(0) var<storage, read_write> rays: array<Ray>;
@group(2) @binding(1) var<uniform> params: PrimaryRaysParams;

// Where pixel p's ray goes. Tiles: tile after tile, row-major within each, every pixel once: a tile
// row of height h holds 8·W pixels above it, tiles left of it hold 8·h each, and a tile of width w
// (narrower at the right edge) holds its own row-major.
fn ray_slot(p: vec2u, size: vec2u) -> u32 {
  if (params.order == RAY_ORDER_SCANLINE) {
    return p.y * size.x + p.x;
  }
  let t = vec2u(PIXEL_TILE_X, PIXEL_TILE_Y);
  let tile = p / t;
  let tile_size = min(t, size - tile * t);
  let local = p % t;
  return tile.y * t.y * size.x + tile.x * t.x * tile_size.y + local.y * tile_size.x + local.x;
}

@compute @workgroup_size(PIXEL_TILE_X, PIXEL_TILE_Y)
fn generate_primary_rays(@builtin(global_invocation_id) id: vec3u) {
  if (any(id.xy >= view.image_size)) {
    return;
  }
  let pixel_index = id.y * view.image_size.x + id.x;
  var rng = rng_seed(pixel_index, 0u, 0u);
  rays[ray_slot(id.xy, view.image_size)] = camera_sample_ray(vec2f(id.xy) + 0.5, &rng);
}
