/**
 * The BVH build spread over worker threads, giving exactly the tree of `buildBvh` (build.ts).
 *
 * The calling thread splits the root with the same loop as `buildBvh`, down to nodes of at most half
 * the input, and leaves those unbuilt: each one's range of boxes and indices, which no later step
 * touches, is copied out and sent to a worker as soon as it appears. A worker builds a task's
 * subtree with the same loop into node arrays of its own (root at local slot 0, children from
 * local slot 2); a big task (more than ~n / (6 · workers) primitives) it splits only down to half
 * its size and sends those halves back unbuilt, as new tasks for any worker. So the top levels are
 * spread over the workers too: the work no other thread can share is about n + n/2 + n/4 + ... =
 * 2n primitive visits, where building the top alone would take one pass over all n primitives
 * per level.
 *
 * Stitching: `buildBvh` numbers nodes as it pops them off a depth-first stack, children in pairs
 * from a running counter, so the descendants of any node take one contiguous block of slots,
 * allocated in the same order as a subtree built alone from local slot 2. Walking the pieces with
 * that same stack (into a task's piece where its parent left the node unbuilt), and shifting a
 * finished subtree's block to the current counter, therefore reproduces the single-thread
 * numbering. Each node's decisions depend only on its own primitives (in the order the partitions
 * above left them), its box and its depth, so the arrays come out bit for bit those of `buildBvh`,
 * whatever the number of workers, the cuts, or the order in which tasks finish. The SAH-cost sums are taken again over the stitched tree in the same preorder, so the statistics
 * match too (the build time aside).
 *
 * Nothing here needs SharedArrayBuffer: ranges travel as copies in transferred buffers (a few ms for
 * a million primitives), so the page needs no cross-origin isolation. The threads themselves come
 * from the host: cli/bvh-workers.ts (Node worker_threads), app/bvh-workers.ts (Web Workers), both
 * through `BvhWorkerPool` below.
 */
import { LanternError } from '../errors.ts';
import { halfAreaAt } from './box-area.ts';
import { buildBvh, buildSubtree, finishBvh, newTotals, newTree, NodeSplitter, rangeBox, resolveBvhOptions, type BuildTotals, type TreeArrays } from './build.ts';
import { computeTriangleBoxes } from './triangle-boxes.ts';
import type { Bvh, BvhBuildOptions } from './types.ts';

/** Below this many primitives the build stays on the calling thread: it takes tens of ms, about what starting workers costs. */
export const PARALLEL_MIN_PRIMITIVES = 100_000;
/** Whole subtrees per worker the splitting aims for, so that uneven subtrees still keep every worker busy. */
const TASKS_PER_WORKER = 6;
/** Subtrees of at most this many primitives are never split for other workers: messages would cost more than they save. */
const MIN_TASK_PRIMITIVES = 2048;

/** Overrides of the size thresholds, for tests (which need many workers' worth of tasks from small inputs). */
export interface ParallelTuning {
  /** Inputs smaller than this are built on the calling thread (default PARALLEL_MIN_PRIMITIVES). */
  readonly minPrimitives?: number;
  /** Tasks of at most this many primitives are built whole (default: about 6 per worker, >= 2048); bigger ones are split further. */
  readonly taskPrimitives?: number;
}

/** One subtree for a worker: a copied range of the build's working boxes and indices. */
export interface SubtreeTask {
  readonly id: number;
  /** Where the range starts in the whole build's index array (leaves store it + their local offset). */
  readonly first: number;
  readonly depth: number;
  /** The subtree root's box: min xyz, max xyz. */
  readonly box: readonly number[];
  readonly options: BvhBuildOptions;
  /**
   * 0: build the whole subtree. Otherwise build only down to nodes of at most `cut` primitives and
   * send those back unbuilt (`SubtreeResult.deferred`), so that other workers share them.
   */
  readonly cut: number;
  /** 6 floats per primitive (min xyz, max xyz) and the primitives' source indices, in range order. */
  readonly work: Float32Array;
  readonly index: Uint32Array;
}

/** A node a worker left unbuilt (a task's `cut`): its local slot and what a task for it needs. */
export interface DeferredNode {
  readonly node: number;
  readonly first: number;
  readonly depth: number;
  readonly box: readonly number[];
  readonly work: Float32Array;
  readonly index: Uint32Array;
}

