/**
 * The page's BVH build workers: Web Workers started by the scene worker (a worker may start
 * workers), one per logical core as the browser reports them, at most 16. Where a worker cannot
 * start them (no nested workers), there is no pool and the BVH is built in the scene worker alone.
 */
import { SubtreeWorkerPool, type BvhWorkerPool, type SubtreePort, type SubtreeReply } from '../bvh/build-parallel.ts';

const MAX_THREADS = 16;
let pool: BvhWorkerPool | undefined | null = null;

/** The pool; its workers start with the first build big enough to use them (PARALLEL_MIN_PRIMITIVES). */
export function webBvhPool(): BvhWorkerPool | undefined {
  if (pool !== null) return pool;
  const threads = Math.min(MAX_THREADS, typeof navigator === 'undefined' ? 1 : navigator.hardwareConcurrency || 1);
  if (typeof Worker === 'undefined' || threads < 2) return (pool = undefined);
  return (pool = new SubtreeWorkerPool(threads, webPort));
}

function webPort(): SubtreePort {
  const worker = new Worker(new URL('./bvh-worker.ts', import.meta.url), { type: 'module', name: 'lantern bvh' });
  return {
    post: (task, transfer) => worker.postMessage(task, transfer),
    listen(onReply, onFailure) {
      worker.onmessage = (event: MessageEvent<SubtreeReply>) => onReply(event.data);
      worker.onerror = (event) => {
        event.preventDefault();
        onFailure(new Error(event.message || 'the worker could not start'));
      };
    },
    terminate: () => worker.terminate(),
  };
}
