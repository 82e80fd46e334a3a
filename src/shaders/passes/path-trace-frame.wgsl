// The real-time frame: `samples` jittered paths per pixel (integrator/path's trace_path, whose record
// hands back each path's first hit), written — not added — as the frame's demodulated radiance, plus the
// G-buffer: the surface through the pixel centre (one extra primary ray, so that depth, normal and
// id do not flicker with the jitter and the temporal tests stay stable while the camera is still),
// reprojected into the previous camera. With a thin lens the samples start on the aperture while the
// G-buffer keeps the chief ray through the lens centre: motion vectors and the edge-stopping guide
// stay those of one defined surface, and defocus is a spread of the samples that temporal
// accumulation averages like any other noise (docs/denoise.md, "Depth of field"). Each sample's emission seen at its first hit is kept apart
// (it needs no filtering) and the rest is divided by its first-hit albedo, so textures and lights are
// not blurred by the spatial filter (Schied et al. 2017, "Spatiotemporal Variance-Guided Filtering", §4).
// On and around emitters a sample's first-hit emission is replaced by the pixel's box-filtered
// emission (pixel_emission, traced on a sub-pixel grid): lamp textures and lamp edges are then steady
// from the first frame; elsewhere a silhouette sample's emission joins the illumination, which the
// temporal pass accumulates, where the pixel stands still, and stays apart where it moves
// (split_sample).
// With ReSTIR on (frame.restir), restir/restir runs over the whole image between the two entries and
// each path's first bounce shades the pixel's final reservoir, handed to it in the path's record
// (integrator/path; this kernel is compiled with RESTIR). The records and the sample split are
// integrator/frame's, which the wavefront shares.
// Expects the scene (group 0) and view (group 1); group 2 adds the previous camera and the outputs.

#import lib/workgroup
#import integrator/frame
#import view/projection

// The pixel's reservoir and the centre surface it was made for (integrator/path's PathRecord.restir).
fn restir_pixel_at(pixel: vec2u, pixel_index: u32) -> RestirPixel {
  let s = unpack_surface(surface_records[pixel_index]);
  if (frame.restir == 0u || is_miss_depth(s.linear_depth)) {
    return NO_RESTIR_PIXEL;
  }
  let r = unpack_reservoir(ReservoirTexel(frame_scratch[FRAME_WORDS * pixel_index + RESTIR_SCRATCH_A], frame_scratch[FRAME_WORDS * pixel_index + RESTIR_SCRATCH_B]));
  // Placed as restir/restir's surface_point places it: through the pixel centre at the stored depth.
  let position = pixel_centre_point(view.camera, pixel, s.linear_depth);
  return RestirPixel(true, r.point, r.w, position, s.normal, s.linear_depth, s.id);
}

// The surface through the pixel centre and where it was in the previous frame.
struct CentreTexel {
  surface: SurfaceTexel,
  // Previous image position − pixel centre, pixels; on_screen false: behind the previous camera.
  motion: vec2f,
  on_screen: bool,
  // Linear depth seen from the previous camera (MISS_DEPTH for a miss).
  previous_depth: f32,
}

// Sub-pixel points over which pixel_emission averages what emits in the pixel: a (0,4,2)-net in base 2
// (Hammersley's 16 points, x = k/16 and y = k's four bits reversed / 16), so that every row and every
// column of 16 strata of the pixel holds one point, moved each frame by a random toroidal shift
// (Cranley-Patterson rotation) that keeps this. Each point is then uniform over the pixel, so the
// measured coverage of a lamp's edge is unbiased in any one frame, and an axis-aligned edge is
// measured to within 1/16 of the pixel (a fixed 4 × 4 grid measured it in steps of 1/4 with a bias
// of up to 1/8 that no number of frames removed: the Cornell light's bottom edge row read 30 % low,
// issue #27). An edge whose covered part is a whole number of sixteenths reads exactly that in every frame.
const EMISSION_POINTS: u32 = 16u;

fn emission_point(k: u32, shift: vec2f) -> vec2f {
  let y = ((k & 1u) << 3u) | ((k & 2u) << 1u) | ((k & 4u) >> 1u) | ((k & 8u) >> 3u);
  return fract(vec2f(f32(k), f32(y)) / f32(EMISSION_POINTS) + shift);
}