/** A built subtree: its node slots 0 and 2.. (slot 1 unused), and its indices in leaf order. */
export interface SubtreeResult {
  readonly id: number;
  readonly bounds: Float32Array;
  readonly leftFirst: Uint32Array;
  readonly triCount: Uint32Array;
  readonly index: Uint32Array;
  readonly leafCount: number;
  readonly maxDepth: number;
  readonly leafDepthSum: number;
  /** Nodes left unbuilt (only with a task `cut`), each to become a task of its own. */
  readonly deferred: readonly DeferredNode[];
}

/** A worker's answer: the subtree, or why it could not build it. */
export type SubtreeReply = SubtreeResult | { readonly id: number; readonly error: string };

/** Threads that build subtrees; how they are started is the host's business (Node or the browser). */
export interface BvhWorkerPool {
  /** How many workers run subtrees at once. */
  readonly size: number;
  /** Builds the subtree on a worker (queued while all are busy); the task's buffers are transferred. */
  build(task: SubtreeTask): Promise<SubtreeResult>;
}

/**
 * Node slots for building `count` primitives down to nodes of at most `cut` (0: all the way). With
 * a cut of at least half the count (rounded down), no two siblings are both built (each would hold
 * more than half of the count), so the nodes built form one chain from the root: two slots a level.
 */
function slotsFor(count: number, cut: number, maxDepth: number): number {
  return cut > 0 && cut >= count >> 1 ? 2 * (Math.min(maxDepth, count) + 2) : 2 * count;
}

/** What a worker does with a task: the whole of the worker side. Returns the reply and its buffers to transfer. */
export function runSubtreeTask(task: SubtreeTask): { reply: SubtreeReply; transfer: ArrayBuffer[] } {
  try {
    const count = task.index.length;
    const tree = newTree(slotsFor(count, task.cut, task.options.maxDepth));
    for (let c = 0; c < 6; c++) tree.bounds[c] = task.box[c]!;
    const totals = newTotals();
    const deferred: DeferredNode[] = [];
    const transfer: ArrayBuffer[] = [];
    const { work, index, cut } = task;
    const defer = cut > 0
      ? (node: number, first: number, n: number, depth: number): boolean => {
          if (node === 0 || n > cut) return false;
          const d: DeferredNode = { node, first: task.first + first, depth, box: Array.from(tree.bounds.subarray(node * 6, node * 6 + 6)), work: work.slice(first * 6, (first + n) * 6), index: index.slice(first, first + n) };
          deferred.push(d);
          transfer.push(d.work.buffer as ArrayBuffer, d.index.buffer as ArrayBuffer);
          return true;
        }
      : undefined;
    buildSubtree(new NodeSplitter(task.options, work, index), tree, 0, 0, count, task.depth, totals, task.first, defer);
    const used = totals.next;
    const reply: SubtreeResult = {
      id: task.id,
      bounds: tree.bounds.slice(0, used * 6),
      leftFirst: tree.leftFirst.slice(0, used),
      triCount: tree.triCount.slice(0, used),
      index,
      leafCount: totals.leafCount,
      maxDepth: totals.maxDepth,
      leafDepthSum: totals.leafDepthSum,
      deferred,
    };
    transfer.push(reply.bounds.buffer as ArrayBuffer, reply.leftFirst.buffer as ArrayBuffer, reply.triCount.buffer as ArrayBuffer, index.buffer as ArrayBuffer);
    return { reply, transfer };
  } catch (e) {
    return { reply: { id: task.id, error: (e as Error)?.message ?? String(e) }, transfer: [] };
  }
}

/**
 * Runs the builder once over a small made-up mesh, so that a fresh worker has its hot loops compiled
 * before real work arrives (a new thread starts with cold code: its first subtree would otherwise
 * run several times slower). Takes a few ms.
 */
