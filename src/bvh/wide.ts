/**
 * Wide BVHs collapsed from the binary BVH, their GPU node words, and their CPU traversals (the
 * oracles of shaders/scene/bvh4.wgsl and cwbvh.wgsl, step for step, with the same work counts):
 *
 * - `bvh4`: four children per node, their fp32 boxes stored in the parent as structure of arrays
 *   (one 128-byte node fetch gives all four boxes), children visited nearest first.
 * - `cwbvh`: eight children per node, compressed to 80 bytes as in Ylitie, Karras & Laine, "Efficient
 *   Incoherent Ray Traversal on GPUs Through Compressed Wide BVHs" (HPG 2017): child boxes quantised
 *   to 8 bits per plane relative to a per-node origin and power-of-two scale per axis, rounded
 *   outward so that no hit is lost (the exact primitive test decides hits); children put in slots by
 *   the direction octant they suit and visited in the ray's octant order; a stack of node groups
 *   (child base, hit mask, internal-child mask).
 *
 * Both are collapsed from the binary tree, by the paper's SAH-optimal dynamic programme (the default)
 * or greedily: a wide node starts from its binary node's two children and keeps opening its
 * largest-area interior child until it has `width` children (WideStats.sahCost compares them). Leaves
 * are the binary tree's leaves (a leaf too large for the layout's count field is halved into pieces
 * of the same box), so they index the binary tree's leaf order: a hit reports the leaf position the
 * binary traversal reports, and the primitive arrays (triangles_hot, triangles_shading) are shared.
 *
 * Counting convention (the GPU's counters follow it): nodesVisited = wide nodes fetched (the root
 * always: its own box is not stored, its children's are), trianglesTested = primitive tests run.
 * Pure (no GPU).
 */
import { LanternError } from '../errors.ts';
import { halfAreaAt } from './box-area.ts';
import { prepareRay, T_MISS, type PreparedRay, type Ray } from './ray.ts';
import type { BvhStats } from './stats.ts';
import { Closest, type AnyTrace, type ClosestTrace } from './traverse.ts';
import type { Bvh } from './types.ts';

export const WIDE_LAYOUTS = ['bvh4', 'cwbvh'] as const;
export type WideLayout = (typeof WIDE_LAYOUTS)[number];

/** u32 words of one node (BVH4: 128 bytes; CWBVH: 80 bytes). */
export const BVH4_NODE_WORDS = 32;
export const CWBVH_NODE_WORDS = 20;
/** Children per node. */
export const WIDE_WIDTH: Record<WideLayout, number> = { bvh4: 4, cwbvh: 8 };
/** The most primitives one leaf reference can hold (BVH4: 4 bits of count; CWBVH: 5 bits of meta). */
export const WIDE_MAX_LEAF: Record<WideLayout, number> = { bvh4: 16, cwbvh: 31 };
/** Stack entries of the GPU traversals (BVH4_STACK_SIZE, CWBVH_STACK_SIZE in the WGSL). */
export const WIDE_STACK_SIZE = 64;

/**
 * A BVH4 child reference (one u32): an interior child's node index, or for a leaf
 * BVH4_LEAF_BIT | (count - 1) << 27 | first leaf position. An unused slot holds WIDE_EMPTY.
 */
export const BVH4_LEAF_BIT = 0x80000000;
const BVH4_FIRST_MASK = (1 << 27) - 1;
export const WIDE_EMPTY = 0xffffffff;

export interface WideStats {
  readonly layout: WideLayout;
  /** Wide nodes (each fetched as one record). */
  readonly nodeCount: number;
  /** Leaf references (binary leaves, or their pieces). */
  readonly leafCount: number;
  /** Depth of the deepest wide node (root 0); leaves hang one below their node. */
  readonly maxDepth: number;
  /** Mean depth of leaf references (a leaf child of the root has depth 1). */
  readonly meanLeafDepth: number;
  /** Mean children per node. */
  readonly meanChildren: number;
  /** Σ_nodes (A_node/A_root)·Ct + Σ_leaves (A_leaf/A_root)·count·Ci (a node's box: the union of its children's). */
  readonly sahCost: number;
  /** leafSizeHistogram[k] = leaf references holding k primitives. */
  readonly leafSizeHistogram: readonly number[];
  /** The most stack entries the GPU traversal can need (checked against WIDE_STACK_SIZE). */
  readonly stackNeeded: number;
  /** Bytes on the GPU: header, nodes and (CWBVH) the leaf table. */
  readonly gpuBytes: number;
  /** Collapse and packing time, milliseconds. */
  readonly buildMs: number;
}

