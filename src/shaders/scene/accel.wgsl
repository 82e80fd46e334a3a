// Which structure the static world is traced through: one enum override (scene-pack features
// .staticAccel, setting `accel`; the host sets it per scene, gpu/kernel-variants.ts). Every
// structure stays packed beside the binary BVH, so a pipeline compiled for ACCEL_BVH2 still traces
// any scene correctly. scene/bvh dispatches on it (scene/grid, scene/wide: scene/bvh4, scene/cwbvh);
// the unrolled traversal of a small frozen scene (scene/traversal-unrolled) has none of them.

const ACCEL_BVH2: u32 = 0u;
const ACCEL_BVH4: u32 = 1u;
const ACCEL_CWBVH: u32 = 2u;
const ACCEL_GRID: u32 = 3u;
override STATIC_ACCEL: u32 = ACCEL_BVH2;
