// ReSTIR DI for the first bounce of the real-time frame (Bitterli et al. 2020), three passes over the
// whole image between the G-buffer (frame_gbuffer) and the frame path tracer, at the pixel-centre
// surfaces the G-buffer recorded (position rebuilt from the camera ray and linear depth, the stored
// shading normal):
//
//   restir_initial: RIS over `candidates` light samples (restir/reservoir restir_candidate, goal p̂)
//     → one shadow ray for the chosen point (visibility reuse: occluded, W = 0) → the frame scratch
//     (words 0 and 3, free until the path tracer writes its radiance).
//   restir_temporal: that reservoir combined with the previous frame's final reservoir at the
//     reprojected pixel (motion vector; rejected unless the previous surface has the same material,
//     a normal within ~25° and a depth within 10 %), its M capped at RESTIR_HISTORY_CAP batches →
//     back to the same scratch words.
//   restir_spatial: this pixel's reservoir and `neighbours` random ones within `radius` pixels that
//     pass the same geometric tests → the final reservoir, which the path tracer shades
//     (integrator/path, RESTIR) and the next frame reuses (the host copies it to
//     `previous_reservoirs` once the frame is finished, passes/restir-pass.ts).
//
// Unbiased combination (Bitterli et al., Algorithm 6, with visibility): W = Σ wᵢ / (Z · p̂(y)) with
// Z the M of the inputs that could have produced y, i.e. p̂ᵢ(y) > 0 and y visible from input i's
// surface (a shadow ray each). Every stored reservoir has W = 0 where its point is occluded from its
// own surface, so "could have produced" is exactly p̂ᵢ · Vᵢ > 0 and no input is counted wrongly.
// Expects the scene (group 0), the view (group 1); group 2: integrator/dispatch's parameters and ray
// counters, and the bindings below.

#import lib/workgroup
#import integrator/dispatch
#import denoise/gbuffer
#import restir/reservoir

// Batches (of a pixel's initial candidates) of history a reservoir may carry into the next frame:
// Bitterli et al. cap M at 20 × the current candidates so a stale history cannot dominate.
const RESTIR_HISTORY_CAP: u32 = 20u;
// The scratch words the initial, then temporal reservoir occupies between the passes (denoise/gbuffer FRAME_*):
// FRAME_RADIANCE is written later by the path tracer, word 3 by the denoiser's temporal pass.
// Geometric tests for reusing another pixel's reservoir (previous frame or neighbour).
const RESTIR_NORMAL_COS: f32 = 0.906;
const RESTIR_DEPTH_TOLERANCE: f32 = 0.1;

struct RestirParams {
  previous_camera: Camera,
  // Light samples per pixel per frame (the initial RIS).
  candidates: u32,
  // 1: the previous frame's reservoirs are valid (same image size, not reset).
  use_history: u32,
  // Spatial reuse: neighbours and the radius (pixels) they are drawn in.
  neighbours: u32,
  radius: f32,
}

@group(2) @binding(3) var<uniform> restir: RestirParams;
@group(2) @binding(4) var<storage, read_write> frame_scratch: array<u32>;
@group(2) @binding(5) var<storage, read> surface_records: array<SurfaceTexel>;
@group(2) @binding(6) var<storage, read> previous_surface_records: array<SurfaceTexel>;
// This frame's final reservoir per pixel, written by restir_spatial (the frame kernel reads it).
@group(2) @binding(7) var<storage, read_write> reservoirs: array<ReservoirTexel>;
// The last finished frame's final reservoirs, read (reprojected) by restir_temporal.
@group(2) @binding(8) var<storage, read> previous_reservoirs: array<ReservoirTexel>;

// A pixel-centre surface as the reservoirs see it.
struct ShadingPoint {
  position: vec3f,
  normal: vec3f,
  depth: f32,
  id: u32,
  valid: bool,
}

// The surface `record` holds for `pixel`, seen by camera c (its point: view/bindings pixel_centre_point).
fn surface_point(c: Camera, pixel: vec2u, record: SurfaceTexel) -> ShadingPoint {
  let s = unpack_surface(record);
  if (is_miss_depth(s.linear_depth)) {
    return ShadingPoint(vec3f(0.0), vec3f(0.0, 0.0, 1.0), MISS_DEPTH, NO_ID, false);
  }
  return ShadingPoint(pixel_centre_point(c, pixel, s.linear_depth), s.normal, s.linear_depth, s.id, true);
}

