/**
 * Refitting: after triangles moved, every box is recomputed bottom-up from the same tree, so the
 * BVH stays exact (each box the union of its triangles' boxes) without a rebuild. Children always
 * sit after their parent in the node array (the builder allocates them later), so one backward pass
 * sees every child before its parent. The tree's quality degrades as things move far; a rebuild is
 * the remedy (a two-level BVH makes moving instances cheap to rebuild at the top).
 */
import { computeTriangleBoxes } from './triangle-boxes.ts';
import type { Bvh } from './types.ts';

/** A new BVH with the same tree as `bvh` and boxes fitted to `positions` (9 floats per primitive, of `kinds`; triangles without). */
export function refitBvh(bvh: Bvh, positions: Float32Array, kinds?: Uint8Array): Bvh {
  const bounds = new Float32Array(bvh.bounds);
  const boxes = computeTriangleBoxes(positions, kinds);
  const { leftFirst, triCount, triIndices } = bvh;
  // The union of the boxes at `entries` of `from` (6 floats each), written as node's box.
  const fit = (node: number, from: Float32Array, entries: Iterable<number>) => {
    let minX = Infinity, minY = Infinity, minZ = Infinity, maxX = -Infinity, maxY = -Infinity, maxZ = -Infinity;
    for (const e of entries) {
      const o = e * 6;
      minX = Math.min(minX, from[o]!);
      minY = Math.min(minY, from[o + 1]!);
      minZ = Math.min(minZ, from[o + 2]!);
      maxX = Math.max(maxX, from[o + 3]!);
      maxY = Math.max(maxY, from[o + 4]!);
      maxZ = Math.max(maxZ, from[o + 5]!);
    }
    bounds.set([minX, minY, minZ, maxX, maxY, maxZ], node * 6);
  };
  for (let node = bvh.nodeCount - 1; node >= 0; node--) {
    if (node === 1) continue; // the unused slot keeps its inverted box
    const first = leftFirst[node]!;
    if (triCount[node]! > 0) fit(node, boxes, triIndices.subarray(first, first + triCount[node]!));
    else fit(node, bounds, [first, first + 1]);
  }
  return { ...bvh, bounds };
}
