// The real-time frame: `samples` jittered paths per pixel (trace_path of passes/path-trace, compiled
// with CAPTURE_PRIMARY), written — not added — as the frame's demodulated radiance, plus the
// G-buffer: the surface through the pixel centre (one extra primary ray, so that depth, normal and
// id do not flicker with the jitter and the temporal tests stay stable while the camera is still),
// reprojected into the previous camera. With a thin lens the samples start on the aperture while the
// G-buffer keeps the chief ray through the lens centre: motion vectors and the edge-stopping guide
// stay those of one defined surface, and defocus is a spread of the samples that temporal
// accumulation averages like any other noise (docs/denoise.md, "Depth of field"). Each sample's emission seen at its first hit is kept apart
// (it needs no filtering) and the rest is divided by its first-hit albedo, so textures and lights are
// not blurred by the spatial filter (Schied et al. 2017, "Spatiotemporal Variance-Guided Filtering", §4).
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
// The à-trous filter's edge-stopping guide, apart from the 64-byte G-buffer records so that its 25
// taps per pixel read 16 bytes each: xyz = normal, w = linear depth (as in GBufferTexel).
@group(2) @binding(6) var<storage, read_write> guide: array<vec4f>;

// The G-buffer record of the surface through the pixel centre (albedo and emission are filled in from the samples).
fn centre_texel(pixel: vec2u) -> GBufferTexel {
  let ray = camera_ray(vec2f(pixel) + 0.5);
  let hit = trace_closest(ray);
  if (hit.triangle == NO_TRIANGLE) {
    let previous = project_offset(frame.previous_camera, view.image_size, ray.direction);
    let position = select(vec2f(OFF_SCREEN), previous.xy, previous.z > 0.0);
    return GBufferTexel(-ray.direction, MISS_DEPTH, vec3f(1.0), NO_ID, vec3f(0.0), MISS_DEPTH, position);
  }
  let surface = surface_at(hit, ray);
  let normal = select(surface.shading_normal, -surface.shading_normal, dot(surface.shading_normal, ray.direction) > 0.0);
  // Where the point was: moved with its instance, seen by the previous camera.
  let previous = project_point(frame.previous_camera, view.image_size, previous_world_point(hit.instance, surface.position));
  let position = select(vec2f(OFF_SCREEN), previous.xy, previous.z > 0.0);
  let depth = dot(surface.position - view.camera.position, view.camera.forward);
  return GBufferTexel(normal, depth, vec3f(1.0), surface.material, vec3f(0.0), previous.z, position);
}

@compute @workgroup_size(8, 8)
fn path_trace_frame(@builtin(global_invocation_id) id: vec3u, @builtin(local_invocation_index) local: u32) {
  begin_ray_count(local);

  let pixel = params.tile_origin + id.xy;
  if (all(id.xy < params.tile_size) && all(pixel < view.image_size)) {
    let pixel_index = pixel.y * view.image_size.x + pixel.x;
    var rng = rng_seed(pixel_index, params.sample_index, params.seed);
    var illumination = vec3f(0.0);
    var albedo = vec3f(0.0);
    var emission = vec3f(0.0);
    // The pixel-centre ray of the G-buffer counts as one more extension ray.
    var extension_rays = 1u;
    var shadow_rays = 0u;
    for (var s = 0u; s < params.samples; s++) {
      primary = PrimaryHit(vec3f(1.0), vec3f(0.0));
      let image_point = vec2f(pixel) + rng_next_2d(&rng);
      let path = trace_path(camera_sample_ray(image_point, &rng), &rng, path_settings());
      let radiance = select(vec3f(0.0), path.radiance, is_finite_vec3(path.radiance));
      let emitted = select(vec3f(0.0), primary.emission, is_finite_vec3(primary.emission));
      illumination += max(radiance - emitted, vec3f(0.0)) / demodulation(primary.albedo);
      albedo += primary.albedo;
      emission += emitted;
      extension_rays += path.extension_rays;
      shadow_rays += path.shadow_rays;
    }
    let inv = 1.0 / f32(params.samples);
    var texel = centre_texel(pixel);
    texel.albedo = albedo * inv;
    texel.emission = emission * inv;
    frame_radiance[pixel_index] = vec4f(illumination * inv, 1.0);
    gbuffer[pixel_index] = texel;
    guide[pixel_index] = vec4f(texel.normal, texel.linear_depth);
    count_rays(extension_rays, shadow_rays);
  }
  // The same ray counters as the progressive kernel, so the viewer's rays per second stay honest.
  end_ray_count(local);
}
