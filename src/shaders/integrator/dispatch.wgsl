// What every path-tracing compute dispatch shares (the progressive kernel, the real-time frame's, the
// wavefront's, the hybrid's traced passes, ReSTIR's): the dispatch parameters (integrator/
// dispatch-params) and the exact ray counters with their per-workgroup reduction. Group 2, bindings 0
// and 2; the entry files add their own from binding 1 and 3 on. Expects the view (group 1).

#import integrator/dispatch-params

// 64-bit ray counters as (low, high) word pairs: a 4K image at a few thousand samples overflows 32 bits.
const COUNTER_EXTENSION_RAYS: u32 = 0u;
const COUNTER_SHADOW_RAYS: u32 = 2u;

// Words: extension rays (low, high), shadow rays (low, high).
@group(2) @binding(2) var<storage, read_write> ray_counters: array<atomic<u32>, 4>;

var<workgroup> workgroup_extension_rays: atomic<u32>;
var<workgroup> workgroup_shadow_rays: atomic<u32>;

// Adds n to the counter whose low word is ray_counters[low]; n < 2³², so at most one carry.
fn add_to_counter(low: u32, n: u32) {
  let before = atomicAdd(&ray_counters[low], n);
  if (before + n < before) {
    atomicAdd(&ray_counters[low + 1u], 1u);
  }
}

// Ray counting per workgroup (one global atomic per workgroup and counter): every invocation calls
// begin first and end last, in uniform control flow; count in between.
fn begin_ray_count(local: u32) {
  if (local == 0u) {
    atomicStore(&workgroup_extension_rays, 0u);
    atomicStore(&workgroup_shadow_rays, 0u);
  }
  workgroupBarrier();
}

fn count_rays(extension_rays: u32, shadow_rays: u32) {
  atomicAdd(&workgroup_extension_rays, extension_rays);
  atomicAdd(&workgroup_shadow_rays, shadow_rays);
}

fn end_ray_count(local: u32) {
  workgroupBarrier();
  if (local == 0u) {
    add_to_counter(COUNTER_EXTENSION_RAYS, atomicLoad(&workgroup_extension_rays));
    add_to_counter(COUNTER_SHADOW_RAYS, atomicLoad(&workgroup_shadow_rays));
  }
}
