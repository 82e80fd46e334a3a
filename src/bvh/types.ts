/**
 * The flat BVH the builder produces and the GPU packer and the CPU oracle consume.
 *
 * Layout (structure of arrays, one slot per node):
 * - Node 0 is the root.
 * - Slot 1 is never used: children are allocated in pairs starting at slot 2, so every sibling pair
 *   (2,3), (4,5), ... starts at an even index and two 32-byte GPU nodes share one 64-byte block.
 *   Slot 1 holds an inverted (empty) but finite box, triCount 0 and leftFirst 0.
 * - Siblings are adjacent: the right child of an interior node is always leftFirst + 1.
 * Every node's box is the exact union of its triangles' boxes (float32 values, no padding).
 */

export interface BvhBuildOptions {
  /** Centroid bins per axis for the binned SAH (>= 2). */
  readonly bins: number;
  /** SAH cost of visiting an interior node (Ct). */
  readonly traversalCost: number;
  /** SAH cost of one ray/triangle test (Ci). */
  readonly intersectionCost: number;
  /** Leaves with more triangles than this are always split when the input allows it. */
  readonly maxLeafSize: number;
  /** A node at this depth (root = 0) becomes a leaf whatever its size. */
  readonly maxDepth: number;
}

export interface BvhBuildStats {
  /** Wall-clock build time in milliseconds. */
  readonly buildMs: number;
  /** Nodes in the tree, excluding the unused slot 1 (so `Bvh.nodeCount - 1`). */
  readonly nodeCount: number;
  readonly leafCount: number;
  /** Depth of the deepest node; the root has depth 0. */
  readonly maxDepth: number;
  /** Mean depth over leaves (each leaf counts once, whatever its size). */
  readonly meanLeafDepth: number;
  /**
   * Σ_interior (A_node/A_root)·Ct + Σ_leaves (A_node/A_root)·count·Ci, A = surface area. When the
   * root box has zero area (all triangles on one line or point) every ratio is taken as 1.
   */
  readonly sahCost: number;
  readonly triangleCount: number;
  /** Worker threads that built it (build-parallel.ts); absent when it was built on the calling thread alone. */
  readonly workers?: number;
}

export interface Bvh {
  /** Number of node slots used (including the unused slot 1, see above). Always >= 2. */
  readonly nodeCount: number;
  /** 6 floats per node: min xyz, max xyz (world space). */
  readonly bounds: Float32Array;
  /** Interior node: index of its left child; the right child is leftFirst+1. Leaf: index of its first entry in triIndices. */
  readonly leftFirst: Uint32Array;
  /** 0 for an interior node, the number of triangles (>= 1) for a leaf. */
  readonly triCount: Uint32Array;
  /** Leaf order -> source triangle index. A permutation of 0..n-1. */
  readonly triIndices: Uint32Array;
  readonly stats: BvhBuildStats;
}
