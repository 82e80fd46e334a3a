// The wavefront path tracer's state: every live path's PathState (integrator/path) kept between
// kernels in structure-of-arrays form, its closest hit, the shadow rays its last bounce asked for,
// and the queues (extension queue ping-pong, two shadow queues) that the kernels fill by atomic
// compaction. Expects the scene (group 0) and view (group 1); the frame's records are integrator/frame's.
// Follows Laine, Karras and Aila 2013, "Megakernels Considered Harmful: Wavefront Path Tracing on GPUs".

#import lib/workgroup
#import integrator/frame
#import view/projection

// One path slot per pixel: slot = pixel index, so a path's state never moves, only its index does.
// `paths` holds PATH_FIELD_COUNT fields of one vec4u each, field-major (field f of slot s at
// f × slots + s), so the threads of a kernel read each field coalesced. Floats are stored as bits.
// The fields are declared here once, each numbered after the one before it: adding one is one line,
// and the count (and the host's byte count, through PathSlotFields) follows. Untyped (u32 from the
// literals): the reflection webgpu-utils bundles cannot evaluate `const X: u32 = Y + 1u`.
const F_ORIGIN = 0u;                              // xyz: the next ray's origin; w: last_bsdf_pdf
const F_DIRECTION = F_ORIGIN + 1u;                // xyz: the next ray's direction; w: cone_width
const F_THROUGHPUT = F_DIRECTION + 1u;            // the path's throughput, four channels
const F_RADIANCE = F_THROUGHPUT + 1u;             // radiance gathered so far, four channels
const F_ABSORPTION = F_RADIANCE + 1u;             // the medium's absorption coefficient, four channels (general materials only)
const F_PRIMARY_ALBEDO = F_ABSORPTION + 1u;       // xyz: PrimaryHit.albedo, w: its id (written at the first bounce only)
const F_PRIMARY_EMISSION = F_PRIMARY_ALBEDO + 1u; // xyz: PrimaryHit.emission (ditto); w: spectrum_u
const F_MISC = F_PRIMARY_EMISSION + 1u;           // x: rng_word of the random stream; y: flags (PATH_*) | bounce << PATH_BOUNCE_SHIFT; z: cone_spread; w: hit.instance
const F_HIT = F_MISC + 1u;                        // t, triangle, u, v of the closest hit of the ray
// Shadow queue q's entry k: fields F_SHADOWS + SHADOW_FIELDS × q + (0: origin.xyz, slot; 1:
// direction.xyz, t_max; 2: contribution), at index k (entries are compacted, not per slot). One
// queue per shadow slot the wavefront uses (integrator/path SHADOW_LIGHT, SHADOW_TORCH).
const F_SHADOWS = F_HIT + 1u;
const SHADOW_FIELDS = 3u;
const SHADOW_QUEUES = 2u;
// The pixel's sums over the frame's samples so far (xyz): demodulated radiance, first-hit albedo,
// kept first-hit emission (wavefront_finish; the frame's packed outputs are written after the last).
const F_SUM_ILLUMINATION = F_SHADOWS + SHADOW_FIELDS * SHADOW_QUEUES;
const F_SUM_ALBEDO = F_SUM_ILLUMINATION + 1u;
const F_SUM_EMISSION = F_SUM_ALBEDO + 1u;
const PATH_FIELD_COUNT = F_SUM_EMISSION + 1u;

// The fields of one slot as a struct, for the host's byte count (reflection); the kernels index `paths`.
struct PathSlotFields {
  fields: array<vec4u, PATH_FIELD_COUNT>,
}

const PATH_AFTER_DELTA: u32 = 1u;
const PATH_SECONDARY_ALIVE: u32 = 2u;
const PATH_BOUNCE_SHIFT: u32 = 8u;

// Queue counters (counters[...]): paths to extend this bounce, paths pushed for the next bounce,
// shadow rays toward a light sample and toward the torch (SHADOW_LIGHT, SHADOW_TORCH of
// integrator/path, offset by QUEUE_SHADOWS), and which half of `items` is the current queue.
const QUEUE_CURRENT: u32 = 0u;
const QUEUE_NEXT: u32 = 1u;
const QUEUE_SHADOWS: u32 = 2u;
const QUEUE_PARITY: u32 = 4u;

struct Queues {
  counters: array<atomic<u32>, 8>,
  // Two extension queues of slot indices, `slots` each: [parity × slots, …) is the current one.
  items: array<u32>,
}

// Which sample of the frame a generate or finish dispatch is (one uniform buffer per sample, written once).
struct WavefrontSample {
  sample: u32,
}

@group(2) @binding(7) var<storage, read_write> paths: array<vec4u>;
@group(2) @binding(8) var<storage, read_write> queues: Queues;
@group(2) @binding(9) var<uniform> wavefront: WavefrontSample;