export interface WideBvh {
  readonly layout: WideLayout;
  readonly nodeCount: number;
  /** Node words, node i at i × BVH4_NODE_WORDS or i × CWBVH_NODE_WORDS; child indices count from node 0 (the root). */
  readonly nodes: Uint32Array;
  /** CWBVH: the first leaf position of each leaf reference, node after node (a node's from its leaf base). Empty for BVH4. */
  readonly leafTable: Uint32Array;
  /** The binary tree's leaf order → source primitive (what a hit reports as `triangle`). */
  readonly triIndices: Uint32Array;
  readonly stats: WideStats;
}

// ---------------------------------------------------------------------------------------------------
// Collapse

/**
 * A child of a wide node. Its box is always a binary node's (`src`): a wide node's box, the union of
 * its children's, is its binary node's, and a piece of an oversized leaf keeps the leaf's box.
 */
interface WideLeaf {
  readonly kind: 'leaf';
  readonly src: number;
  readonly first: number;
  readonly count: number;
}

interface WideNode {
  readonly kind: 'node';
  readonly src: number;
  /** In storage (slot) order; CWBVH slots may hold undefined (an empty slot between used ones). */
  children: (WideNode | WideLeaf | undefined)[];
  index: number;
}

type WideChild = WideNode | WideLeaf;

/** A binary node or a piece of an oversized binary leaf (src: the binary node giving the box; count 0: interior). */
interface Item {
  readonly src: number;
  readonly first: number;
  readonly count: number;
}

function collapse(bvh: Bvh, layout: WideLayout): WideNode {
  const width = WIDE_WIDTH[layout], maxLeaf = WIDE_MAX_LEAF[layout];
  const { bounds, leftFirst, triCount } = bvh;
  const itemOf = (node: number): Item => ({ src: node, first: leftFirst[node]!, count: triCount[node]! });
  const openable = (it: Item) => it.count === 0 || it.count > maxLeaf;
  const open = (it: Item): Item[] => {
    if (it.count === 0) return [itemOf(leftFirst[it.src]!), itemOf(leftFirst[it.src]! + 1)];
    const half = Math.ceil(it.count / 2);
    return [
      { src: it.src, first: it.first, count: half },
      { src: it.src, first: it.first + half, count: it.count - half },
    ];
  };
  const build = (it: Item): WideNode => {
    const children = open(it);
    while (children.length < width) {
      let best = -1, bestArea = -1;
      for (let i = 0; i < children.length; i++) {
        const c = children[i]!;
        if (!openable(c)) continue;
        const a = halfAreaAt(bounds, c.src);
        if (a > bestArea) {
          best = i;
          bestArea = a;
        }
      }
      if (best < 0) break;
      children.splice(best, 1, ...open(children[best]!));
    }
    const kids: WideChild[] = children.map((c) => (openable(c) ? build(c) : { kind: 'leaf', src: c.src, first: c.first, count: c.count }));
    return { kind: 'node', src: it.src, children: kids, index: -1 };
  };
  const root = itemOf(0);
  if (bvh.triIndices.length === 0) return { kind: 'node', src: 0, children: [], index: 0 };
  if (!openable(root)) return { kind: 'node', src: 0, children: [{ kind: 'leaf', src: 0, first: root.first, count: root.count }], index: 0 };
  return build(root);
}

/**
 * CWBVH slot assignment (the paper's §3.2): slot s suits rays of direction octant s (bit k set: the
 * direction's k component is negative). Assigning child c to slot s costs the projection of the
 * child's centre offset on that octant's diagonal, so the child met first by such rays gets the slot;
 * pairs are taken greedily, cheapest first (ties: lower child, then lower slot). The traversal visits
 * slot (b ^ octant) for b = 0, 1, ...
 */