export function warmUpBuilder(): void {
  const n = 2_000;
  const positions = new Float32Array(n * 9);
  let seed = 1;
  for (let t = 0; t < n; t++) {
    // A deterministic soup of small triangles (xorshift), nothing to do with any scene.
    const c = [0, 0, 0].map(() => ((seed = (seed ^ (seed << 13)) >>> 0, seed = (seed ^ (seed >>> 17)) >>> 0, seed = (seed ^ (seed << 5)) >>> 0) / 2 ** 32));
    for (let v = 0; v < 9; v++) positions[t * 9 + v] = c[v % 3]! + ((v * 7 + t) % 5) * 0.002;
  }
  buildBvh(positions);
}

/** A worker of the pool died or could not start (as opposed to an error in the build itself). */
export class BvhWorkerFailure extends LanternError {}

/**
 * `buildBvh`'s tree, built with the pool's workers when there are at least two and the input is big
 * enough (PARALLEL_MIN_PRIMITIVES), on the calling thread otherwise, and on the calling thread
 * again if a worker fails (a pool whose worker failed is not used again).
 */
export async function buildBvhParallel(
  positions: Float32Array, options: Partial<BvhBuildOptions> = {}, kinds: Uint8Array | undefined, pool: BvhWorkerPool | undefined,
  tuning: ParallelTuning = {},
): Promise<Bvh> {
  const n = positions.length / 9;
  const minPrimitives = tuning.minPrimitives ?? PARALLEL_MIN_PRIMITIVES;
  if (!pool || pool.size < 2 || n < Math.max(2, minPrimitives)) return buildBvh(positions, options, kinds);
  try {
    return await buildOnWorkers(positions, options, kinds, pool, tuning);
  } catch (e) {
    if (e instanceof BvhWorkerFailure) return buildBvh(positions, options, kinds);
    throw e;
  }
}

async function buildOnWorkers(positions: Float32Array, options: Partial<BvhBuildOptions>, kinds: Uint8Array | undefined, pool: BvhWorkerPool, tuning: ParallelTuning): Promise<Bvh> {
  const n = positions.length / 9;
  const startMs = performance.now();
  const opts = resolveBvhOptions(options);
  const work = computeTriangleBoxes(positions, kinds);
  const index = new Uint32Array(n);
  for (let i = 0; i < n; i++) index[i] = i;

  // Sizes: tasks of at most `fine` primitives are built whole; a bigger one is split by its worker
  // only down to half its size (`cut`), and the halves come back as tasks for any worker. The
  // calling thread does the same with the root. So the chain of work no other thread can share is
  // about n + n/2 + n/4 + ... = 2n triangle visits, not one full level of the tree per halving.
  const fine = tuning.taskPrimitives ?? Math.max(MIN_TASK_PRIMITIVES, Math.ceil(n / (TASKS_PER_WORKER * pool.size)));
  const cutFor = (count: number) => (count > fine ? Math.max(fine, count >> 1) : 0);

  /** Task id -> its result, and which of its local slots were left for which task. */
  const results: SubtreeResult[] = [];
  const childTasks: Map<number, number>[] = [];
  const taskFirst: number[] = [];
  const running: Promise<void>[] = [];
  const launch = (d: Omit<DeferredNode, 'node'>): number => {
    const id = taskFirst.length;
    taskFirst.push(d.first);
    const cut = cutFor(d.index.length);
    const done = pool.build({ id, first: d.first, depth: d.depth, box: d.box, options: opts, cut, work: d.work, index: d.index }).then((r) => {
      if (r.leafCount === 0 && r.deferred.length === 0) throw new LanternError(`BVH worker returned an empty subtree for task ${r.id}`);
      results[id] = r;
      childTasks[id] = new Map(r.deferred.map((c) => [c.node, launch(c)]));
    });
    // Awaited below; this only keeps a second failure from being reported as unhandled.
    done.catch(() => {});
    running.push(done);
    return id;
  };

  // The top of the tree, in slots of its own (renumbered when stitched).
  const topCut = cutFor(n);
  const top = newTree(slotsFor(n, topCut, opts.maxDepth));
  rangeBox(work, 0, n, top.bounds, 0);
  /** Top slot -> the task built there. */
  const topChildren = new Map<number, number>();
  const topTotals = newTotals();
  buildSubtree(new NodeSplitter(opts, work, index), top, 0, 0, n, 0, topTotals, 0, (node, first, count, depth) => {
    if (count > topCut) return false;
    // Copies: the workers own them from here, and the top build never touches this range again.
    topChildren.set(node, launch({ first, depth, box: Array.from(top.bounds.subarray(node * 6, node * 6 + 6)), work: work.slice(first * 6, (first + count) * 6), index: index.slice(first, first + count) }));
    return true;
  });
  // Tasks add tasks as they finish: wait until none is left.
  for (let i = 0; i < running.length; i++) await running[i];

  // Stitch: the single-thread numbering, walking the pieces with the same stack discipline.
  let slots = topTotals.next;
  for (const r of results) slots += r.leftFirst.length - 2;
  const tree = newTree(slots);
  const totals: BuildTotals = { ...topTotals };
  for (const r of results) {
    totals.leafCount += r.leafCount;
    totals.leafDepthSum += r.leafDepthSum;
    if (r.maxDepth > totals.maxDepth) totals.maxDepth = r.maxDepth;
  }
  // Entries (piece, slot in the piece, final slot); piece -1 is the top, k >= 0 task k's result.
  const stack: number[] = [-1, 0, 0];
  let next = 2;
  while (stack.length > 0) {
    const at = stack.pop()!, local = stack.pop()!, piece = stack.pop()!;
    const pieceChildren = piece < 0 ? topChildren : childTasks[piece]!;
    const task = pieceChildren.get(local);
    if (task !== undefined) {
      // The root of a task's piece; a piece that left nothing unbuilt goes over in one block.
      index.set(results[task]!.index, taskFirst[task]!);
      if (childTasks[task]!.size === 0) next = placeSubtree(results[task]!, tree, at, next);
      else stack.push(task, 0, at);
      continue;
    }
    const src: TreeArrays = piece < 0 ? top : results[piece]!;
    tree.bounds.set(src.bounds.subarray(local * 6, local * 6 + 6), at * 6);
    if (src.triCount[local]! > 0) {
      tree.leftFirst[at] = src.leftFirst[local]!;
      tree.triCount[at] = src.triCount[local]!;
      continue;
    }
    const left = next;
    next += 2;
    tree.leftFirst[at] = left;
    const srcLeft = src.leftFirst[local]!;
    stack.push(piece, srcLeft + 1, left + 1, piece, srcLeft, left);
  }
  if (next !== slots) throw new Error(`BVH stitch: placed ${next} slots, expected ${slots}`);
  totals.next = next;
  preorderSah(tree, opts, totals, n);
  const bvh = finishBvh(tree, totals, index, n, startMs);
  return { ...bvh, stats: { ...bvh.stats, workers: pool.size } };
}