// The most workgroups of a queue kernel put along x (the rest go along y); its threads per workgroup
// are lib/workgroup RAY_GROUP.
const MAX_GROUPS_X: u32 = 32768u;

fn slot_count() -> u32 {
  return view.image_size.x * view.image_size.y;
}

fn field(f: u32, slot: u32) -> u32 {
  return f * slot_count() + slot;
}

fn load_f(f: u32, slot: u32) -> vec4f {
  return bitcast<vec4f>(paths[field(f, slot)]);
}

fn store_f(f: u32, slot: u32, v: vec4f) {
  paths[field(f, slot)] = bitcast<vec4u>(v);
}

// The index into a queue of a thread of a 1D queue dispatch (groups spread over x and y).
fn queue_index(group: vec3u, groups: vec3u, local: u32) -> u32 {
  return (group.y * groups.x + group.x) * RAY_GROUP + local;
}

fn current_half() -> u32 {
  return atomicLoad(&queues.counters[QUEUE_PARITY]);
}

// Restores the spectral private state (lib/spectrum) of a path from its stored u and flags.
fn restore_spectrum(u: f32, flags: u32) {
  if (SPECTRAL) {
    spectrum_begin_path(u);
    path_secondary_alive = (flags & PATH_SECONDARY_ALIVE) != 0u;
  }
}

fn path_flags(state: PathState) -> u32 {
  var flags = select(0u, PATH_AFTER_DELTA, state.after_delta);
  if (!SPECTRAL || path_secondary_alive) {
    flags |= PATH_SECONDARY_ALIVE;
  }
  return flags;
}

fn path_bounce(misc: vec4u) -> u32 {
  return misc.y >> PATH_BOUNCE_SHIFT;
}

fn load_path(slot: u32, misc: vec4u) -> PathState {
  let origin = load_f(F_ORIGIN, slot);
  let direction = load_f(F_DIRECTION, slot);
  var u = 0.0;
  if (SPECTRAL) {
    u = load_f(F_PRIMARY_EMISSION, slot).w;
  }
  restore_spectrum(u, misc.y);
  // Only glass with a volume ever sets an absorption: other scenes neither store nor load it.
  var absorption = vec4f(0.0);
  if (SCENE_HAS_GENERAL_MATERIALS) {
    absorption = load_f(F_ABSORPTION, slot);
  }
  return PathState(
    load_f(F_RADIANCE, slot), load_f(F_THROUGHPUT, slot), absorption,
    Ray(origin.xyz, 0.0, direction.xyz, T_MISS), origin.w, (misc.y & PATH_AFTER_DELTA) != 0u,
    direction.w, bitcast<f32>(misc.z), u,
  );
}

// Stores a path's state; the primary hit (and spectrum_u beside it) where `with_primary` (generate,
// and shade at the first bounce: later bounces leave them as they are).
fn store_path(slot: u32, state: PathState, rng: Rng, bounce: u32, instance: u32, p: PrimaryHit, with_primary: bool) {
  store_f(F_ORIGIN, slot, vec4f(state.ray.origin, state.last_bsdf_pdf));
  store_f(F_DIRECTION, slot, vec4f(state.ray.direction, state.cone_width));
  store_f(F_THROUGHPUT, slot, state.throughput);
  store_f(F_RADIANCE, slot, state.radiance);
  if (SCENE_HAS_GENERAL_MATERIALS) {
    store_f(F_ABSORPTION, slot, state.absorption);
  }
  if (with_primary) {
    store_f(F_PRIMARY_ALBEDO, slot, vec4f(p.albedo, bitcast<f32>(p.id)));
    store_f(F_PRIMARY_EMISSION, slot, vec4f(p.emission, state.spectrum_u));
  }
  paths[field(F_MISC, slot)] = vec4u(rng_word(rng), path_flags(state) | (bounce << PATH_BOUNCE_SHIFT), bitcast<u32>(state.cone_spread), instance);
}

// Pushes onto queues with one global atomic per workgroup and queue: every thread calls
// push_begin first and push_commit after reserving, in uniform control flow; then a thread that
// reserved offset o in lane q writes entry push_bases[q] + o. Lane q counts on counters[q + 1]
// (lane 0: the next extension queue; 1, 2: the shadow queues).
const PUSH_LANES: u32 = 3u;
var<workgroup> push_counts: array<atomic<u32>, 3>;
var<workgroup> push_bases: array<u32, 3>;

fn push_begin(local: u32) {
  if (local < PUSH_LANES) {
    atomicStore(&push_counts[local], 0u);
  }
  workgroupBarrier();
}

fn push_reserve(lane: u32) -> u32 {
  return atomicAdd(&push_counts[lane], 1u);
}

fn push_commit(local: u32) {
  workgroupBarrier();
  if (local < PUSH_LANES) {
    let n = atomicLoad(&push_counts[local]);
    if (n > 0u) {
      push_bases[local] = atomicAdd(&queues.counters[local + 1u], n);
    }
  }
  workgroupBarrier();
}