function assignSlots(node: WideNode, bounds: Float32Array, cost: Float64Array): void {
  const kids = node.children.filter((c): c is WideChild => c !== undefined);
  const centre = (n: number, k: number) => 0.5 * (bounds[n * 6 + k]! + bounds[n * 6 + 3 + k]!);
  for (let c = 0; c < kids.length; c++) {
    const d = [0, 1, 2].map((k) => centre(kids[c]!.src, k) - centre(node.src, k));
    for (let s = 0; s < 8; s++) cost[c * 8 + s] = (s & 1 ? -d[0]! : d[0]!) + (s & 2 ? -d[1]! : d[1]!) + (s & 4 ? -d[2]! : d[2]!);
  }
  const slots: (WideChild | undefined)[] = [undefined, undefined, undefined, undefined, undefined, undefined, undefined, undefined];
  let placed = 0, freeSlots = 0xff;
  for (let round = 0; round < kids.length; round++) {
    let bestC = -1, bestS = -1, best = Infinity;
    for (let c = 0; c < kids.length; c++) {
      if ((placed >> c) & 1) continue;
      for (let s = 0; s < 8; s++) {
        if (((freeSlots >> s) & 1) && cost[c * 8 + s]! < best) {
          best = cost[c * 8 + s]!;
          bestC = c;
          bestS = s;
        }
      }
    }
    slots[bestS] = kids[bestC];
    placed |= 1 << bestC;
    freeSlots &= ~(1 << bestS);
  }
  node.children = slots;
}

/**
 * The SAH-optimal collapse of Ylitie et al. (§3.1), a dynamic programme over the binary tree with the
 * same costs as WideStats.sahCost (Ct per wide node, Ci per primitive, weighted by area): for each
 * binary node n, cost(n) is the best of n as a leaf (its subtree's primitives, a contiguous range of
 * leaf positions, at most `leafMax` of them; a binary leaf is always one) and n as a wide node
 * (A(n)·Ct + the best split of its children into at most `width` subtrees), and dist(n, j) the best
 * cost of n's subtree as a forest of at most j children. Children come after their parent in the
 * binary arrays, so one pass from the last node back fills both; the tree is then read off top down
 * by recomputing the same minima (exact float equality: the same operations in the same order).
 */
function collapseSah(bvh: Bvh, layout: WideLayout): WideNode {
  const W = WIDE_WIDTH[layout], leafMax = Math.min(8, WIDE_MAX_LEAF[layout]);
  const { bounds, leftFirst, triCount, nodeCount } = bvh;
  const Ct = 1, Ci = 1;
  const count = new Float64Array(nodeCount), first = new Uint32Array(nodeCount);
  const cost = new Float64Array(nodeCount), dist = new Float64Array(nodeCount * W);
  const isLeaf = (n: number) => triCount[n]! > 0;
  const bestSplit = (n: number, j: number): [number, number] => {
    const l = leftFirst[n]!, r = l + 1;
    let best = Infinity, bestK = 1;
    for (let k = 1; k < j; k++) {
      const c = dist[l * W + k - 1]! + dist[r * W + j - k - 1]!;
      if (c < best) {
        best = c;
        bestK = k;
      }
    }
    return [best, bestK];
  };
  const asNode = (n: number) => halfAreaAt(bounds, n) * Ct + bestSplit(n, W)[0];
  const asLeaf = (n: number) => (isLeaf(n) || count[n]! <= leafMax ? halfAreaAt(bounds, n) * Ci * count[n]! : Infinity);
  for (let n = nodeCount - 1; n >= 0; n--) {
    if (n === 1) continue;
    if (isLeaf(n)) {
      count[n] = triCount[n]!;
      first[n] = leftFirst[n]!;
      cost[n] = asLeaf(n);
      for (let j = 0; j < W; j++) dist[n * W + j] = cost[n]!;
      continue;
    }
    const l = leftFirst[n]!;
    count[n] = count[l]! + count[l + 1]!;
    first[n] = Math.min(first[l]!, first[l + 1]!);
    cost[n] = Math.min(asLeaf(n), asNode(n));
    dist[n * W] = cost[n]!;
    for (let j = 2; j <= W; j++) dist[n * W + j - 1] = Math.min(dist[n * W + j - 2]!, bestSplit(n, j)[0]);
  }
  const leaf = (n: number): WideLeaf => ({ kind: 'leaf', src: n, first: first[n]!, count: count[n]! });
  // A binary leaf over the layout's limit is halved into pieces (as the greedy collapse does).
  const pieces = (n: number, f: number, c: number): WideChild[] => {
    if (c <= WIDE_MAX_LEAF[layout]) return [{ kind: 'leaf', src: n, first: f, count: c }];
    const half = Math.ceil(c / 2);
    return [{ kind: 'node', src: n, children: [...pieces(n, f, half), ...pieces(n, f + half, c - half)], index: -1 }];
  };
  const forest = (n: number, j: number): WideChild[] => {
    if (isLeaf(n)) return pieces(n, first[n]!, count[n]!);
    if (j === 1) return asLeaf(n) <= asNode(n) ? [leaf(n)] : [node(n)];
    if (dist[n * W + j - 1] === dist[n * W + j - 2]) return forest(n, j - 1);
    const k = bestSplit(n, j)[1];
    return [...forest(leftFirst[n]!, k), ...forest(leftFirst[n]! + 1, j - k)];
  };
  const node = (n: number): WideNode => {
    const k = bestSplit(n, W)[1];
    return { kind: 'node', src: n, children: [...forest(leftFirst[n]!, k), ...forest(leftFirst[n]! + 1, W - k)], index: -1 };
  };
  if (bvh.triIndices.length === 0) return { kind: 'node', src: 0, children: [], index: 0 };
  if (isLeaf(0)) return { kind: 'node', src: 0, children: pieces(0, first[0]!, count[0]!), index: 0 };
  return node(0);
}

