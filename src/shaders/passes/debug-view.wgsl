// Debug views, first half: one primary ray through each pixel centre (no jitter, so the result is
// deterministic), traced by scene/bvh's own trace_closest compiled with its work counters
// (BVH_COUNT_WORK), so the heat map counts exactly what the path tracer's traversal does and what
// the CPU oracle bvh/traverse.ts counts. Writes one vec4f of raw values per pixel (the EXR of
// `lantern render --debug`) and the image's maximum of the view's scalar; passes/debug-compose
// colours them. Expects the scene (group 0) and view (group 1); its own inputs and outputs are group 2.
// With a thin lens the rays are still the chief rays through the lens centre (view/bindings camera_ray):
// debug views show the scene sharp, as the wireframe's pinhole projection does.
//
// debug_values per view (w = 1 where the ray hit a triangle, 0 where it missed):
//   heat-nodes      (nodes visited, triangles tested, 0, hit)
//   heat-triangles  (triangles tested, nodes visited, 0, hit)
//   leaf-size       (triangles in the leaf hit, 0, 0, hit)
//   bvh-depth       (depth of the leaf hit, root = 0, 0, 0, hit)
//   normals         (unit shading normal, world space, hit)
//   albedo          (linear albedo at the hit, hit)
//   barycentrics    (weights of v0, v1, v2, hit)
//   triangle-id     (source triangle index or -1, 0, 0, hit)
//   wireframe       (|cos| between the normal and the ray, 0, 0, hit): the shaded backdrop of the lines

#import lib/workgroup
#import lib/debug-views
#import scene/bvh
#import scene/surface
#import scene/materials
#import view/bindings

struct DebugViewParams {
  // One of the DEBUG_VIEW_* constants of lib/debug-views.
  view_kind: u32,
}

@group(2) @binding(0) var<uniform> params: DebugViewParams;
// Depth of every BVH node (root = 0), from bvh/depths.ts.
@group(2) @binding(1) var<storage, read> node_depths: array<u32>;
@group(2) @binding(2) var<storage, read_write> debug_values: array<vec4f>;
// [0]: the image's maximum of the view's scalar (scalar views only), rounded down to a whole number.
@group(2) @binding(3) var<storage, read_write> debug_range: array<atomic<u32>, 2>;

fn debug_value(kind: u32, ray: Ray, hit: Hit) -> vec4f {
  let work = bvh_work;
  let hit_flag = select(0.0, 1.0, hit.triangle != NO_TRIANGLE);
  if (kind == DEBUG_VIEW_HEAT_NODES) {
    return vec4f(f32(work.nodes_visited), f32(work.triangles_tested), 0.0, hit_flag);
  }
  if (kind == DEBUG_VIEW_HEAT_TRIANGLES) {
    return vec4f(f32(work.triangles_tested), f32(work.nodes_visited), 0.0, hit_flag);
  }
  if (hit.triangle == NO_TRIANGLE) {
    return select(vec4f(0.0), vec4f(-1.0, 0.0, 0.0, 0.0), kind == DEBUG_VIEW_TRIANGLE_ID);
  }
  switch kind {
    case DEBUG_VIEW_LEAF_SIZE: {
      return vec4f(f32(scene_bvh_node(work.hit_leaf).tri_count), 0.0, 0.0, 1.0);
    }
    case DEBUG_VIEW_BVH_DEPTH: {
      return vec4f(f32(node_depths[work.hit_leaf]), 0.0, 0.0, 1.0);
    }
    case DEBUG_VIEW_TRIANGLE_ID: {
      return vec4f(f32(world_shading(hit.instance, hit.triangle).source_index), 0.0, 0.0, 1.0);
    }
    case DEBUG_VIEW_BARYCENTRICS: {
      return vec4f(1.0 - hit.u - hit.v, hit.u, hit.v, 1.0);
    }
    default: {}
  }
  let surface = surface_at(hit, ray);
  switch kind {
    case DEBUG_VIEW_NORMALS: {
      return vec4f(surface.shading_normal, 1.0);
    }
    case DEBUG_VIEW_ALBEDO: {
      return vec4f(material_albedo(scene_material(surface.material), surface.uv).rgb, 1.0);
    }
    default: {
      return vec4f(abs(dot(surface.shading_normal, ray.direction)), 0.0, 0.0, 1.0);
    }
  }
}

@compute @workgroup_size(PIXEL_TILE_X, PIXEL_TILE_Y)
fn debug_view(@builtin(global_invocation_id) id: vec3u) {
  if (any(id.xy >= view.image_size)) {
    return;
  }
  let ray = camera_ray(vec2f(id.xy) + vec2f(0.5));
  let hit = trace_closest(ray);
  let value = debug_value(params.view_kind, ray, hit);
  debug_values[id.y * view.image_size.x + id.x] = value;
  if (is_scalar_debug_view(params.view_kind)) {
    atomicMax(&debug_range[0], u32(value.x));
  }
}