// The frame's shift of the pixel's net: a hash of the pixel, the frame's first sample and the seed.
fn emission_shift(pixel: vec2u) -> vec2f {
  let h = pcg_hash(image_index(pixel) ^ pcg_hash(params.sample_index ^ pcg_hash(params.seed ^ 0x9e3779b9u)));
  return vec2f(f32(h & 0xffffu), f32(h >> 16u)) / 65536.0;
}

// Rays pixel_emission traced for this thread's pixel (counted with the G-buffer's).
var<private> emission_rays: u32 = 0u;

// Whether a material emits at all (its emission factor; a texture only modulates it). The centre
// records' id is the material's index.
fn material_emits(id: u32) -> bool {
  return id != NO_ID && any(scene_material(id).emission > vec3f(0.0));
}

// Whether the centre of the pixel or of a neighbour (3×3) is on an emitting material (this frame's
// records: the centres pass covers the tile and a pixel around it).
fn near_emitter(pixel: vec2u) -> bool {
  let lo = max(vec2i(pixel) - 1, vec2i(0));
  let hi = min(vec2i(pixel) + 1, vec2i(view.image_size) - 1);
  for (var y = lo.y; y <= hi.y; y++) {
    for (var x = lo.x; x <= hi.x; x++) {
      if (material_emits(surface_records[u32(y) * view.image_size.x + u32(x)].id)) {
        return true;
      }
    }
  }
  return false;
}

// The first-hit emission of the pixel: the mean over the EMISSION_POINTS points of the pixel of the
// emission each point's own ray meets (0 where it meets nothing that emits toward the camera), so a
// lamp texture is box-filtered over the pixel's footprint as the converged image averages it, and a
// lamp's edge covers the pixel by the fraction it really covers. Traced only where the centre or a
// centre next to it (3×3) is on an emitting material: the lamps and the ring of pixels around them,
// whose samples then leave their own first-hit emission out (split_sample), so that the part kept
// apart from the filters is steady from frame to frame. Elsewhere it is 0 and the samples' own
// emission counts. (The Cornell light's rim pixels flipped between the whole light and the ceiling
// with each sample before the grid; with the ring's emission in the temporally accumulated
// illumination instead, moving the camera carried the light off the lamp's edge, see split_sample.)
fn pixel_emission(pixel: vec2u) -> u32 {
  if (!near_emitter(pixel)) {
    return pack_grid_emission(false, vec3f(0.0));
  }
  var sum = vec3f(0.0);
  let shift = emission_shift(pixel);
  for (var k = 0u; k < EMISSION_POINTS; k++) {
    let r = camera_ray(vec2f(pixel) + emission_point(k, shift));
    let h = trace_closest(r);
    emission_rays += 1u;
    if (h.triangle == NO_TRIANGLE) {
      continue;
    }
    let s = surface_at(h, r);
    let material = scene_material(s.material);
    if (!(emitter_cosine(material, -dot(s.geometric_normal, r.direction)) > 0.0)) {
      continue;
    }
    // The points do the filtering: read level 0.
    texture_lod = -1e30;
    sum += material_emission(material, s.uv, r.direction);
  }
  return pack_grid_emission(true, sum / f32(EMISSION_POINTS));
}

fn centre_texel(pixel: vec2u) -> CentreTexel {
  let ray = camera_ray(vec2f(pixel) + 0.5);
  let hit = trace_closest(ray);
  if (hit.triangle == NO_TRIANGLE) {
    let previous = project_offset(frame.previous_camera, view.image_size, ray.direction);
    return CentreTexel(pack_surface(-ray.direction, MISS_DEPTH, NO_ID), previous.xy - (vec2f(pixel) + 0.5), previous.z > 0.0, MISS_DEPTH);
  }
  let surface = surface_at(hit, ray);
  let normal = select(surface.shading_normal, -surface.shading_normal, dot(surface.shading_normal, ray.direction) > 0.0);
  // Where the point was: moved with its instance, seen by the previous camera.
  let previous = project_point(frame.previous_camera, view.image_size, previous_world_point(hit.instance, surface.position));
  let depth = dot(surface.position - view.camera.position, view.camera.forward);
  return CentreTexel(pack_surface(normal, depth, surface.material), previous.xy - (vec2f(pixel) + 0.5), previous.z > 0.0, previous.z);
}