/** Nodes in index order: breadth first, so each node's interior children have consecutive indices (CWBVH needs it; BVH4 shares it). */
function numberNodes(root: WideNode): WideNode[] {
  const order = [root];
  root.index = 0;
  for (let i = 0; i < order.length; i++) {
    for (const c of order[i]!.children) {
      if (c?.kind === 'node') {
        c.index = order.length;
        order.push(c);
      }
    }
  }
  return order;
}

// ---------------------------------------------------------------------------------------------------
// Packing

function packBvh4(order: readonly WideNode[], bounds: Float32Array): Uint32Array {
  const words = new Uint32Array(order.length * BVH4_NODE_WORDS);
  const f32 = new Float32Array(words.buffer);
  for (const node of order) {
    const o = node.index * BVH4_NODE_WORDS;
    for (let s = 0; s < 4; s++) {
      const c = node.children[s];
      if (!c) {
        words[o + 24 + s] = WIDE_EMPTY;
        continue;
      }
      for (let k = 0; k < 6; k++) f32[o + 4 * k + s] = bounds[c.src * 6 + k]!;
      if (c.kind === 'node') words[o + 24 + s] = c.index;
      else {
        if (c.first > BVH4_FIRST_MASK - 1) throw new LanternError(`BVH4: leaf position ${c.first} does not fit a 27-bit child reference`, 'Use --accel bvh or cwbvh for scenes of over 134 million primitives');
        words[o + 24 + s] = (BVH4_LEAF_BIT | ((c.count - 1) << 27) | c.first) >>> 0;
      }
    }
  }
  return words;
}

/**
 * The quantisation of axis k of a CWBVH node whose used children (boxes of binary nodes `srcs`) lie
 * from p: the exponent e (scale 2^e) and each child's planes in qlo / qhi, rounded outward so that
 * the f32 value p + q·2^e the GPU computes is at or beyond the exact plane. p + q·2^e: q·2^e is exact
 * and the f64 sum rounded to f32 is the f32 sum correctly rounded (53 ≥ 2·24 + 2), as on the GPU.
 */
function quantiseAxis(p: number, bounds: Float32Array, srcs: readonly number[], k: number, qlo: Uint8Array, qhi: Uint8Array): number {
  let extent = 0;
  for (const n of srcs) extent = Math.max(extent, bounds[n * 6 + 3 + k]! - p);
  let e = extent > 0 ? Math.max(-126, Math.ceil(Math.log2(extent / 255))) : -126;
  for (; e <= 127; e++) {
    const s = 2 ** e;
    let fits = true;
    for (let i = 0; i < srcs.length && fits; i++) {
      const lo = bounds[srcs[i]! * 6 + k]!, hi = bounds[srcs[i]! * 6 + 3 + k]!;
      let ql = Math.min(255, Math.max(0, Math.floor((lo - p) / s)));
      while (ql > 0 && Math.fround(p + ql * s) > lo) ql--;
      let qh = Math.max(0, Math.ceil((hi - p) / s));
      while (qh <= 255 && Math.fround(p + qh * s) < hi) qh++;
      fits = qh <= 255;
      qlo[i] = ql;
      qhi[i] = qh;
    }
    if (fits) return e;
  }
  throw new LanternError('CWBVH: a node box too large to quantise (coordinates beyond the f32 range?)');
}

