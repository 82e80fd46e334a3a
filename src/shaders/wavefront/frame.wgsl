// The real-time frame traced as a wavefront: the estimator of passes/path-trace-frame (trace_path
// and its record's first hit, demodulated radiance, albedo and emission) split into kernels over
// queues of live paths instead of one thread following each path to its end. Per sample:
//
//   generate (a camera path per pixel, its camera ray traced at once in 8 × 8 pixel tiles → the queue)
//   per bounce: queue_args (the queue to extend now, its indirect dispatch) → extend (trace_closest;
//     from the second bounce on)
//     → shade (path_step: emission, MIS, a light and a torch sample whose shadow rays the record
//       hands back → the shadow queues, the BSDF sample → the next extension queue, Russian roulette)
//     → shadow_args → shadow_light, shadow_torch (trace_any; the unoccluded add their contribution)
//   finish (the sample's sums; after the last sample, the frame's radiance, albedo and emission)
//
// The pixel-centre G-buffer is traced before, by path-trace-frame's frame_gbuffer.
//
// Each path draws its random numbers in trace_path's order and adds its radiance in the same order,
// so the frame equals the megakernel's up to float rounding (tests/gpu/wavefront.test.ts).
// Expects the scene (group 0) and view (group 1); group 2 adds wavefront/paths' state to the frame's.

#import lib/workgroup
#import wavefront/paths

// The indirect dispatch arguments (x, y, z workgroups): [0, 3) the extension queue (extend, shade),
// [3, 6) light shadow rays, [6, 9) torch shadow rays. Written by the *_args kernels only (a buffer bound
// as storage cannot be the indirect buffer of the same dispatch).
const ARGS_EXTEND: u32 = 0u;
const ARGS_SHADOWS: u32 = 3u;
@group(2) @binding(10) var<storage, read_write> indirect_args: array<u32, 9>;

fn write_args(at: u32, n: u32) {
  let groups = (n + RAY_GROUP - 1u) / RAY_GROUP;
  let x = min(groups, MAX_GROUPS_X);
  indirect_args[at] = x;
  indirect_args[at + 1u] = select(0u, (groups + x - 1u) / max(x, 1u), x > 0u);
  indirect_args[at + 2u] = 1u;
}

// The random stream of this sample of a pixel, seeded as the megakernel seeds it; the path state keeps
// one word of it (rng_word) for shade to resume from.
fn sample_stream(pixel: vec2u) -> Rng {
  return sampler_seed(params.sampler, pixel, view.image_size, params.sample_index + wavefront.sample, params.seed);
}

// A camera path per pixel, with the random stream of its sample (as the megakernel seeds it). The camera ray is traced here, in pixel tiles as
// coherent as the megakernel's (one extend dispatch less per sample).
@compute @workgroup_size(PIXEL_TILE_X, PIXEL_TILE_Y)
fn wavefront_generate(@builtin(global_invocation_id) id: vec3u, @builtin(local_invocation_index) local: u32) {
  push_begin(local);
  var offset = 0u;
  var pushed = false;
  let slot = id.y * view.image_size.x + id.x;
  if (all(id.xy < view.image_size)) {
    var rng = sample_stream(id.xy);
    let image_point = vec2f(id.xy) + rng_next_2d(&rng);
    let state = path_begin(camera_sample_ray(image_point, &rng), &rng, path_settings());
    let hit = trace_closest(state.ray);
    store_path(slot, state, rng, 0u, hit.instance, PrimaryHit(vec3f(1.0), vec3f(0.0), NO_PRIMARY_ID), true);
    store_hit(slot, hit);
    offset = push_reserve(0u);
    pushed = true;
  }
  push_commit(local);
  if (pushed) {
    queues.items[(1u - current_half()) * slot_count() + push_bases[0] + offset] = slot;
  }
}

// The paths pushed last become the queue to extend; the next queue and the shadow queues empty.
@compute @workgroup_size(1)
fn wavefront_queue_args() {
  let n = atomicLoad(&queues.counters[QUEUE_NEXT]);
  atomicStore(&queues.counters[QUEUE_CURRENT], n);
  atomicStore(&queues.counters[QUEUE_NEXT], 0u);
  atomicStore(&queues.counters[QUEUE_SHADOWS + SHADOW_LIGHT], 0u);
  atomicStore(&queues.counters[QUEUE_SHADOWS + SHADOW_TORCH], 0u);
  atomicStore(&queues.counters[QUEUE_PARITY], 1u - atomicLoad(&queues.counters[QUEUE_PARITY]));
  write_args(ARGS_EXTEND, n);
  add_to_counter(COUNTER_EXTENSION_RAYS, n);
}

