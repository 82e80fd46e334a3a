/**
 * Top-down binned-SAH BVH builder over a flat triangle list.
 *
 * Built for speed in plain JS: per-triangle boxes are precomputed into one typed array that is
 * permuted together with the triangle index array (so every node owns a contiguous range of both
 * and the hot loops read memory in order), work items live on an explicit typed-array stack (no
 * recursion, no per-node objects), and child boxes come straight out of the SAH bins, so a node
 * costs one binning pass and one partition pass over its triangles.
 *
 * Node boxes are exact unions of the triangles' float32 boxes: no padding, no rounding.
 */
import { LanternError } from '../errors.ts';
import { halfAreaAt } from './box-area.ts';
import { partitionByPlane } from './partition.ts';
import { SahBinner } from './sah-binner.ts';
import { SMALL_NODE_MAX, SmallSahSplitter } from './sah-small.ts';
import { computeTriangleBoxes, F32_MAX } from './triangle-boxes.ts';
import type { Bvh, BvhBuildOptions } from './types.ts';

export type { Bvh, BvhBuildOptions, BvhBuildStats } from './types.ts';

export const DEFAULT_BVH_BUILD_OPTIONS: BvhBuildOptions = Object.freeze({
  bins: 16,
  traversalCost: 1,
  intersectionCost: 1,
  maxLeafSize: 8,
  maxDepth: 60,
});

export function resolveBvhOptions(partial: Partial<BvhBuildOptions>): BvhBuildOptions {
  const o = { ...DEFAULT_BVH_BUILD_OPTIONS, ...partial };
  const bad = (what: string): never => {
    throw new LanternError(`invalid BVH build option: ${what}`);
  };
  if (!Number.isInteger(o.bins) || o.bins < 2 || o.bins > 4096) bad(`bins must be an integer in [2, 4096], got ${o.bins}`);
  if (!(o.traversalCost >= 0 && o.traversalCost < Infinity)) bad(`traversalCost must be finite and >= 0, got ${o.traversalCost}`);
  if (!(o.intersectionCost > 0 && o.intersectionCost < Infinity)) bad(`intersectionCost must be finite and > 0, got ${o.intersectionCost}`);
  if (!Number.isInteger(o.maxLeafSize) || o.maxLeafSize < 1) bad(`maxLeafSize must be an integer >= 1, got ${o.maxLeafSize}`);
  if (!Number.isInteger(o.maxDepth) || o.maxDepth < 0) bad(`maxDepth must be an integer >= 0, got ${o.maxDepth}`);
  return o;
}

/** How a node is turned into children; see the main loop. */
const Split = { Leaf: 0, Binned: 1, Small: 2, Middle: 3 } as const;

/**
 * Builds a BVH over `positions` (9 floats per primitive: for triangles v0 xyz, v1 xyz, v2 xyz; with
 * `kinds`, spheres and capsules too, laid out as scene/triangles.ts says). Everything below works on
 * the primitives' boxes, so the kinds only matter there.
 *
 * A node becomes a leaf when it holds one triangle, sits at maxDepth, or when no split is cheaper
 * than the leaf (count·Ci <= Ct + (A_L·N_L + A_R·N_R)/A·Ci) and it holds at most maxLeafSize
 * triangles. Larger nodes are split at the best SAH plane even when that plane does not pay, and
 * when all their centroids coincide (no plane exists) they are cut in the middle of their index range.
 *
 * Candidate planes: nodes of more than SMALL_NODE_MAX triangles bin centroids into `bins` slabs per
 * axis spanning the node's box (the centroid bounds when that finds nothing); smaller nodes score
 * every gap between sorted centroids exactly (sah-small.ts).
 *
 * Every decision about a node depends only on its own triangles (their boxes, in the order the
 * partitions above left them), its box and its depth, never on when it is built: that is what lets
 * build-parallel.ts build subtrees elsewhere and get this exact tree.
 */
export function buildBvh(positions: Float32Array, options: Partial<BvhBuildOptions> = {}, kinds?: Uint8Array): Bvh {
  const startMs = performance.now();
  const opts = resolveBvhOptions(options);
  /** Primitive boxes, permuted in step with `index` so every node's primitives are contiguous in it. */
  const work = computeTriangleBoxes(positions, kinds);
  const n = work.length / 6;
  if (n === 0) throw new LanternError('cannot build a BVH over zero triangles');
  const index = new Uint32Array(n);
  for (let i = 0; i < n; i++) index[i] = i;
  const tree = newTree(2 * n);
  rangeBox(work, 0, n, tree.bounds, 0);
  const totals = newTotals();
  buildSubtree(new NodeSplitter(opts, work, index), tree, 0, 0, n, 0, totals);
  return finishBvh(tree, totals, index, n, startMs);
}

/** Node arrays of a tree being built: slot 0 the root, slot 1 the unused inverted box, pairs from 2. */
export interface TreeArrays {
  readonly bounds: Float32Array;
  readonly leftFirst: Uint32Array;
  readonly triCount: Uint32Array;
}