/** Copies a worker's subtree with its root at final slot `at` and its other slots from `next` on; returns the new `next`. */
function placeSubtree(r: SubtreeResult, tree: TreeArrays, at: number, next: number): number {
  const shift = next - 2;
  const { bounds, leftFirst, triCount } = tree;
  bounds.set(r.bounds.subarray(0, 6), at * 6);
  triCount[at] = r.triCount[0]!;
  leftFirst[at] = r.triCount[0]! > 0 ? r.leftFirst[0]! : r.leftFirst[0]! + shift;
  const used = r.leftFirst.length;
  if (used <= 2) return next;
  bounds.set(r.bounds.subarray(12), next * 6);
  triCount.set(r.triCount.subarray(2), next);
  for (let i = 2; i < used; i++) leftFirst[shift + i] = r.triCount[i]! > 0 ? r.leftFirst[i]! : r.leftFirst[i]! + shift;
  return next + used - 2;
}

/** The SAH-cost sums over the finished tree, added in the order `buildSubtree` adds them (preorder, left first). */
function preorderSah(tree: TreeArrays, opts: BvhBuildOptions, totals: BuildTotals, n: number): void {
  const Ct = opts.traversalCost, Ci = opts.intersectionCost;
  const { bounds, leftFirst, triCount } = tree;
  let sahWeighted = 0, sahUnweighted = 0;
  // At most depth + 1 entries wait, and the depth is at most min(maxDepth, n - 1).
  const stack = new Uint32Array(Math.min(opts.maxDepth, n) + 2);
  let sp = 1;
  stack[0] = 0;
  while (sp > 0) {
    const node = stack[--sp]!;
    const area = halfAreaAt(bounds, node);
    const count = triCount[node]!;
    if (count > 0) {
      sahWeighted += area * count * Ci;
      sahUnweighted += count * Ci;
      continue;
    }
    sahWeighted += area * Ct;
    sahUnweighted += Ct;
    stack[sp++] = leftFirst[node]! + 1;
    stack[sp++] = leftFirst[node]!;
  }
  totals.sahWeighted = sahWeighted;
  totals.sahUnweighted = sahUnweighted;
}

