// What every BVH build kernel shares: the box type, half areas and the sentinel for "no cluster".
// Expects nothing. The builder follows Meister & Bittner 2018, "Parallel Locally-Ordered Clustering
// for BVH Construction" (PLOC); gpu/build/gpu-bvh-builder.ts drives it.

// An axis-aligned box in world space (scene units).
struct Aabb {
  lo: vec3f,
  hi: vec3f,
}

// Marks a cluster slot emptied by a merge, and a node the output has not placed yet.
const NONE: u32 = 0xffffffffu;

fn box_union(a: Aabb, b: Aabb) -> Aabb {
  return Aabb(min(a.lo, b.lo), max(a.hi, b.hi));
}

// Half the surface area: the SAH's measure (CPU: bvh/box-area.ts), 0 for an empty box.
fn half_area(lo: vec3f, hi: vec3f) -> f32 {
  let d = max(hi - lo, vec3f(0.0));
  return d.x * d.y + d.y * d.z + d.z * d.x;
}
