/**
 * The depth of every BVH node (root = 0), for the debug views: the depth of the leaf a ray hits and
 * the boxes of one depth in the wireframe. The GPU layout stores no depth, so it is computed here
 * once per scene by walking the tree.
 */
import type { Bvh } from './types.ts';

/** Depth of a slot that is not part of the tree (the unused slot 1). */
export const NO_DEPTH = 0xffffffff;

/** depths[node] for every slot of the flat layout; NO_DEPTH for the unused slot 1. */
export function nodeDepths(bvh: Pick<Bvh, 'nodeCount' | 'leftFirst' | 'triCount'>): Uint32Array {
  const depths = new Uint32Array(bvh.nodeCount).fill(NO_DEPTH);
  const stack = [0];
  depths[0] = 0;
  while (stack.length > 0) {
    const node = stack.pop()!;
    if (bvh.triCount[node]! > 0) continue;
    const left = bvh.leftFirst[node]!;
    depths[left] = depths[left + 1] = depths[node]! + 1;
    stack.push(left, left + 1);
  }
  return depths;
}

/** The nodes at exactly depth `d`, in slot order (empty beyond the deepest leaf). */
export function nodesAtDepth(depths: Uint32Array, d: number): Uint32Array {
  const out: number[] = [];
  depths.forEach((depth, node) => {
    if (depth === d) out.push(node);
  });
  return Uint32Array.from(out);
}

/** The deepest node's depth. */
export function maxNodeDepth(depths: Uint32Array): number {
  let max = 0;
  for (const d of depths) if (d !== NO_DEPTH && d > max) max = d;
  return max;
}