/** The byte `b` (0..3) of word `w`. */
const byteOf = (w: number, b: number) => (w >>> (8 * b)) & 0xff;

function packCwbvh(order: readonly WideNode[], bounds: Float32Array): { nodes: Uint32Array; leafTable: Uint32Array } {
  const words = new Uint32Array(order.length * CWBVH_NODE_WORDS);
  const f32 = new Float32Array(words.buffer);
  const table: number[] = [];
  const qlo = new Uint8Array(8), qhi = new Uint8Array(8);
  const setByte = (w: number, b: number, v: number) => {
    words[w] = (words[w]! | (v << (8 * b))) >>> 0;
  };
  for (const node of order) {
    const o = node.index * CWBVH_NODE_WORDS;
    const slots: number[] = [], srcs: number[] = [];
    node.children.forEach((c, s) => {
      if (c) {
        slots.push(s);
        srcs.push(c.src);
      }
    });
    const leafBase = table.length;
    let imask = 0, childBase = 0;
    for (let k = 0; k < 3; k++) {
      let p = srcs.length > 0 ? Infinity : 0;
      for (const n of srcs) p = Math.min(p, bounds[n * 6 + k]!);
      f32[o + k] = p;
      const e = quantiseAxis(p, bounds, srcs, k, qlo, qhi);
      setByte(o + 3, k, e + 127);
      slots.forEach((s, i) => {
        setByte(o + 8 + 2 * k + (s >> 2), s & 3, qlo[i]!);
        setByte(o + 14 + 2 * k + (s >> 2), s & 3, qhi[i]!);
      });
    }
    for (const s of slots) {
      const c = node.children[s]!;
      if (c.kind === 'node') {
        if (imask === 0) childBase = c.index;
        imask |= 1 << s;
      } else {
        setByte(o + 6 + (s >> 2), s & 3, c.count | ((table.length - leafBase) << 5));
        table.push(c.first);
      }
    }
    setByte(o + 3, 3, imask);
    words[o + 4] = childBase;
    words[o + 5] = leafBase;
  }
  return { nodes: words, leafTable: Uint32Array.from(table) };
}

// ---------------------------------------------------------------------------------------------------
// Statistics

function measure(root: WideNode, layout: WideLayout, bounds: Float32Array) {
  const rootArea = halfAreaAt(bounds, root.src);
  const weight = (n: number) => (rootArea > 0 ? halfAreaAt(bounds, n) / rootArea : 1);
  let nodes = 0, leaves = 0, maxDepth = 0, leafDepthSum = 0, children = 0, sah = 0, stackNeeded = 0;
  const histogram: number[] = [0];
  const walk = (n: WideNode, depth: number, stackBefore: number) => {
    nodes++;
    maxDepth = Math.max(maxDepth, depth);
    sah += weight(n.src);
    let kids = 0;
    for (const c of n.children) if (c) kids++;
    children += kids;
    // BVH4 pushes every hit child and pops one; CWBVH keeps one group entry per level.
    stackNeeded = Math.max(stackNeeded, layout === 'bvh4' ? stackBefore + kids : depth);
    for (const c of n.children) {
      if (!c) continue;
      if (c.kind === 'node') walk(c, depth + 1, layout === 'bvh4' ? stackBefore + kids - 1 : 0);
      else {
        leaves++;
        leafDepthSum += depth + 1;
        sah += weight(c.src) * c.count;
        while (histogram.length <= c.count) histogram.push(0);
        histogram[c.count]!++;
      }
    }
  };
  walk(root, 0, 0);
  return { nodes, leaves, maxDepth, meanLeafDepth: leaves > 0 ? leafDepthSum / leaves : 0, meanChildren: children / nodes, sahCost: sah, histogram, stackNeeded };
}

/** How a wide tree is collapsed from the binary one: greedily (largest child opened first) or by the SAH dynamic programme. */
export const WIDE_COLLAPSES = ['greedy', 'sah'] as const;
export type WideCollapse = (typeof WIDE_COLLAPSES)[number];
// The programme: on the Stanford Dragon its SAH cost is at most the greedy one's (BVH4 3.54 vs 3.57,
// CWBVH 2.69 vs 2.70) with fuller nodes (BVH4 197k nodes vs 225k, CWBVH 102k vs 137k), for about 40 %
// more collapse time.
export const DEFAULT_WIDE_COLLAPSE: WideCollapse = 'sah';

