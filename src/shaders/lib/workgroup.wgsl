// The workgroup sizes of the kernels that run one invocation per pixel or per ray. They have no
// value here: TypeScript sets them (gpu/kernel-variants.ts WORKGROUP, passed into every pipeline
// whose module declares them by gpu/kernel.ts) and sizes each dispatch grid from the same numbers,
// so a kernel and its dispatch cannot disagree.
//   PIXEL_TILE_X × PIXEL_TILE_Y   the per-pixel passes (one invocation a pixel, tiles of the image)
//   RAY_GROUP                     the 1D passes over rays (trace-rays) and the wavefront's queues
override PIXEL_TILE_X: u32;
override PIXEL_TILE_Y: u32;
override RAY_GROUP: u32;