// This frame's surface at `pixel`, seen by the current camera.
fn pixel_surface(pixel: vec2u) -> ShadingPoint {
  return surface_point(view.camera, pixel, surface_records[image_index(pixel)]);
}

// Whether reservoirs are made and reused at `here`: a surface, and lights to draw from.
fn takes_reservoirs(here: ShadingPoint) -> bool {
  return here.valid && scene_light_count() > 0u;
}

// Whether a reservoir made at `other` may be reused at `here`.
fn similar(here: ShadingPoint, other: ShadingPoint, other_depth_seen: f32) -> bool {
  return other.valid && other.id == here.id && dot(here.normal, other.normal) > RESTIR_NORMAL_COS &&
    abs(other.depth - other_depth_seen) <= RESTIR_DEPTH_TOLERANCE * other.depth;
}

fn read_scratch_reservoir(pixel_index: u32) -> Reservoir {
  return unpack_reservoir(ReservoirTexel(frame_scratch[FRAME_WORDS * pixel_index + RESTIR_SCRATCH_A], frame_scratch[FRAME_WORDS * pixel_index + RESTIR_SCRATCH_B]));
}

fn write_scratch_reservoir(pixel_index: u32, r: Reservoir) {
  let t = pack_reservoir(r);
  frame_scratch[FRAME_WORDS * pixel_index + RESTIR_SCRATCH_A] = t.a;
  frame_scratch[FRAME_WORDS * pixel_index + RESTIR_SCRATCH_B] = t.b;
}

// A stream of its own per pixel, frame and pass (white noise: the Sobol dimensions belong to the paths).
fn restir_rng(pixel_index: u32, pass_salt: u32) -> Rng {
  return rng_seed(pixel_index, params.sample_index, params.seed ^ pass_salt);
}

@compute @workgroup_size(PIXEL_TILE_X, PIXEL_TILE_Y)
fn restir_initial(@builtin(global_invocation_id) id: vec3u, @builtin(local_invocation_index) local: u32) {
  begin_ray_count(local);
  let pixel = id.xy;
  if (all(pixel < view.image_size)) {
    let pixel_index = image_index(pixel);
    let here = pixel_surface(pixel);
    var out = empty_reservoir();
    var shadow_rays = 0u;
    if (takes_reservoirs(here)) {
      var rng = restir_rng(pixel_index, 0x7e3a1c55u);
      // Initial RIS: candidates weighed lum(L) cos θ / pdf (= p̂ / source density in any measure).
      var initial = empty_stream();
      let candidates = max(restir.candidates, 1u);
      for (var i = 0u; i < candidates; i++) {
        let point = restir_candidate(here.position, &rng);
        let v = view_light_point(point, here.position);
        let goal = restir_goal(v, here.normal);
        stream_offer(&initial, point, select(0.0, goal / (v.pdf * v.geometry), goal > 0.0), goal, 0u, 0u, rng_next_f32(&rng));
      }
      // One batch: W = (Σ w / candidates) / p̂(y).
      var w_current = select(0.0, initial.weight_sum / (f32(candidates) * initial.goal), initial.goal > 0.0);
      // Visibility reuse: an occluded choice keeps its M but contributes nothing.
      if (w_current > 0.0) {
        shadow_rays += 1u;
        if (!restir_visible(here.position, here.normal, here.depth, view_light_point(initial.point, here.position))) {
          w_current = 0.0;
        }
      }
      out = Reservoir(initial.point, w_current, 1u);
    }
    write_scratch_reservoir(pixel_index, out);
    count_rays(0u, shadow_rays);
  }
  end_ray_count(local);
}