export interface WideBuildOptions {
  readonly collapse?: WideCollapse;
}

/** The wide tree of `layout` collapsed from the binary `bvh`, packed as the GPU reads it. */
export function buildWideBvh(bvh: Bvh, layout: WideLayout, options: WideBuildOptions = {}): WideBvh {
  const t0 = performance.now();
  const root = (options.collapse ?? DEFAULT_WIDE_COLLAPSE) === 'sah' ? collapseSah(bvh, layout) : collapse(bvh, layout);
  let order = numberNodes(root);
  if (layout === 'cwbvh') {
    const cost = new Float64Array(64);
    for (const node of order) assignSlots(node, bvh.bounds, cost);
    // Slots moved interior children: number again so that they stay consecutive in slot order.
    order = numberNodes(root);
  }
  const m = measure(root, layout, bvh.bounds);
  if (m.stackNeeded > WIDE_STACK_SIZE) throw new LanternError(`${layout}: the tree needs ${m.stackNeeded} stack entries, more than the GPU traversal's ${WIDE_STACK_SIZE}`, 'Use --accel bvh');
  const packed = layout === 'bvh4' ? { nodes: packBvh4(order, bvh.bounds), leafTable: new Uint32Array(0) } : packCwbvh(order, bvh.bounds);
  const gpuBytes = wideRecords(packed, 8) * 32;
  return {
    layout,
    nodeCount: order.length,
    nodes: packed.nodes,
    leafTable: packed.leafTable,
    triIndices: bvh.triIndices,
    stats: {
      layout,
      nodeCount: m.nodes,
      leafCount: m.leaves,
      maxDepth: m.maxDepth,
      meanLeafDepth: m.meanLeafDepth,
      meanChildren: m.meanChildren,
      sahCost: m.sahCost,
      leafSizeHistogram: m.histogram,
      stackNeeded: m.stackNeeded,
      gpuBytes,
      buildMs: performance.now() - t0,
    },
  };
}

/** The statistics `lantern bvh-stats` prints for a wide layout, in the binary layout's shape (bvh/stats.ts). */
export function wideBvhStats(wide: WideBvh, binaryBuildMs: number, triangleBytes = 0): BvhStats {
  const s = wide.stats;
  const triangleCount = wide.triIndices.length;
  const leafPrims = s.leafSizeHistogram.reduce((a, n, k) => a + n * k, 0);
  return {
    triangleCount,
    nodeCount: s.nodeCount,
    leafCount: s.leafCount,
    maxDepth: s.maxDepth,
    meanLeafDepth: s.meanLeafDepth,
    leafSizeHistogram: s.leafSizeHistogram,
    meanLeafSize: s.leafCount > 0 ? leafPrims / s.leafCount : 0,
    sahCost: s.sahCost,
    nodeBytes: s.gpuBytes,
    triangleBytes: triangleCount * triangleBytes,
    bytesPerTriangle: (s.gpuBytes + triangleCount * triangleBytes) / Math.max(1, triangleCount),
    buildMs: binaryBuildMs + s.buildMs,
  };
}

/**
 * The wide tree as node-sized records of u32 words for bvh_nodes (gpu/pack/scene-pack.ts packGeometry
 * puts them from record `base`; shaders/scene/bvh4.wgsl, cwbvh.wgsl read them): a header record
 * (word 0: the word index of node 0, word 1: the word index of the leaf table, both counted from
 * record 0 of bvh_nodes; word 2: the layout, 0 BVH4, 1 CWBVH), then the nodes, then the leaf table.
 */
export function packWide(wide: Pick<WideBvh, 'nodes' | 'leafTable'> & { readonly layout: WideLayout }, base: number, strideWords: number): Uint32Array {
  const records = wideRecords(wide, strideWords);
  const words = new Uint32Array(records * strideWords);
  const nodesAt = strideWords, tableAt = strideWords + Math.ceil(wide.nodes.length / strideWords) * strideWords;
  words[0] = base * strideWords + nodesAt;
  words[1] = base * strideWords + tableAt;
  words[2] = wide.layout === 'bvh4' ? 0 : 1;
  words.set(wide.nodes, nodesAt);
  words.set(wide.leafTable, tableAt);
  return words;
}

