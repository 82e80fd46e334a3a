/**
 * The BVH layouts Lantern can build, each with what `lantern bvh-stats` needs to compare them: a
 * name, what it is, the bytes of one node, a builder and its statistics. A new layout is one more
 * entry here, and the statistics, the command and its tests pick it up. The wide layouts (bvh/wide.ts)
 * are collapsed from the binary tree: `build` gives that tree and `stats` measures the wide one.
 */
import { buildBvh, DEFAULT_BVH_BUILD_OPTIONS } from './build.ts';
import { BVH_NODE_BYTES, bvhStats, type BvhStats, type BvhStatsOptions } from './stats.ts';
import type { Bvh, BvhBuildOptions } from './types.ts';
import { BVH4_NODE_WORDS, buildWideBvh, CWBVH_NODE_WORDS, WIDE_MAX_LEAF, wideBvhStats } from './wide.ts';

export interface BvhLayout {
  readonly name: string;
  readonly description: string;
  /** Bytes of one node on the GPU. */
  readonly nodeBytes: number;
  /** The SAH costs its statistics use. */
  readonly options: BvhBuildOptions;
  /** Over primitives of `kinds` (scene/triangles.ts), or triangles only without. */
  readonly build: (positions: Float32Array, kinds?: Uint8Array) => Bvh;
  /** Statistics of the layout over the tree `build` gave (node memory counts this layout's nodes and tables). */
  readonly stats: (bvh: Bvh, options: BvhStatsOptions) => BvhStats;
}

const o = DEFAULT_BVH_BUILD_OPTIONS;

export const BVH_LAYOUTS: readonly BvhLayout[] = [
  {
    name: 'binary-sah',
    description: `binary BVH, binned SAH build (${o.bins} bins per axis, leaves of at most ${o.maxLeafSize} primitives), ${BVH_NODE_BYTES}-byte nodes, sibling pairs in 64-byte blocks; what the GPU traverses`,
    nodeBytes: BVH_NODE_BYTES,
    options: o,
    build: (positions, kinds) => buildBvh(positions, o, kinds),
    stats: bvhStats,
  },
  {
    name: 'bvh4',
    description: `4-wide BVH collapsed from binary-sah by the SAH dynamic programme (Ylitie et al. 2017), fp32 child boxes in the parent as structure of arrays, ${BVH4_NODE_WORDS * 4}-byte nodes, leaves of binary-sah (at most ${WIDE_MAX_LEAF.bvh4} a reference); --accel bvh4`,
    nodeBytes: BVH4_NODE_WORDS * 4,
    options: o,
    build: (positions, kinds) => buildBvh(positions, o, kinds),
    stats: (bvh, options) => wideBvhStats(buildWideBvh(bvh, 'bvh4'), bvh.stats.buildMs, options.triangleBytes),
  },
  {
    name: 'cwbvh',
    description: `compressed 8-wide BVH (Ylitie et al. 2017) collapsed from binary-sah by the SAH dynamic programme, ${CWBVH_NODE_WORDS * 4}-byte nodes with 8-bit conservative child boxes, octant-ordered slots, a leaf table of 4 bytes a leaf; --accel cwbvh`,
    nodeBytes: CWBVH_NODE_WORDS * 4,
    options: o,
    build: (positions, kinds) => buildBvh(positions, o, kinds),
    stats: (bvh, options) => wideBvhStats(buildWideBvh(bvh, 'cwbvh'), bvh.stats.buildMs, options.triangleBytes),
  },
  // The greedy collapse, to compare (not what --accel builds).
  ...(['bvh4', 'cwbvh'] as const).map(
    (layout): BvhLayout => ({
      name: `${layout}-greedy`,
      description: `${layout} collapsed greedily instead (the largest-area child opened first until the node is full); for comparison only`,
      nodeBytes: (layout === 'bvh4' ? BVH4_NODE_WORDS : CWBVH_NODE_WORDS) * 4,
      options: o,
      build: (positions, kinds) => buildBvh(positions, o, kinds),
      stats: (bvh, options) => wideBvhStats(buildWideBvh(bvh, layout, { collapse: 'greedy' }), bvh.stats.buildMs, options.triangleBytes),
    }),
  ),
];