// restir_temporal binds no ray counters (with them it would bind 11 storage buffers, one more than a
// browser gives a compute stage): it leaves its shadow-ray count in the high half of the pixel's
// previous-depth word (an f16 whose high half the G-buffer leaves 0 and nothing else reads), and
// restir_spatial counts it with its own.
fn pass_temporal_rays(pixel_index: u32, rays: u32) {
  let k = FRAME_WORDS * pixel_index + FRAME_PREVIOUS_DEPTH;
  frame_scratch[k] = (frame_scratch[k] & 0xffffu) | (rays << 16u);
}

fn temporal_rays(pixel_index: u32) -> u32 {
  return frame_scratch[FRAME_WORDS * pixel_index + FRAME_PREVIOUS_DEPTH] >> 16u;
}

@compute @workgroup_size(PIXEL_TILE_X, PIXEL_TILE_Y)
fn restir_temporal(@builtin(global_invocation_id) id: vec3u) {
  let pixel = id.xy;
  if (restir.use_history != 0u && all(pixel < view.image_size)) {
    let pixel_index = image_index(pixel);
    let here = pixel_surface(pixel);
    var shadow_rays = 0u;
    // Temporal reuse through the motion vector.
    let motion = unpack_motion(frame_scratch[FRAME_WORDS * pixel_index + FRAME_MOTION]);
    let previous_pixel = vec2i(floor(vec2f(pixel) + 0.5 + motion));
    if (takes_reservoirs(here) && !is_off_screen_motion(motion) && all(previous_pixel >= vec2i(0)) && all(previous_pixel < vec2i(view.image_size))) {
      let pp = vec2u(previous_pixel);
      let previous_index = image_index(pp);
      let there = surface_point(restir.previous_camera, pp, previous_surface_records[previous_index]);
      let depth_seen = unpack2x16float(frame_scratch[FRAME_WORDS * pixel_index + FRAME_PREVIOUS_DEPTH]).x;
      if (similar(here, there, depth_seen)) {
        var rng = restir_rng(pixel_index, 0x5d1f9a63u);
        let out = read_scratch_reservoir(pixel_index);
        let goal_out = restir_goal(view_light_point(out.point, here.position), here.normal);
        var history = unpack_reservoir(previous_reservoirs[previous_index]);
        history.m = min(history.m, RESTIR_HISTORY_CAP);
        var s = empty_stream();
        stream_offer(&s, out.point, goal_out * out.w * f32(out.m), goal_out, out.m, 0u, rng_next_f32(&rng));
        let v_history = view_light_point(history.point, here.position);
        let goal_history = restir_goal(v_history, here.normal);
        stream_offer(&s, history.point, goal_history * history.w * f32(history.m), goal_history, history.m, 1u, rng_next_f32(&rng));
        // Z: the chosen input counts (its W > 0 says y is visible from its surface); the other
        // counts where y has p̂ > 0 there and is visible from there. Chosen from the history and
        // not visible from here: W = 0 (every reservoir's points are visible from its surface).
        var other = there;
        if (s.chosen == 1u) {
          other = here;
        }
        var z = select(out.m, history.m, s.chosen == 1u);
        var keep = true;
        if (s.chosen != NOT_CHOSEN) {
          let v = view_light_point(s.point, other.position);
          if (restir_goal(v, other.normal) > 0.0) {
            shadow_rays += 1u;
            if (restir_visible(other.position, other.normal, other.depth, v)) {
              z += select(history.m, out.m, s.chosen == 1u);
            } else {
              keep = s.chosen == 0u;
            }
          } else {
            keep = s.chosen == 0u;
          }
        }
        let w = select(0.0, s.weight_sum / (f32(z) * s.goal), s.chosen != NOT_CHOSEN && z > 0u && s.goal > 0.0 && keep);
        write_scratch_reservoir(pixel_index, Reservoir(s.point, w, s.m));
      }
    }
    pass_temporal_rays(pixel_index, shadow_rays);
  }
}

// The largest number of neighbours restir_spatial takes (its arrays are this long).
const RESTIR_MAX_NEIGHBOURS: u32 = 8u;

