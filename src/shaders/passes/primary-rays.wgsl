// Coherent primary rays through pixel centres, for the traversal benchmark (as tinybvh's speed test
// measures it); with a thin lens each pixel's ray leaves its own random point of the aperture (as
// the path tracer's do), so they are less coherent. Expects the view (group 1); its output is group 2.

#import view/bindings

@group(2) @binding(0) var<storage, read_write> rays: array<Ray>;

@compute @workgroup_size(8, 8)
fn generate_primary_rays(@builtin(global_invocation_id) id: vec3u) {
  if (any(id.xy >= view.image_size)) {
    return;
  }
  let pixel_index = id.y * view.image_size.x + id.x;
  var rng = rng_seed(pixel_index, 0u, 0u);
  rays[pixel_index] = camera_sample_ray(vec2f(id.xy) + 0.5, &rng);
}