// Writes the centre's records: the surface and the motion words.
fn write_centre(pixel_index: u32, c: CentreTexel) {
  surface_records[pixel_index] = c.surface;
  frame_scratch[FRAME_WORDS * pixel_index + FRAME_MOTION] = pack_motion(c.motion, c.on_screen);
  frame_scratch[FRAME_WORDS * pixel_index + FRAME_PREVIOUS_DEPTH] = pack_f16_pair(c.previous_depth, 0.0);
}

// The G-buffer of the surface through each pixel centre, a pass of its own before the paths (albedo
// and emission come from the samples; the record keeps pixel_emission for them meanwhile), dispatched
// twice: the centres (emission_pass 0, over the tile and a pixel around it, so that the second pass
// finds every neighbour's record of this frame; a record written twice is the same), then the pixel
// emission (emission_pass 1, over the tile). Apart, this ray's traversal and surface evaluation are
// not compiled into the path kernel a second time: measured on the H200 (E1M1, 1080p), the frame
// took 10.9 ms with them inside and 7.7 ms without (docs/perf.md). One entry point for both passes:
// one pipeline to compile.
@compute @workgroup_size(PIXEL_TILE_X, PIXEL_TILE_Y)
fn frame_gbuffer(@builtin(global_invocation_id) id: vec3u, @builtin(local_invocation_index) local: u32) {
  begin_ray_count(local);
  let pixel = tile_pixel(id);
  if (shades_tile_pixel(id)) {
    let pixel_index = image_index(pixel);
    if (frame.emission_pass == 0u) {
      write_centre(pixel_index, centre_texel(pixel));
      // The pixel-centre ray counts as an extension ray.
      count_rays(select(0u, 1u, all(pixel >= frame.core_min) && all(pixel < frame.core_max)), 0u);
    } else {
      frame_records[pixel_index].emission = pixel_emission(pixel);
      // So do the emission grid's rays.
      count_rays(emission_rays, 0u);
    }
  }
  end_ray_count(local);
}

@compute @workgroup_size(PIXEL_TILE_X, PIXEL_TILE_Y)
fn path_trace_frame(@builtin(global_invocation_id) id: vec3u, @builtin(local_invocation_index) local: u32) {
  begin_ray_count(local);

  let pixel = tile_pixel(id);
  if (shades_tile_pixel(id)) {
    let pixel_index = image_index(pixel);
    let centre_id = surface_records[pixel_index].id;
    // pixel_emission, left in the frame record by the G-buffer's emission pass.
    let grid = unpack_grid_emission(frame_records[pixel_index].emission);
    let still = pixel_still(pixel_index);
    let demodulate = pixel_demodulation(pixel_index);
    var illumination = vec3f(0.0);
    var albedo = vec3f(0.0);
    var emission = vec3f(0.0);
    var extension_rays = 0u;
    var shadow_rays = 0u;
    var restir_pixel = NO_RESTIR_PIXEL;
    if (RESTIR) {
      restir_pixel = restir_pixel_at(pixel, pixel_index);
    }
    for (var s = 0u; s < params.samples; s++) {
      var record = path_record(restir_pixel);
      // One stream per sample: a Sobol stream is one sample of its pixel's sequence.
      var rng = sampler_seed(params.sampler, pixel, view.image_size, params.sample_index + s, params.seed);
      let image_point = vec2f(pixel) + rng_next_2d(&rng);
      let path = trace_path(camera_sample_ray(image_point, &rng), &rng, path_settings(), &record);
      let primary = record.primary;
      let radiance = select(vec3f(0.0), path.radiance, is_finite_vec3(path.radiance));
      let emitted = select(vec3f(0.0), primary.emission, is_finite_vec3(primary.emission));
      let split = split_sample(primary, radiance, emitted, centre_id, grid, still, sample_factor(demodulate, primary));
      illumination += split.illumination;
      albedo += primary.albedo;
      emission += split.emission;
      extension_rays += path.extension_rays;
      shadow_rays += path.shadow_rays;
    }
    let inv = 1.0 / f32(params.samples);
    frame_scratch[FRAME_WORDS * pixel_index + FRAME_RADIANCE] = pack_rgb9e5(illumination * inv);
    frame_records[pixel_index] = FrameTexel(pack_rgb9e5(remodulation_albedo(demodulate, albedo * inv)), pack_rgb9e5(emission * inv));
    count_rays(extension_rays, shadow_rays);
  }
  // The same ray counters as the progressive kernel, so the viewer's rays per second stay honest.
  end_ray_count(local);
}
