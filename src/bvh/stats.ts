/**
 * Statistics of a built BVH, recomputed from its arrays (so they also check the builder's own
 * numbers), and their short human-readable form for `lantern info`.
 */
import { halfAreaAt } from './box-area.ts';
import type { Bvh } from './types.ts';

/** Bytes of one GPU node (BvhNode in shaders/scene/types.wgsl: two vec3f + two u32). */
export const BVH_NODE_BYTES = 32;

export interface BvhStatsOptions {
  /** SAH traversal cost Ct (default 1, the builder's default). */
  readonly traversalCost?: number;
  /** SAH intersection cost Ci (default 1, the builder's default). */
  readonly intersectionCost?: number;
  /** GPU bytes per triangle to add to the node memory (default 0: nodes only). */
  readonly triangleBytes?: number;
  /** Bytes of one node (default BVH_NODE_BYTES, the layout the GPU traverses). */
  readonly nodeBytes?: number;
}

export interface BvhStats {
  readonly triangleCount: number;
  /** Nodes in the tree, excluding the unused slot 1. */
  readonly nodeCount: number;
  readonly leafCount: number;
  /** Depth of the deepest node; the root has depth 0. */
  readonly maxDepth: number;
  /** Mean depth over leaves (each leaf counts once). */
  readonly meanLeafDepth: number;
  /** leafSizeHistogram[k] = number of leaves holding k triangles (index 0 is always 0). */
  readonly leafSizeHistogram: readonly number[];
  readonly meanLeafSize: number;
  /** Same definition as BvhBuildStats.sahCost. */
  readonly sahCost: number;
  /** Node buffer size: every slot (unused slot 1 included) × options.nodeBytes. */
  readonly nodeBytes: number;
  /** triangleCount × options.triangleBytes. */
  readonly triangleBytes: number;
  /** (nodeBytes + triangleBytes) / triangleCount. */
  readonly bytesPerTriangle: number;
  /** From the build (not recomputable). */
  readonly buildMs: number;
}

export function bvhStats(bvh: Bvh, options: BvhStatsOptions = {}): BvhStats {
  const Ct = options.traversalCost ?? 1, Ci = options.intersectionCost ?? 1;
  const { bounds, leftFirst, triCount } = bvh;
  const histogram: number[] = [0];
  let nodeCount = 0, leafCount = 0, maxDepth = 0, leafDepthSum = 0, triangles = 0;
  let sahWeighted = 0, sahUnweighted = 0;
  // Explicit (node, depth) stack in the builder's depth-first order, left subtree first.
  const stack: number[] = [0, 0];
  while (stack.length > 0) {
    const depth = stack.pop()!, node = stack.pop()!;
    if (node >= bvh.nodeCount || node === 1) throw new Error(`BVH node ${node} is referenced but lies outside the tree`);
    nodeCount++;
    if (depth > maxDepth) maxDepth = depth;
    const area = halfAreaAt(bounds, node);
    const count = triCount[node]!;
    if (count > 0) {
      leafCount++;
      leafDepthSum += depth;
      triangles += count;
      while (histogram.length <= count) histogram.push(0);
      histogram[count]!++;
      sahWeighted += area * count * Ci;
      sahUnweighted += count * Ci;
    } else {
      sahWeighted += area * Ct;
      sahUnweighted += Ct;
      stack.push(leftFirst[node]! + 1, depth + 1, leftFirst[node]!, depth + 1);
    }
  }
  const rootArea = halfAreaAt(bounds, 0);
  const triangleCount = bvh.triIndices.length;
  const nodeBytes = bvh.nodeCount * (options.nodeBytes ?? BVH_NODE_BYTES);
  const triangleBytes = triangleCount * (options.triangleBytes ?? 0);
  return {
    triangleCount,
    nodeCount,
    leafCount,
    maxDepth,
    meanLeafDepth: leafDepthSum / leafCount,
    leafSizeHistogram: histogram,
    meanLeafSize: triangles / leafCount,
    sahCost: rootArea > 0 ? sahWeighted / rootArea : sahUnweighted,
    nodeBytes,
    triangleBytes,
    bytesPerTriangle: (nodeBytes + triangleBytes) / triangleCount,
    buildMs: bvh.stats.buildMs,
  };
}

const int = (x: number): string => x.toLocaleString('en-US');
const mib = (bytes: number): string => `${(bytes / (1024 * 1024)).toFixed(1)} MiB`;

/**
 * A few lines for `lantern info`, e.g.
 *   BVH: 958,957 nodes, 479,479 leaves, depth 26 (mean leaf depth 19.4), SAH cost 49.17
 *   leaf sizes: 1:160,416 2:279,196 ... (mean 1.82)
 *   node memory: 29.3 MiB (35.2 bytes/triangle); built in 1,140 ms
 */
export function formatBvhStats(bvh: Bvh, options: BvhStatsOptions = {}, stats?: BvhStats): string {
  const s = stats ?? bvhStats(bvh, options);
  const shown = 8;
  const sizes = s.leafSizeHistogram.slice(1, shown + 1).map((n, i) => `${i + 1}:${int(n)}`);
  const larger = s.leafSizeHistogram.slice(shown + 1).reduce((a, b) => a + b, 0);
  if (larger > 0) sizes.push(`>${shown}:${int(larger)}`);
  const memoryLabel = s.triangleBytes > 0 ? 'memory (nodes + triangles)' : 'node memory';
  return [
    `BVH: ${int(s.nodeCount)} nodes, ${int(s.leafCount)} leaves, depth ${s.maxDepth} (mean leaf depth ${s.meanLeafDepth.toFixed(1)}), SAH cost ${s.sahCost.toFixed(2)}`,
    `  leaf sizes: ${sizes.join(' ')} (mean ${s.meanLeafSize.toFixed(2)})`,
    `  ${memoryLabel}: ${mib(s.nodeBytes + s.triangleBytes)} (${s.bytesPerTriangle.toFixed(1)} bytes/triangle); built in ${int(Math.round(s.buildMs))} ms`,
  ].join('\n');
}

/** Length of the diagonal of the root box: the scene's size, for scales and speeds (0 for an empty box). */
export function boundsDiagonal(bvh: Pick<Bvh, 'bounds'>): number {
  const b = bvh.bounds;
  return Math.hypot(b[3]! - b[0]!, b[4]! - b[1]!, b[5]! - b[2]!) || 0;
}
