/**
 * The CLI's BVH build workers: Node worker_threads running bvh-worker.mjs, the bundle's second entry
 * (vite.cli.config.ts). Run from the TypeScript sources (tests) that file does not exist, and the
 * build stays on one thread.
 */
import { existsSync } from 'node:fs';
import { availableParallelism } from 'node:os';
import { fileURLToPath } from 'node:url';
import { Worker } from 'node:worker_threads';
import { SubtreeWorkerPool, type SubtreePort, type SubtreeReply } from '../bvh/build-parallel.ts';
import { LanternError } from '../errors.ts';

/** Beside the bundle; a variable, so the bundler leaves the URL alone. */
const WORKER_FILE = './bvh-worker.mjs';

/** The machine's cores: the default number of build threads. */
export const defaultBuildThreads = (): number => availableParallelism();

const pools = new Map<number, SubtreeWorkerPool>();

/**
 * A pool of `threads` workers (kept for the process's life, and never keeping it alive), or
 * undefined for one thread or where the worker script is missing. The workers start with the first
 * build big enough to use them (PARALLEL_MIN_PRIMITIVES), so small scenes never pay for them.
 */
export function nodeBvhPool(threads = defaultBuildThreads()): SubtreeWorkerPool | undefined {
  if (!Number.isInteger(threads) || threads < 1) throw new LanternError(`--threads must be an integer >= 1, got ${threads}`);
  if (threads < 2) return undefined;
  const url = new URL(WORKER_FILE, import.meta.url);
  if (url.protocol !== 'file:' || !existsSync(fileURLToPath(url))) return undefined;
  let pool = pools.get(threads);
  if (!pool) {
    pool = new SubtreeWorkerPool(threads, () => nodePort(url));
    pools.set(threads, pool);
  }
  return pool;
}

function nodePort(url: URL): SubtreePort {
  const worker = new Worker(url, { name: 'lantern bvh' });
  // Referenced only while it works, so an idle pool never holds the process open (one that is
  // still warming up may be cut short at exit: harmless).
  worker.unref();
  let stopping = false;
  return {
    post(task, transfer) {
      worker.ref();
      worker.postMessage(task, transfer);
    },
    listen(onReply, onFailure) {
      worker.on('message', (reply: SubtreeReply) => {
        worker.unref();
        onReply(reply);
      });
      worker.on('error', (e) => onFailure(e instanceof Error ? e : new Error(String(e))));
      worker.on('exit', (code) => {
        if (code !== 0 && !stopping) onFailure(new Error(`worker exited with code ${code}`));
      });
    },
    terminate() {
      stopping = true;
      void worker.terminate();
    },
  };
}