/** Node arrays for `slots` nodes, slot 1 already holding its inverted but finite box. */
export function newTree(slots: number): TreeArrays {
  const bounds = new Float32Array(slots * 6);
  // Slot 1: inverted but finite box, so it never hits and never feeds an infinity to the GPU.
  bounds.fill(F32_MAX, 6, 9);
  bounds.fill(-F32_MAX, 9, 12);
  return { bounds, leftFirst: new Uint32Array(slots), triCount: new Uint32Array(slots) };
}

/** What the build loop counts as it goes; `next` is the next free slot (children come in pairs). */
export interface BuildTotals {
  next: number;
  leafCount: number;
  maxDepth: number;
  leafDepthSum: number;
  /** SAH cost sums, area-weighted and (for a zero-area root) unweighted, in build (preorder) order. */
  sahWeighted: number;
  sahUnweighted: number;
}

export const newTotals = (): BuildTotals => ({ next: 2, leafCount: 0, maxDepth: 0, leafDepthSum: 0, sahWeighted: 0, sahUnweighted: 0 });

/** The tree's arrays trimmed to the slots used, with its statistics. */
export function finishBvh(tree: TreeArrays, totals: BuildTotals, index: Uint32Array, n: number, startMs: number): Bvh {
  const rootArea = halfAreaAt(tree.bounds, 0);
  const nodeCount = totals.next;
  // Copies, so that larger scratch allocations (2n slots) can be freed; arrays of the right size as they are.
  const fit = <T extends Float32Array | Uint32Array>(a: T, length: number): T => (a.length === length ? a : (a.slice(0, length) as T));
  return {
    nodeCount,
    bounds: fit(tree.bounds, nodeCount * 6),
    leftFirst: fit(tree.leftFirst, nodeCount),
    triCount: fit(tree.triCount, nodeCount),
    triIndices: index,
    stats: {
      buildMs: performance.now() - startMs,
      nodeCount: nodeCount - 1,
      leafCount: totals.leafCount,
      maxDepth: totals.maxDepth,
      meanLeafDepth: totals.leafDepthSum / totals.leafCount,
      sahCost: rootArea > 0 ? totals.sahWeighted / rootArea : totals.sahUnweighted,
      triangleCount: n,
    },
  };
}

/** The split search and partition of one node, over one working range of boxes and indices. */
export class NodeSplitter {
  readonly opts: BvhBuildOptions;
  readonly work: Float32Array;
  readonly workBits: Uint32Array;
  readonly index: Uint32Array;
  readonly binner: SahBinner;
  readonly small = new SmallSahSplitter();
  /** The binning range of the current node: min xyz, max xyz in centroid (min + max) units. */
  readonly range = new Float64Array(6);

  constructor(opts: BvhBuildOptions, work: Float32Array, index: Uint32Array) {
    this.opts = opts;
    this.work = work;
    this.workBits = new Uint32Array(work.buffer, work.byteOffset, work.length);
    this.index = index;
    this.binner = new SahBinner(opts.bins);
  }
}

/**
 * Builds the subtree under `root` (whose box is already in tree.bounds) over work/index[first,
 * first + count) at `depth`, allocating child pairs from totals.next on. Leaves store
 * `leafBase + first`, so a range copied out of a bigger array can store its leaves' places in that
 * array. With `defer`, a popped node for which it returns true is left untouched (no leaf, no
 * children, no statistics) for someone else to build; build-parallel.ts uses that for the top levels.
 */
