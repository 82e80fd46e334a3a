// The real-time frame: `samples` jittered paths per pixel (trace_path of passes/path-trace, compiled
// with CAPTURE_PRIMARY), written — not added — as the frame's demodulated radiance, plus the
// G-buffer of the first sample's first hit, reprojected into the previous camera for the temporal
// pass. Demodulation divides each sample by its own first-hit albedo, so textures are not blurred by
// the spatial filter (Schied et al. 2017, "Spatiotemporal Variance-Guided Filtering", §4).
// Expects the scene (group 0) and view (group 1); group 2 adds the previous camera and the outputs.

#import passes/path-trace
#import view/projection
#import denoise/gbuffer

struct FrameParams {
  // The camera of the previous frame (equal to view.camera for a still camera).
  previous_camera: Camera,
}

@group(2) @binding(3) var<uniform> frame: FrameParams;
// Per pixel: rgb = the frame's mean demodulated radiance; a = 1.
@group(2) @binding(4) var<storage, read_write> frame_radiance: array<vec4f>;
@group(2) @binding(5) var<storage, read_write> gbuffer: array<GBufferTexel>;

fn miss_texel(direction: vec3f) -> GBufferTexel {
  let previous = project_offset(frame.previous_camera, view.image_size, direction);
  let position = select(vec2f(OFF_SCREEN), previous.xy, previous.z > 0.0);
  return GBufferTexel(-direction, MISS_DEPTH, vec3f(1.0), NO_ID, position, MISS_DEPTH);
}

fn hit_texel(h: PrimaryHit) -> GBufferTexel {
  let previous = project_point(frame.previous_camera, view.image_size, h.position);
  let position = select(vec2f(OFF_SCREEN), previous.xy, previous.z > 0.0);
  let depth = dot(h.position - view.camera.position, view.camera.forward);
  return GBufferTexel(h.normal, depth, h.albedo, h.material, position, previous.z);
}

@compute @workgroup_size(8, 8)
fn path_trace_frame(@builtin(global_invocation_id) id: vec3u) {
  let pixel = params.tile_origin + id.xy;
  if (any(id.xy >= params.tile_size) || any(pixel >= view.image_size)) {
    return;
  }
  let pixel_index = pixel.y * view.image_size.x + pixel.x;
  var rng = rng_seed(pixel_index, params.sample_index, params.seed);
  var illumination = vec3f(0.0);
  var albedo = vec3f(0.0);
  var texel: GBufferTexel;
  for (var s = 0u; s < params.samples; s++) {
    let ray = camera_ray(vec2f(pixel) + rng_next_2d(&rng));
    primary.hit = false;
    primary.albedo = vec3f(1.0);
    let path = trace_path(ray, &rng);
    let radiance = select(vec3f(0.0), path.radiance, is_finite_vec3(path.radiance));
    illumination += radiance / demodulation(primary.albedo);
    albedo += primary.albedo;
    if (s == 0u) {
      if (primary.hit) {
        texel = hit_texel(primary);
      } else {
        texel = miss_texel(ray.direction);
      }
    }
  }
  let inv = 1.0 / f32(params.samples);
  texel.albedo = albedo * inv;
  frame_radiance[pixel_index] = vec4f(illumination * inv, 1.0);
  gbuffer[pixel_index] = texel;
}
