/**
 * The BVH layouts Lantern can build, each with what `lantern bvh-stats` needs to compare them: a
 * name, what it is, the bytes of one node and a builder. One layout so far; a new one (a wide BVH,
 * compressed nodes) is one more entry here, and the statistics, the command and its tests pick it up.
 */
import { buildBvh, DEFAULT_BVH_BUILD_OPTIONS } from './build.ts';
import { BVH_NODE_BYTES } from './stats.ts';
import type { Bvh, BvhBuildOptions } from './types.ts';

export interface BvhLayout {
  readonly name: string;
  readonly description: string;
  /** Bytes of one node on the GPU. */
  readonly nodeBytes: number;
  /** The SAH costs its statistics use. */
  readonly options: BvhBuildOptions;
  /** Over primitives of `kinds` (scene/triangles.ts), or triangles only without. */
  readonly build: (positions: Float32Array, kinds?: Uint8Array) => Bvh;
}

const o = DEFAULT_BVH_BUILD_OPTIONS;

export const BVH_LAYOUTS: readonly BvhLayout[] = [
  {
    name: 'binary-sah',
    description: `binary BVH, binned SAH build (${o.bins} bins per axis, leaves of at most ${o.maxLeafSize} primitives), ${BVH_NODE_BYTES}-byte nodes, sibling pairs in 64-byte blocks; what the GPU traverses`,
    nodeBytes: BVH_NODE_BYTES,
    options: o,
    build: (positions, kinds) => buildBvh(positions, o, kinds),
  },
];
