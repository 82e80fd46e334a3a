/**
 * A Web Worker that builds BVH subtrees for the scene worker (bvh-workers.ts, bvh/build-parallel.ts).
 * Ranges arrive as transferred copies, so no SharedArrayBuffer (and no cross-origin isolation) is needed.
 */
import { runSubtreeTask, warmUpBuilder, type SubtreeTask } from '../bvh/build-parallel.ts';

self.onmessage = (event: MessageEvent<SubtreeTask>) => {
  const { reply, transfer } = runSubtreeTask(event.data);
  (self as unknown as Worker).postMessage(reply, transfer);
};

// Compiles the hot loops before the first real subtree; tasks that arrive meanwhile wait.
warmUpBuilder();