export function buildSubtree(
  s: NodeSplitter, tree: TreeArrays, root: number, first0: number, count0: number, depth0: number, totals: BuildTotals,
  leafBase = 0, defer?: (node: number, first: number, count: number, depth: number) => boolean,
): void {
  const { opts, work, workBits, index, binner, small, range } = s;
  const { bounds, leftFirst, triCount } = tree;
  const Ct = opts.traversalCost, Ci = opts.intersectionCost;
  // Work stack of (node, first, count, depth). Each split pops one node and pushes its two
  // children, so from the bottom up the depths strictly increase except for the sibling pair on
  // top: at most D + 2 entries for a tree of depth D <= min(maxDepth, count - 1).
  const stack = new Uint32Array((Math.min(opts.maxDepth, count0) + 2) * 4);
  stack[0] = root;
  stack[1] = first0;
  stack[2] = count0;
  stack[3] = depth0;
  let sp = 1;
  let next = totals.next;
  let leafCount = totals.leafCount, maxDepth = totals.maxDepth, leafDepthSum = totals.leafDepthSum;
  let sahWeighted = totals.sahWeighted, sahUnweighted = totals.sahUnweighted;

  while (sp > 0) {
    sp--;
    const node = stack[sp * 4]!, first = stack[sp * 4 + 1]!, count = stack[sp * 4 + 2]!, depth = stack[sp * 4 + 3]!;
    if (defer !== undefined && defer(node, first, count, depth)) continue;
    const end = first + count;
    const area = halfAreaAt(bounds, node);
    if (depth > maxDepth) maxDepth = depth;

    let how: number = Split.Leaf;
    if (count > 1 && depth < opts.maxDepth) {
      let found: boolean, cost: number;
      if (count <= SMALL_NODE_MAX) {
        found = small.findSplit(work, first, end);
        cost = small.cost;
      } else {
        // Bins span the node box (2·min .. 2·max in centroid units), which the children's boxes
        // give for free. The tighter centroid bounds would cost a pass per node and improve the
        // dragon's SAH cost by only ~0.15 %; they are computed only when the box range finds no
        // plane (centroids bunched into one bin, or all equal).
        for (let c = 0; c < 6; c++) range[c] = 2 * bounds[node * 6 + c]!;
        found = binner.findSplit(work, first, end, range);
        if (!found) {
          centroidRange(work, first, end, range);
          found = binner.findSplit(work, first, end, range);
        }
        cost = binner.cost;
      }
      if (found) {
        // Compare  Ct + cost/A·Ci < count·Ci  multiplied through by A, which also makes a zero-area
        // node (every side zero too) come out as "no gain" instead of 0/0.
        const pays = Ct * area + Ci * cost < Ci * count * area;
        if (pays || count > opts.maxLeafSize) how = count <= SMALL_NODE_MAX ? Split.Small : Split.Binned;
      } else if (count > opts.maxLeafSize) {
        how = Split.Middle;
      }
    }

    if (how === Split.Leaf) {
      leftFirst[node] = leafBase + first;
      triCount[node] = count;
      leafCount++;
      leafDepthSum += depth;
      sahWeighted += area * count * Ci;
      sahUnweighted += count * Ci;
      continue;
    }

    const left = next, right = next + 1;
    next += 2;
    leftFirst[node] = left;
    triCount[node] = 0;
    sahWeighted += area * Ct;
    sahUnweighted += Ct;

    let nLeft: number;
    if (how === Split.Binned) {
      nLeft = partitionByPlane(binner.plane, index, work, workBits, first, end);
      if (nLeft !== binner.leftCount) throw new Error(`BVH build: partition put ${nLeft} triangles left, the bins counted ${binner.leftCount}`);
      copyBox(binner.leftBox, bounds, left);
      copyBox(binner.rightBox, bounds, right);
    } else if (how === Split.Small) {
      nLeft = small.leftCount;
      small.apply(index, work, first, end);
      copyBox(small.leftBox, bounds, left);
      copyBox(small.rightBox, bounds, right);
    } else {
      nLeft = count >> 1;
      rangeBox(work, first, first + nLeft, bounds, left * 6);
      rangeBox(work, first + nLeft, end, bounds, right * 6);
    }

    // The right child goes below the left one on the stack, so the left subtree is built first and
    // the tree comes out in depth-first order (good locality for traversal).
    const r = sp * 4;
    stack[r] = right;
    stack[r + 1] = first + nLeft;
    stack[r + 2] = count - nLeft;
    stack[r + 3] = depth + 1;
    stack[r + 4] = left;
    stack[r + 5] = first;
    stack[r + 6] = nLeft;
    stack[r + 7] = depth + 1;
    sp += 2;
  }
  totals.next = next;
  totals.leafCount = leafCount;
  totals.maxDepth = maxDepth;
  totals.leafDepthSum = leafDepthSum;
  totals.sahWeighted = sahWeighted;
  totals.sahUnweighted = sahUnweighted;
}

function copyBox(box: Float64Array, bounds: Float32Array, node: number): void {
  for (let c = 0; c < 6; c++) bounds[node * 6 + c] = box[c]!;
}

/** Exact box of work[start..end) into out[outOff..outOff+6). */
export function rangeBox(work: Float32Array, start: number, end: number, out: Float32Array, outOff: number): void {
  let x0 = Infinity, y0 = Infinity, z0 = Infinity, x1 = -Infinity, y1 = -Infinity, z1 = -Infinity;
  for (let b = start * 6, bEnd = end * 6; b < bEnd; b += 6) {
    if (work[b]! < x0) x0 = work[b]!;
    if (work[b + 1]! < y0) y0 = work[b + 1]!;
    if (work[b + 2]! < z0) z0 = work[b + 2]!;
    if (work[b + 3]! > x1) x1 = work[b + 3]!;
    if (work[b + 4]! > y1) y1 = work[b + 4]!;
    if (work[b + 5]! > z1) z1 = work[b + 5]!;
  }
  out[outOff] = x0; out[outOff + 1] = y0; out[outOff + 2] = z0;
  out[outOff + 3] = x1; out[outOff + 4] = y1; out[outOff + 5] = z1;
}

/** Bounds of the centroids (min + max units) of work[start..end) into out (min xyz, max xyz). */
function centroidRange(work: Float32Array, start: number, end: number, out: Float64Array): void {
  out.fill(Infinity, 0, 3);
  out.fill(-Infinity, 3, 6);
  for (let b = start * 6, bEnd = end * 6; b < bEnd; b += 6) {
    for (let a = 0; a < 3; a++) {
      const c = work[b + a]! + work[b + 3 + a]!;
      if (c < out[a]!) out[a] = c;
      if (c > out[3 + a]!) out[3 + a] = c;
    }
  }
}