/** One worker as the pool sees it; cli/ and app/ wrap Node's and the browser's workers in this. */
export interface SubtreePort {
  post(task: SubtreeTask, transfer: ArrayBuffer[]): void;
  /** Called once: `onReply` for each answer, `onFailure` if the worker dies or cannot start. */
  listen(onReply: (reply: SubtreeReply) => void, onFailure: (error: Error) => void): void;
  terminate(): void;
}

/**
 * A fixed set of workers (started on first use, then kept) that take subtree tasks one at a time
 * each; a task waits in a queue while every worker is busy. A worker that dies fails its task and
 * every later one with a BvhWorkerFailure that says so (buildBvhParallel then builds on its own).
 */
export class SubtreeWorkerPool implements BvhWorkerPool {
  readonly size: number;
  private readonly spawn: () => SubtreePort;
  private ports: SubtreePort[] | undefined;
  private readonly busy: (Waiting | undefined)[] = [];
  private readonly queue: Waiting[] = [];
  private failure: Error | undefined;

  constructor(size: number, spawn: () => SubtreePort) {
    if (!Number.isInteger(size) || size < 1) throw new LanternError(`BVH worker count must be an integer >= 1, got ${size}`);
    this.size = size;
    this.spawn = spawn;
  }

  /** Starts the workers now (they warm up while the caller does other work, e.g. loads the scene). */
  start(): void {
    this.started();
  }

  build(task: SubtreeTask): Promise<SubtreeResult> {
    if (this.failure) return Promise.reject(this.failure);
    return new Promise((resolve, reject) => {
      this.queue.push({ task, resolve, reject });
      this.pump();
    });
  }

  /** Stops the workers; a later build starts new ones. */
  terminate(): void {
    for (const p of this.ports ?? []) p.terminate();
    this.ports = undefined;
    this.busy.length = 0;
  }

  /** The workers, started if they are not; undefined (and the pool failed) if one cannot start. */
  private started(): SubtreePort[] | undefined {
    if (this.ports || this.failure) return this.ports;
    const ports: SubtreePort[] = [];
    try {
      for (let w = 0; w < this.size; w++) {
        const port = this.spawn();
        ports.push(port);
        port.listen(
          (reply) => this.answer(w, reply),
          (error) => this.fail(new BvhWorkerFailure(`a BVH build worker failed: ${error.message}`)),
        );
      }
    } catch (e) {
      for (const p of ports) p.terminate();
      this.fail(new BvhWorkerFailure(`cannot start a BVH build worker: ${(e as Error)?.message ?? String(e)}`));
      return undefined;
    }
    this.busy.length = 0;
    for (let w = 0; w < this.size; w++) this.busy.push(undefined);
    return (this.ports = ports);
  }

  private pump(): void {
    const ports = this.started();
    if (!ports) return;
    for (let w = 0; w < ports.length && this.queue.length > 0; w++) {
      if (this.busy[w]) continue;
      const job = this.queue.shift()!;
      this.busy[w] = job;
      ports[w]!.post(job.task, [job.task.work.buffer, job.task.index.buffer] as ArrayBuffer[]);
    }
  }

  private answer(w: number, reply: SubtreeReply): void {
    const job = this.busy[w];
    this.busy[w] = undefined;
    if (!job) return;
    if ('error' in reply) job.reject(new LanternError(`BVH build worker: ${reply.error}`));
    else job.resolve(reply);
    this.pump();
  }

  private fail(error: Error): void {
    this.failure = error;
    for (const job of [...this.busy, ...this.queue.splice(0)]) job?.reject(error);
    this.terminate();
  }
}

interface Waiting {
  readonly task: SubtreeTask;
  resolve(result: SubtreeResult): void;
  reject(error: Error): void;
}