@compute @workgroup_size(RAY_GROUP)
fn wavefront_extend(@builtin(workgroup_id) group: vec3u, @builtin(num_workgroups) groups: vec3u, @builtin(local_invocation_index) local: u32) {
  let i = queue_index(group, groups, local);
  if (i >= atomicLoad(&queues.counters[QUEUE_CURRENT])) {
    return;
  }
  let slot = queues.items[current_half() * slot_count() + i];
  let origin = load_f(F_ORIGIN, slot);
  let direction = load_f(F_DIRECTION, slot);
  let hit = trace_closest(Ray(origin.xyz, 0.0, direction.xyz, T_MISS));
  store_hit(slot, hit);
  paths[field(F_MISC, slot)].w = hit.instance;
}

fn store_hit(slot: u32, hit: Hit) {
  paths[field(F_HIT, slot)] = vec4u(bitcast<u32>(hit.t), hit.triangle, bitcast<u32>(hit.u), bitcast<u32>(hit.v));
}

// Shadow entry k of queue q: the ray, the slot it belongs to, its contribution.
fn store_shadow(q: u32, k: u32, slot: u32, request: ShadowRequest) {
  let base = F_SHADOWS + SHADOW_FIELDS * q;
  store_f(base, k, vec4f(request.ray.origin, bitcast<f32>(slot)));
  store_f(base + 1u, k, vec4f(request.ray.direction, request.ray.t_max));
  store_f(base + 2u, k, request.contribution);
}

@compute @workgroup_size(RAY_GROUP)
fn wavefront_shade(@builtin(workgroup_id) group: vec3u, @builtin(num_workgroups) groups: vec3u, @builtin(local_invocation_index) local: u32) {
  push_begin(local);
  let i = queue_index(group, groups, local);
  var slot = 0u;
  // Lanes this thread pushes onto (bit q: lane q) and its offsets there.
  var lanes = 0u;
  var offsets = vec3u(0u);
  // The record path_step hands back: the first hit (kept at bounce 0) and, collected instead of
  // traced, the shadow rays, which go to the shadow queues.
  var record = path_record_collecting();
  if (i < atomicLoad(&queues.counters[QUEUE_CURRENT])) {
    slot = queues.items[current_half() * slot_count() + i];
    let misc = paths[field(F_MISC, slot)];
    let h = paths[field(F_HIT, slot)];
    let hit = Hit(bitcast<f32>(h.x), h.y, bitcast<f32>(h.z), bitcast<f32>(h.w), misc.w);
    let bounce = path_bounce(misc);
    var rng = rng_resume(sample_stream(vec2u(slot % view.image_size.x, slot / view.image_size.x)), misc.x);
    var state = load_path(slot, misc);
    var result = PathResult(vec3f(0.0), 0u, 0u);
    let goes_on = path_step(&state, &record, hit, bounce, &rng, path_settings(), &result);
    store_path(slot, state, rng, bounce + 1u, misc.w, record.primary, bounce == 0u);
    if (goes_on) {
      offsets.x = push_reserve(0u);
      lanes |= 1u;
    }
    if ((record.shadow_mask & (1u << SHADOW_LIGHT)) != 0u) {
      offsets.y = push_reserve(1u + SHADOW_LIGHT);
      lanes |= 2u;
    }
    if ((record.shadow_mask & (1u << SHADOW_TORCH)) != 0u) {
      offsets.z = push_reserve(1u + SHADOW_TORCH);
      lanes |= 4u;
    }
  }
  push_commit(local);
  if ((lanes & 1u) != 0u) {
    queues.items[(1u - current_half()) * slot_count() + push_bases[0] + offsets.x] = slot;
  }
  if ((lanes & 2u) != 0u) {
    store_shadow(SHADOW_LIGHT, push_bases[1u + SHADOW_LIGHT] + offsets.y, slot, record.shadows[SHADOW_LIGHT]);
  }
  if ((lanes & 4u) != 0u) {
    store_shadow(SHADOW_TORCH, push_bases[1u + SHADOW_TORCH] + offsets.z, slot, record.shadows[SHADOW_TORCH]);
  }
}

