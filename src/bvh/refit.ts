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
  for (let node = bvh.nodeCount - 1; node >= 0; node--) {
    if (node === 1) continue; // the unused slot keeps its inverted box
    let minX = Infinity, minY = Infinity, minZ = Infinity, maxX = -Infinity, maxY = -Infinity, maxZ = -Infinity;
    if (triCount[node]! > 0) {
      const first = leftFirst[node]!, end = first + triCount[node]!;
      for (let i = first; i < end; i++) {
        const o = triIndices[i]! * 6;
        minX = Math.min(minX, boxes[o]!);
        minY = Math.min(minY, boxes[o + 1]!);
        minZ = Math.min(minZ, boxes[o + 2]!);
        maxX = Math.max(maxX, boxes[o + 3]!);
        maxY = Math.max(maxY, boxes[o + 4]!);
        maxZ = Math.max(maxZ, boxes[o + 5]!);
      }
    } else {
      for (const child of [leftFirst[node]!, leftFirst[node]! + 1]) {
        const b = child * 6;
        minX = Math.min(minX, bounds[b]!);
        minY = Math.min(minY, bounds[b + 1]!);
        minZ = Math.min(minZ, bounds[b + 2]!);
        maxX = Math.max(maxX, bounds[b + 3]!);
        maxY = Math.max(maxY, bounds[b + 4]!);
        maxZ = Math.max(maxZ, bounds[b + 5]!);
      }
    }
    bounds.set([minX, minY, minZ, maxX, maxY, maxZ], node * 6);
  }
  return { ...bvh, bounds };
}