/** Records of packWide's output. */
export function wideRecords(wide: Pick<WideBvh, 'nodes' | 'leafTable'>, strideWords: number): number {
  return 1 + Math.ceil(wide.nodes.length / strideWords) + Math.ceil(wide.leafTable.length / strideWords);
}

// ---------------------------------------------------------------------------------------------------
// CPU traversals (the oracles)

/** Slab test of a box given by its six planes, as ray.ts intersectAabb (and scene/intersect.wgsl intersect_aabb). */
function slab(x0: number, y0: number, z0: number, x1: number, y1: number, z1: number, r: PreparedRay, tBest: number): number {
  const tx0 = (x0 - r.ox) * r.ix, tx1 = (x1 - r.ox) * r.ix;
  const ty0 = (y0 - r.oy) * r.iy, ty1 = (y1 - r.oy) * r.iy;
  const tz0 = (z0 - r.oz) * r.iz, tz1 = (z1 - r.oz) * r.iz;
  const tNear = Math.max(Math.max(Math.min(tx0, tx1), Math.min(ty0, ty1)), Math.min(tz0, tz1));
  const tFar = Math.min(Math.min(Math.max(tx0, tx1), Math.max(ty0, ty1)), Math.max(tz0, tz1));
  return tNear <= tFar && tFar >= 0 && tNear < tBest ? tNear : T_MISS;
}

/** Child order of a BVH4 node: the four (t, ref) pairs through scene/bvh4.wgsl's sorting network (nearest first, misses last). */
function sortNetwork(t: number[], ref: number[]): void {
  const cx = (a: number, b: number) => {
    if (t[b]! < t[a]!) {
      [t[a], t[b]] = [t[b]!, t[a]!];
      [ref[a], ref[b]] = [ref[b]!, ref[a]!];
    }
  };
  cx(0, 1);
  cx(2, 3);
  cx(0, 2);
  cx(1, 3);
  cx(1, 2);
}

export interface WideTraceOptions {
  /** BVH4 closest hit: visit children nearest first (default, BVH4_SORT_CHILDREN) or in storage order. */
  readonly sortChildren?: boolean;
}

function bvh4Walk(wide: WideBvh, state: Closest, tBest: () => number, sort: boolean, onLeaf: (first: number, count: number) => boolean): void {
  const u32 = wide.nodes, f32 = new Float32Array(u32.buffer, u32.byteOffset, u32.length);
  const r = state.r;
  const stack: number[] = [];
  const t = [0, 0, 0, 0], ref = [0, 0, 0, 0];
  let node = 0;
  for (;;) {
    state.nodesVisited++;
    const o = node * BVH4_NODE_WORDS;
    const best = tBest();
    for (let s = 0; s < 4; s++) {
      ref[s] = u32[o + 24 + s]!;
      t[s] = ref[s] === WIDE_EMPTY ? T_MISS : slab(f32[o + s]!, f32[o + 4 + s]!, f32[o + 8 + s]!, f32[o + 12 + s]!, f32[o + 16 + s]!, f32[o + 20 + s]!, r, best);
    }
    if (sort) sortNetwork(t, ref);
    for (let s = 3; s >= 0; s--) if (t[s] !== T_MISS) stack.push(ref[s]!);
    for (;;) {
      const next = stack.pop();
      if (next === undefined) return;
      if ((next & BVH4_LEAF_BIT) !== 0) {
        if (onLeaf(next & BVH4_FIRST_MASK, ((next >>> 27) & 15) + 1)) return;
        continue;
      }
      node = next;
      break;
    }
  }
}

/** The CWBVH node's eight dequantised child boxes as scene/cwbvh.wgsl computes them (f32: p + q·2^e), six planes each. */
export function cwbvhChildBoxes(nodes: Uint32Array, node: number): Float32Array {
  const o = node * CWBVH_NODE_WORDS;
  const f32 = new Float32Array(nodes.buffer, nodes.byteOffset, nodes.length);
  const out = new Float32Array(48);
  for (let k = 0; k < 3; k++) {
    const p = f32[o + k]!, s = 2 ** (byteOf(nodes[o + 3]!, k) - 127);
    for (let slot = 0; slot < 8; slot++) {
      out[slot * 6 + k] = Math.fround(p + byteOf(nodes[o + 8 + 2 * k + (slot >> 2)]!, slot & 3) * s);
      out[slot * 6 + 3 + k] = Math.fround(p + byteOf(nodes[o + 14 + 2 * k + (slot >> 2)]!, slot & 3) * s);
    }
  }
  return out;
}

