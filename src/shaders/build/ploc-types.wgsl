// The data the PLOC build's kernels share (build/ploc clusters, build/emit writes the tree out):
// clusters, interior nodes, the loop's state on the GPU and the indirect dispatch slots.
// Expects build/common.
#import build/common
#import build/scan-sizes

// A cluster in the working list: its box, triangle count and SAH cost (area-weighted, not divided by
// the root's area).
struct Cluster {
  lo: vec3f,
  count: u32,
  hi: vec3f,
  cost: f32,
}

// An interior node of the clustered tree. Node ids below prim_count are triangles; id prim_count + k
// is nodes[k].
struct PlocNode {
  lo: vec3f,
  count: u32,
  hi: vec3f,
  cost: f32,
  left: u32,
  right: u32,
  // 1 where the subtree is cheaper as one leaf (count <= MAX_LEAF_SIZE).
  leaf: u32,
}

struct BuildState {
  // The number of clusters (build/scan's scan_length aliases this first word).
  cluster_count: u32,
  // Interior nodes made so far.
  node_count: atomic<u32>,
  // Iterations that merged something; level_end[i] = node_count after iteration i.
  iteration_count: u32,
  // Sibling pairs placed by build/emit.
  pair_count: atomic<u32>,
  // build/emit's walk down the iterations: the one being emitted and its node range.
  emit_level: u32,
  emit_start: u32,
  emit_end: u32,
}

struct PlocParams {
  prim_count: u32,
}

// Indirect dispatch sizes (x, y, z), by what they cover.
const ARGS_CLUSTERS: u32 = 0u;
const ARGS_SCAN_BLOCKS: u32 = 3u;
const ARGS_SINGLE: u32 = 6u;
const ARGS_EMIT: u32 = 9u;
// At most this many clusters (one per thread of a workgroup), ploc_tail finishes the clustering in
// one workgroup instead of a handful of dispatches per iteration.
const TAIL_CLUSTERS: u32 = 256u;