@compute @workgroup_size(PIXEL_TILE_X, PIXEL_TILE_Y)
fn restir_spatial(@builtin(global_invocation_id) id: vec3u, @builtin(local_invocation_index) local: u32) {
  begin_ray_count(local);
  let pixel = id.xy;
  if (all(pixel < view.image_size)) {
    let pixel_index = image_index(pixel);
    let here = pixel_surface(pixel);
    var out = empty_reservoir();
    var shadow_rays = 0u;
    if (takes_reservoirs(here)) {
      var rng = restir_rng(pixel_index, 0x2c9b04e7u);
      let own = read_scratch_reservoir(pixel_index);
      var s = empty_stream();
      let v_own = view_light_point(own.point, here.position);
      let goal_own = restir_goal(v_own, here.normal);
      stream_offer(&s, own.point, goal_own * own.w * f32(own.m), goal_own, own.m, 0u, rng_next_f32(&rng));
      // The neighbours that passed the tests: their surfaces and M, for Z.
      var points: array<ShadingPoint, RESTIR_MAX_NEIGHBOURS>;
      var ms: array<u32, RESTIR_MAX_NEIGHBOURS>;
      var taken = 0u;
      let wanted = min(restir.neighbours, RESTIR_MAX_NEIGHBOURS);
      for (var i = 0u; i < wanted; i++) {
        let u = rng_next_2d(&rng);
        let r = restir.radius * sqrt(u.x);
        let offset = vec2i(round(r * vec2f(cos(2.0 * PI * u.y), sin(2.0 * PI * u.y))));
        let q = vec2i(pixel) + offset;
        if (all(offset == vec2i(0)) || any(q < vec2i(0)) || any(q >= vec2i(view.image_size))) {
          continue;
        }
        let qi = image_index(vec2u(q));
        let there = pixel_surface(vec2u(q));
        if (!similar(here, there, here.depth)) {
          continue;
        }
        let n = read_scratch_reservoir(qi);
        let v = view_light_point(n.point, here.position);
        let goal = restir_goal(v, here.normal);
        points[taken] = there;
        ms[taken] = n.m;
        taken += 1u;
        stream_offer(&s, n.point, goal * n.w * f32(n.m), goal, n.m, taken, rng_next_f32(&rng));
      }
      if (s.chosen != NOT_CHOSEN && s.goal > 0.0) {
        // Z over this pixel (index 0) and the neighbours taken (1 … taken), as in restir_temporal;
        // one loop, so the shadow ray is one call site.
        var z = 0u;
        var visible_here = true;
        for (var i = 0u; i <= taken; i++) {
          let m = select(own.m, ms[max(i, 1u) - 1u], i > 0u);
          if (s.chosen == i) {
            z += m;
            continue;
          }
          var there = here;
          if (i > 0u) {
            there = points[i - 1u];
          }
          let v = view_light_point(s.point, there.position);
          var counts = false;
          if (restir_goal(v, there.normal) > 0.0) {
            shadow_rays += 1u;
            counts = restir_visible(there.position, there.normal, there.depth, v);
          }
          if (counts) {
            z += m;
          } else if (i == 0u) {
            visible_here = false;
          }
        }
        let w = select(0.0, s.weight_sum / (f32(z) * s.goal), z > 0u && visible_here);
        out = Reservoir(s.point, w, s.m);
      } else {
        out = Reservoir(own.point, 0.0, s.m);
      }
    }
    reservoirs[pixel_index] = pack_reservoir(out);
    count_rays(0u, shadow_rays + temporal_rays(pixel_index));
  }
  end_ray_count(local);
}

// Lends the frame's final reservoirs to the path tracer in the frame scratch's words A and B (free again
// once restir_spatial has read its neighbours' there; the path tracer then writes its radiance over
// word A after reading them): path_trace_frame binds no buffer of its own for them, since a browser
// gives a compute stage 10 storage buffers and the path tracer's scene and records take them all.
@compute @workgroup_size(PIXEL_TILE_X, PIXEL_TILE_Y)
fn restir_lend(@builtin(global_invocation_id) id: vec3u) {
  if (all(id.xy < view.image_size)) {
    let pixel_index = image_index(id.xy);
    let t = reservoirs[pixel_index];
    frame_scratch[FRAME_WORDS * pixel_index + RESTIR_SCRATCH_A] = t.a;
    frame_scratch[FRAME_WORDS * pixel_index + RESTIR_SCRATCH_B] = t.b;
  }
}