const ctz = (x: number) => 31 - Math.clz32(x & -x);
const popcount = (x: number) => {
  let n = 0;
  for (; x !== 0; x &= x - 1) n++;
  return n;
};

/** The ray's direction octant: bit k set where component k is negative (scene/cwbvh.wgsl ray_octant). */
export const rayOctant = (r: PreparedRay): number => (r.dx < 0 ? 1 : 0) | (r.dy < 0 ? 2 : 0) | (r.dz < 0 ? 4 : 0);

function cwbvhWalk(wide: WideBvh, state: Closest, tBest: () => number, onLeaf: (first: number, count: number) => boolean): void {
  const words = wide.nodes;
  const r = state.r;
  const oct = rayOctant(r);
  const stack: number[] = [];
  // The current node group: child base, hit mask in visiting order (bit b: slot b ^ oct), internal-child mask by slot. Starts as the root alone.
  let base = 0, hits = 1 << oct, imask = 1;
  for (;;) {
    if (hits === 0) {
      if (stack.length === 0) return;
      imask = stack.pop()!;
      hits = stack.pop()!;
      base = stack.pop()!;
    }
    const b = ctz(hits);
    hits &= hits - 1;
    const slot = b ^ oct;
    const child = base + popcount(imask & ((1 << slot) - 1));
    if (hits !== 0) stack.push(base, hits, imask);
    state.nodesVisited++;
    const o = child * CWBVH_NODE_WORDS;
    const boxes = cwbvhChildBoxes(words, child);
    const nodeImask = byteOf(words[o + 3]!, 3);
    const best = tBest();
    let ihits = 0, lhits = 0;
    for (let s = 0; s < 8; s++) {
      const meta = byteOf(words[o + 6 + (s >> 2)]!, s & 3);
      const internal = ((nodeImask >> s) & 1) !== 0;
      if (!internal && meta === 0) continue;
      const q = s * 6;
      if (slab(boxes[q]!, boxes[q + 1]!, boxes[q + 2]!, boxes[q + 3]!, boxes[q + 4]!, boxes[q + 5]!, r, best) === T_MISS) continue;
      if (internal) ihits |= 1 << (s ^ oct);
      else lhits |= 1 << (s ^ oct);
    }
    while (lhits !== 0) {
      const s = ctz(lhits) ^ oct;
      lhits &= lhits - 1;
      const meta = byteOf(words[o + 6 + (s >> 2)]!, s & 3);
      if (onLeaf(wide.leafTable[words[o + 5]! + (meta >> 5)]!, meta & 31)) return;
    }
    base = words[o + 4]!;
    hits = ihits;
    imask = nodeImask;
  }
}

/** Closest hit through the wide tree (the oracle of scene/bvh4.wgsl bvh4_closest, scene/cwbvh.wgsl cwbvh_closest). */
export function traceWide(wide: WideBvh, positions: Float32Array, ray: Ray, kinds?: Uint8Array, options: WideTraceOptions = {}): ClosestTrace {
  const state = new Closest(positions, kinds, wide.triIndices, prepareRay(ray));
  const onLeaf = (first: number, count: number) => {
    state.leaf(first, count);
    return false;
  };
  if (wide.layout === 'bvh4') bvh4Walk(wide, state, () => state.tBest, options.sortChildren ?? true, onLeaf);
  else cwbvhWalk(wide, state, () => state.tBest, onLeaf);
  return state.result();
}

/** Any hit at tMin < t < tMax through the wide tree (BVH4: storage order, as bvh4_any). */
export function traceWideAny(wide: WideBvh, positions: Float32Array, ray: Ray, kinds?: Uint8Array): AnyTrace {
  const state = new Closest(positions, kinds, wide.triIndices, prepareRay(ray));
  let hit = false;
  const onLeaf = (first: number, count: number) => (hit = state.leafAny(first, count));
  if (wide.layout === 'bvh4') bvh4Walk(wide, state, () => state.r.tMax, false, onLeaf);
  else cwbvhWalk(wide, state, () => state.r.tMax, onLeaf);
  return state.anyResult(hit);
}
