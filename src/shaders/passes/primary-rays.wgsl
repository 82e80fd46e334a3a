// Coherent primary rays through pixel centres, for the traversal benchmark (as tinybvh's speed test
// measures it). Expects the view (group 1); its output is group 2.

#import view/bindings

@group(2) @binding(0) var<storage, read_write> rays: array<Ray>;

@compute @workgroup_size(8, 8)
fn generate_primary_rays(@builtin(global_invocation_id) id: vec3u) {
  if (any(id.xy >= view.image_size)) {
    return;
  }
  rays[id.y * view.image_size.x + id.x] = camera_ray(vec2f(id.xy) + 0.5);
}
