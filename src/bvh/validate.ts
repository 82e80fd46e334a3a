/**
 * Structural checks of a built BVH against the triangles it was built from: what every consumer
 * (GPU packing, traversal) relies on. Throws an Error naming the first broken invariant. Linear
 * time; meant for tests and debugging, not for every render.
 */
import { computeTriangleBoxes, F32_MAX } from './triangle-boxes.ts';
import type { Bvh } from './types.ts';

/** `kinds`: the primitive kinds (scene/triangles.ts), absent when every primitive is a triangle. */
export function checkBvh(bvh: Bvh, positions: Float32Array, maxDepth = Infinity, kinds?: Uint8Array): void {
  const fail = (what: string): never => {
    throw new Error(`invalid BVH: ${what}`);
  };
  const { nodeCount, bounds, leftFirst, triCount, triIndices } = bvh;
  const n = positions.length / 9;
  const boxes = computeTriangleBoxes(positions, kinds);
  if (triIndices.length !== n) fail(`triIndices has ${triIndices.length} entries for ${n} triangles`);
  if (nodeCount < 2 || bounds.length !== nodeCount * 6 || leftFirst.length !== nodeCount || triCount.length !== nodeCount) {
    fail(`array sizes do not match nodeCount ${nodeCount}`);
  }
  if (triCount[1] !== 0 || leftFirst[1] !== 0) fail('slot 1 is not empty');
  for (let a = 0; a < 3; a++) if (!(bounds[6 + a]! > bounds[9 + a]!)) fail('slot 1 does not hold an inverted box');

  const seenTriangle = new Uint8Array(n);
  for (let i = 0; i < n; i++) {
    const t = triIndices[i]!;
    if (t >= n || seenTriangle[t]) fail(`triIndices is not a permutation (entry ${i} = ${t})`);
    seenTriangle[t] = 1;
  }

  const seenNode = new Uint8Array(nodeCount);
  const coveredLeafSlot = new Uint8Array(n);
  const stack: number[] = [0, 0]; // (node, depth) pairs
  while (stack.length > 0) {
    const depth = stack.pop()!, node = stack.pop()!;
    if (seenNode[node]) fail(`node ${node} is reachable twice`);
    seenNode[node] = 1;
    if (depth > maxDepth) fail(`node ${node} has depth ${depth} > ${maxDepth}`);
    const b = node * 6;
    for (let a = 0; a < 3; a++) {
      const lo = bounds[b + a]!, hi = bounds[b + 3 + a]!;
      if (!(lo <= hi && lo >= -F32_MAX && hi <= F32_MAX)) fail(`node ${node} has an empty or non-finite box`);
    }
    // The box every node must have: the exact union of its children's boxes, or of its triangles'.
    const union = [Infinity, Infinity, Infinity, -Infinity, -Infinity, -Infinity];
    const count = triCount[node]!;
    if (count > 0) {
      const first = leftFirst[node]!;
      if (first + count > n) fail(`leaf ${node} covers entries ${first}..${first + count - 1} of ${n}`);
      for (let i = first; i < first + count; i++) {
        if (coveredLeafSlot[i]) fail(`entry ${i} of triIndices is in two leaves`);
        coveredLeafSlot[i] = 1;
        const p = triIndices[i]! * 6;
        for (let a = 0; a < 3; a++) {
          union[a] = Math.min(union[a]!, boxes[p + a]!);
          union[3 + a] = Math.max(union[3 + a]!, boxes[p + 3 + a]!);
        }
      }
    } else {
      const left = leftFirst[node]!;
      if (left < 2 || left % 2 !== 0 || left + 1 >= nodeCount) fail(`interior node ${node} has children at ${left}, ${left + 1}`);
      for (const child of [left, left + 1]) {
        for (let a = 0; a < 6; a++) union[a] = a < 3 ? Math.min(union[a]!, bounds[child * 6 + a]!) : Math.max(union[a]!, bounds[child * 6 + a]!);
      }
      stack.push(left + 1, depth + 1, left, depth + 1);
    }
    for (let a = 0; a < 6; a++) {
      if (union[a] !== bounds[b + a]) fail(`node ${node} box is not the exact union of its ${count > 0 ? 'triangles' : 'children'} (component ${a}: ${bounds[b + a]} vs ${union[a]})`);
    }
  }
  for (let i = 0; i < nodeCount; i++) if (i !== 1 && !seenNode[i]) fail(`node ${i} is not reachable from the root`);
  for (let i = 0; i < n; i++) if (!coveredLeafSlot[i]) fail(`entry ${i} of triIndices is in no leaf`);
}