@compute @workgroup_size(1)
fn wavefront_shadow_args() {
  let light = atomicLoad(&queues.counters[QUEUE_SHADOWS + SHADOW_LIGHT]);
  let torch = atomicLoad(&queues.counters[QUEUE_SHADOWS + SHADOW_TORCH]);
  write_args(ARGS_SHADOWS + 3u * SHADOW_LIGHT, light);
  write_args(ARGS_SHADOWS + 3u * SHADOW_TORCH, torch);
  add_to_counter(COUNTER_SHADOW_RAYS, light + torch);
}

// Traces shadow entry i of queue q and adds its contribution to its path's radiance if unoccluded.
// The light and torch queues are separate dispatches: a path may have one entry in each, and its
// radiance is added to without atomics, in trace_path's order (light, then torch).
fn trace_shadow(q: u32, i: u32) {
  if (i >= atomicLoad(&queues.counters[QUEUE_SHADOWS + q])) {
    return;
  }
  let base = F_SHADOWS + SHADOW_FIELDS * q;
  let a = load_f(base, i);
  let b = load_f(base + 1u, i);
  if (!trace_any(Ray(a.xyz, 0.0, b.xyz, b.w))) {
    let slot = bitcast<u32>(a.w);
    store_f(F_RADIANCE, slot, load_f(F_RADIANCE, slot) + load_f(base + 2u, i));
  }
}

@compute @workgroup_size(RAY_GROUP)
fn wavefront_shadow_light(@builtin(workgroup_id) group: vec3u, @builtin(num_workgroups) groups: vec3u, @builtin(local_invocation_index) local: u32) {
  trace_shadow(SHADOW_LIGHT, queue_index(group, groups, local));
}

@compute @workgroup_size(RAY_GROUP)
fn wavefront_shadow_torch(@builtin(workgroup_id) group: vec3u, @builtin(num_workgroups) groups: vec3u, @builtin(local_invocation_index) local: u32) {
  trace_shadow(SHADOW_TORCH, queue_index(group, groups, local));
}

// One sample's path done: its demodulated radiance, albedo and kept emission are added to the
// pixel's sums (path fields F_SUM_*); after the last sample the means are packed into the frame's
// records exactly as path_trace_frame packs them. The pixel-centre surface and its filtered emission
// were written before the samples by path-trace-frame's frame_gbuffer (the same kernel as the megakernel's).
@compute @workgroup_size(PIXEL_TILE_X, PIXEL_TILE_Y)
fn wavefront_finish(@builtin(global_invocation_id) id: vec3u) {
  if (any(id.xy >= view.image_size)) {
    return;
  }
  let pixel = id.xy;
  let slot = pixel.y * view.image_size.x + pixel.x;
  let misc = paths[field(F_MISC, slot)];
  let albedo_id = load_f(F_PRIMARY_ALBEDO, slot);
  let emission_u = load_f(F_PRIMARY_EMISSION, slot);
  restore_spectrum(emission_u.w, misc.y);
  let path_radiance = channels_to_rgb(load_f(F_RADIANCE, slot));
  let radiance = select(vec3f(0.0), path_radiance, is_finite_vec3(path_radiance));
  let emitted = select(vec3f(0.0), emission_u.xyz, is_finite_vec3(emission_u.xyz));
  let p = PrimaryHit(albedo_id.xyz, emitted, bitcast<u32>(albedo_id.w));
  let grid = unpack_grid_emission(frame_records[slot].emission);
  let demodulate = pixel_demodulation(slot);
  let split = split_sample(p, radiance, emitted, surface_records[slot].id, grid, pixel_still(slot), sample_factor(demodulate, p));
  var illumination = split.illumination;
  var albedo = p.albedo;
  var emission = split.emission;
  if (wavefront.sample > 0u) {
    illumination = load_f(F_SUM_ILLUMINATION, slot).xyz + illumination;
    albedo = load_f(F_SUM_ALBEDO, slot).xyz + albedo;
    emission = load_f(F_SUM_EMISSION, slot).xyz + emission;
  }
  if (wavefront.sample + 1u < params.samples) {
    store_f(F_SUM_ILLUMINATION, slot, vec4f(illumination, 0.0));
    store_f(F_SUM_ALBEDO, slot, vec4f(albedo, 0.0));
    store_f(F_SUM_EMISSION, slot, vec4f(emission, 0.0));
    return;
  }
  let inv = 1.0 / f32(params.samples);
  frame_scratch[FRAME_WORDS * slot + FRAME_RADIANCE] = pack_rgb9e5(illumination * inv);
  frame_records[slot] = FrameTexel(pack_rgb9e5(remodulation_albedo(demodulate, albedo * inv)), pack_rgb9e5(emission * inv));
}
