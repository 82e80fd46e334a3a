/**
 * Entry of a Node worker thread that builds BVH subtrees for bvh-workers.ts: bundled beside the CLI
 * as dist/cli/bvh-worker.mjs (vite.cli.config.ts), small so that a worker starts in a few ms.
 */
import { parentPort } from 'node:worker_threads';
import { runSubtreeTask, warmUpBuilder, type SubtreeTask } from '../bvh/build-parallel.ts';

parentPort?.on('message', (task: SubtreeTask) => {
  const { reply, transfer } = runSubtreeTask(task);
  parentPort!.postMessage(reply, transfer);
});

// Tasks that arrive meanwhile wait in the port's queue.
warmUpBuilder();
