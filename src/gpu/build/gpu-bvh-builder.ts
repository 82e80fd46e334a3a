/**
 * A BVH builder on the GPU, of the PLOC family (Meister & Bittner 2018, "Parallel Locally-Ordered
 * Clustering for BVH Construction"): triangle boxes and 30-bit Morton codes of their centroids
 * (shaders/build/morton), an LSD radix sort of 4-bit digits (build/radix-sort, with build/scan's
 * prefix sums), then iterations of nearest-neighbour merging within a search radius and prefix-sum
 * compaction until one cluster is left (build/ploc; the last 256 clusters in one workgroup), and
 * finally the tree written out in the renderer's binary layout (build/emit; bvh/types.ts), subtrees
 * of at most `maxLeafSize` triangles collapsed into one leaf where the SAH says a leaf is cheaper (a
 * bottom-up cost computed as nodes are made, so the collapse costs no pass of its own).
 *
 * The clustering loop's length is known only on the GPU: the host encodes a batch of iterations
 * whose indirect dispatch sizes drop to zero at 256 clusters, then the one-workgroup tail, reads the
 * cluster count back, and encodes another batch only if one cluster is not reached (rare: the first
 * batch is sized from log2 of the count).
 * Each batch is one timestamped compute pass; `gpuMs` sums them and excludes the upload of positions.
 */
import { LanternError } from '../../errors.ts';
import { bvhStats } from '../../bvh/stats.ts';
import type { Bvh } from '../../bvh/types.ts';
import { ComputeKernel, type NamedResource } from '../kernel.ts';
import { createBufferWithData, readBuffer } from '../readback.ts';
import { GpuTimer } from '../timestamps.ts';
import { reflectModule, structLayout } from '../wgsl/reflect.ts';

export interface GpuBvhBuildOptions {
  /** Clusters searched on each side for a nearest neighbour (PLOC's r; 1..32, default 16). */
  readonly searchRadius: number;
  /** Subtrees of at most this many triangles may become one leaf (1..32; 1 keeps PLOC's one triangle per leaf). */
  readonly maxLeafSize: number;
  /** SAH cost of visiting an interior node (Ct), for the collapse. */
  readonly traversalCost: number;
  /** SAH cost of one ray/triangle test (Ci), for the collapse. */
  readonly intersectionCost: number;
  /**
   * Clustering iterations encoded before each read-back of the cluster count (0: 3·log2(n) + 8 first,
   * then 16). Fewer cost read-backs (wall time), more cost empty dispatches (a few µs of GPU time each).
   */
  readonly batchIterations: number;
  /**
   * 'stages' (default): one timestamped pass per stage (sort, each clustering batch, output), the
   * honest total. 'kernels': one pass per dispatch, summed by kernel in GpuBvh.kernels, to see where
   * the time goes; passes add gaps between them that the totals then leave out.
   */
  readonly timing: 'stages' | 'kernels';
}

export const DEFAULT_GPU_BVH_BUILD_OPTIONS: GpuBvhBuildOptions = Object.freeze({
  searchRadius: 16,
  maxLeafSize: 8,
  traversalCost: 1,
  intersectionCost: 1,
  batchIterations: 0,
  timing: 'stages',
});

/** What one build leaves on the GPU, and how long it took. */
export interface GpuBvh {
  /** BvhNode records (shaders/scene/types.wgsl) in the layout of bvh/types.ts; `nodeCount` are used. */
  readonly nodes: GPUBuffer;
  /** Leaf order -> source triangle (u32 each). */
  readonly triIndices: GPUBuffer;
  readonly nodeCount: number;
  readonly triangleCount: number;
  /** Clustering iterations that merged something. */
  readonly iterations: number;
  /** Sum of the build's timestamped passes (upload excluded); undefined without timestamp queries. */
  readonly gpuMs: number | undefined;
  /** GPU time of each stage: the sort, each clustering batch, the output. */
  readonly passes: readonly { name: string; ms: number }[];
  /** With timing 'kernels': GPU time and dispatches of each kernel (entry point), summed over the build. */
  readonly kernels?: readonly { name: string; ms: number; dispatches: number }[];
  /** Wall clock from the first encode to the result's last read-back (includes the batches' read-backs). */
  readonly wallMs: number;
}

/** Radix passes of 4 bits over the 30-bit Morton codes (an even number: the result ends where it began). */
const SORT_PASSES = 8;
const RADIX_BITS = 4;
const RADIX = 16;
const SORT_BLOCK = 1024;
const SCAN_BLOCK = 1024;
const THREADS = 256;
/** Clustering iterations in a later batch, when the first did not reach one cluster. */
const LATER_BATCH = 16;
/** One dispatch dimension's workgroups: WebGPU's guaranteed maximum. */
const MAX_GROUPS = 65535;
/** Byte offsets of the indirect dispatch slots (shaders/build/ploc-types.wgsl ARGS_*). */
const ARGS = { clusters: 0, scanBlocks: 12, single: 24, emit: 36, bytes: 48 } as const;
/** Clusters ploc_tail finishes in one workgroup (shaders/build/ploc-types.wgsl TAIL_CLUSTERS). */
const TAIL_CLUSTERS = 256;

function resolveOptions(partial: Partial<GpuBvhBuildOptions>): GpuBvhBuildOptions {
  const o = { ...DEFAULT_GPU_BVH_BUILD_OPTIONS, ...partial };
  const bad = (what: string): never => {
    throw new LanternError(`invalid GPU BVH build option: ${what}`);
  };
  if (!Number.isInteger(o.searchRadius) || o.searchRadius < 1 || o.searchRadius > 32) bad(`searchRadius must be an integer in [1, 32], got ${o.searchRadius}`);
  if (!Number.isInteger(o.maxLeafSize) || o.maxLeafSize < 1 || o.maxLeafSize > 32) bad(`maxLeafSize must be an integer in [1, 32], got ${o.maxLeafSize}`);
  if (!(o.traversalCost >= 0 && o.traversalCost < Infinity)) bad(`traversalCost must be finite and >= 0, got ${o.traversalCost}`);
  if (!(o.intersectionCost > 0 && o.intersectionCost < Infinity)) bad(`intersectionCost must be finite and > 0, got ${o.intersectionCost}`);
  if (!Number.isInteger(o.batchIterations) || o.batchIterations < 0) bad(`batchIterations must be an integer >= 0, got ${o.batchIterations}`);
  if (o.timing !== 'stages' && o.timing !== 'kernels') bad(`timing must be 'stages' or 'kernels', got ${String(o.timing)}`);
  return o;
}

interface Kernels {
  primitiveBoxes: ComputeKernel;
  mortonCodes: ComputeKernel;
  histogram: ComputeKernel;
  scatter: ComputeKernel;
  scanReduce: ComputeKernel;
  scanBlockSums: ComputeKernel;
  scanApply: ComputeKernel;
  init: ComputeKernel;
  nearest: ComputeKernel;
  merge: ComputeKernel;
  compact: ComputeKernel;
  finalize: ComputeKernel;
  tail: ComputeKernel;
  emitRoot: ComputeKernel;
  emitStep: ComputeKernel;
  emitLevel: ComputeKernel;
}

export class GpuBvhBuilder {
  private constructor(
    private readonly device: GPUDevice,
    readonly options: GpuBvhBuildOptions,
    private readonly kernels: Kernels,
  ) {}

  static async create(device: GPUDevice, options: Partial<GpuBvhBuildOptions> = {}): Promise<GpuBvhBuilder> {
    const o = resolveOptions(options);
    const constants = { SEARCH_RADIUS: o.searchRadius, MAX_LEAF_SIZE: o.maxLeafSize, TRAVERSAL_COST: o.traversalCost, INTERSECTION_COST: o.intersectionCost };
    const k = (module: string, entryPoint: string, withConstants = false) =>
      ComputeKernel.create(device, { module: `build/${module}`, entryPoint, ...(withConstants ? { constants } : {}) });
    const [primitiveBoxes, mortonCodes, histogram, scatter, scanReduce, scanBlockSums, scanApply, init, nearest, merge, compact, finalize, tail, emitRoot, emitStep, emitLevel] = await Promise.all([
      k('morton', 'primitive_boxes'),
      k('morton', 'morton_codes'),
      k('radix-sort', 'radix_histogram'),
      k('radix-sort', 'radix_scatter'),
      k('scan', 'scan_reduce'),
      k('scan', 'scan_block_sums_in_place'),
      k('scan', 'scan_apply'),
      k('ploc', 'ploc_init', true),
      k('ploc', 'ploc_nearest', true),
      k('ploc', 'ploc_merge', true),
      k('ploc', 'ploc_compact', true),
      k('ploc', 'ploc_finalize', true),
      k('ploc', 'ploc_tail', true),
      k('emit', 'emit_root'),
      k('emit', 'emit_step'),
      k('emit', 'emit_level'),
    ]);
    return new GpuBvhBuilder(device, o, { primitiveBoxes, mortonCodes, histogram, scatter, scanReduce, scanBlockSums, scanApply, init, nearest, merge, compact, finalize, tail, emitRoot, emitStep, emitLevel });
  }

  /**
   * Sorts (key, index) pairs by key on the GPU with the build's radix sort, stably: for its tests.
   * Returns the keys in order and, for each, its index in `keys`.
   */
  async sortPairs(keys: Uint32Array): Promise<{ keys: Uint32Array; values: Uint32Array }> {
    const device = this.device, count = keys.length;
    if (count < 1) throw new LanternError('nothing to sort');
    const scratch: GPUBuffer[] = [];
    const storage = (label: string, data: Uint32Array) => {
      const b = createBufferWithData(device, `gpu sort ${label}`, data, GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC);
      scratch.push(b);
      return b;
    };
    try {
      const keyBuffers = [storage('keys a', keys), storage('keys b', new Uint32Array(count))] as const;
      const valueBuffers = [storage('values a', Uint32Array.from({ length: count }, (_, i) => i)), storage('values b', new Uint32Array(count))] as const;
      const blocks = Math.ceil(count / SORT_BLOCK);
      const sortCounts = storage('counts', new Uint32Array(RADIX * blocks));
      const blockSums = storage('block sums', new Uint32Array(Math.ceil((RADIX * blocks) / SCAN_BLOCK)));
      const groups = this.radixSortGroups(count, keyBuffers, valueBuffers, sortCounts, blockSums, scratch);
      const encoder = device.createCommandEncoder({ label: 'gpu sort' });
      const rec = new Recorder(undefined, false);
      rec.begin(encoder, 'sort');
      this.encodeRadixSort(rec, groups);
      rec.end();
      device.queue.submit([encoder.finish()]);
      const [k, v] = await Promise.all([readBuffer(device, keyBuffers[0], count * 4), readBuffer(device, valueBuffers[0], count * 4)]);
      return { keys: new Uint32Array(k), values: new Uint32Array(v) };
    } finally {
      for (const b of scratch) b.destroy();
    }
  }

  /** The bind groups of the radix sort's passes over `count` pairs in keys[0] / values[0] (where they end). */
  private radixSortGroups(count: number, keys: readonly [GPUBuffer, GPUBuffer], values: readonly [GPUBuffer, GPUBuffer], sortCounts: GPUBuffer, blockSums: GPUBuffer, scratch: GPUBuffer[]): RadixSortGroups {
    const kn = this.kernels;
    const blocks = Math.ceil(count / SORT_BLOCK);
    const countLength = RADIX * blocks;
    const lengthBuffer = createBufferWithData(this.device, 'gpu sort count length', new Uint32Array([countLength]), GPUBufferUsage.STORAGE);
    scratch.push(lengthBuffer);
    const scan = { scan_data: sortCounts, scan_block_sums: blockSums, scan_length: lengthBuffer };
    const passes = Array.from({ length: SORT_PASSES }, (_, p) => {
      const [from, to] = p % 2 === 0 ? ([0, 1] as const) : ([1, 0] as const);
      const params = createBufferWithData(this.device, `gpu sort pass ${p}`, new Uint32Array([RADIX_BITS * p, count, blocks, 0]), GPUBufferUsage.UNIFORM);
      scratch.push(params);
      const resources = { sort_params: params, keys_in: keys[from], values_in: values[from], keys_out: keys[to], values_out: values[to], sort_counts: sortCounts };
      return { histogram: { 0: kn.histogram.bindGroup(0, resources) }, scatter: { 0: kn.scatter.bindGroup(0, resources) } };
    });
    return {
      blocks,
      countLength,
      passes,
      reduce: { 0: kn.scanReduce.bindGroup(0, scan) },
      blockSums: { 0: kn.scanBlockSums.bindGroup(0, scan) },
      apply: { 0: kn.scanApply.bindGroup(0, scan) },
    };
  }

  private encodeRadixSort(rec: Recorder, g: RadixSortGroups): void {
    const kn = this.kernels;
    for (const p of g.passes) {
      rec.dispatch(kn.histogram, p.histogram, g.blocks);
      rec.dispatch(kn.scanReduce, g.reduce, Math.ceil(g.countLength / SCAN_BLOCK));
      rec.dispatch(kn.scanBlockSums, g.blockSums, 1);
      rec.dispatch(kn.scanApply, g.apply, Math.ceil(g.countLength / SCAN_BLOCK));
      rec.dispatch(kn.scatter, p.scatter, g.blocks);
    }
  }

  /**
   * Builds a BVH over `count` triangles of 9 floats each (v0, v1, v2 xyz): a Float32Array, uploaded
   * first, or a GPU buffer with STORAGE usage already holding them.
   */
  async build(positions: GPUBuffer | Float32Array, count: number): Promise<GpuBvh> {
    const device = this.device;
    if (!Number.isInteger(count) || count < 1) throw new LanternError(`the GPU BVH builder needs at least one triangle, got ${count}`);
    if (Math.ceil(count / THREADS) > MAX_GROUPS) throw new LanternError(`the GPU BVH builder takes at most ${MAX_GROUPS * THREADS} triangles, got ${count}`);
    const floats = count * 9;
    if (positions instanceof Float32Array) {
      if (positions.length < floats) throw new LanternError(`${count} triangles need ${floats} position floats, got ${positions.length}`);
      checkFinite(positions, floats);
    } else if (positions.size < floats * 4) {
      throw new LanternError(`${count} triangles need a position buffer of ${floats * 4} bytes, got ${positions.size}`);
    }
    const scratch: GPUBuffer[] = [];
    const buffer = (label: string, bytes: number, usage = 0): GPUBuffer => {
      const b = device.createBuffer({ label: `gpu bvh ${label}`, size: Math.max(16, Math.ceil(bytes / 4) * 4), usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC | GPUBufferUsage.COPY_DST | usage });
      scratch.push(b);
      return b;
    };
    const uniform = (label: string, words: number[]): GPUBuffer => {
      const b = createBufferWithData(device, `gpu bvh ${label}`, new Uint32Array([...words, 0, 0, 0, 0].slice(0, Math.max(4, words.length))), GPUBufferUsage.UNIFORM);
      scratch.push(b);
      return b;
    };

    const positionBuffer = positions instanceof Float32Array
      ? (() => {
          const b = createBufferWithData(device, 'gpu bvh positions', positions.subarray(0, floats), GPUBufferUsage.STORAGE);
          scratch.push(b);
          return b;
        })()
      : positions;
    const types = reflectModule('build/emit').defs;
    const aabbBytes = structLayout(types, 'Aabb').stride;
    const clusterBytes = structLayout(types, 'Cluster').stride;
    const plocNodeBytes = structLayout(types, 'PlocNode').stride;
    const stateBytes = structLayout(types, 'BuildState').stride;
    const bvhNode = structLayout(types, 'BvhNode');

    const sortBlocks = Math.ceil(count / SORT_BLOCK);
    const sortCountLength = RADIX * sortBlocks;
    const params = uniform('params', [count]);
    const primBoxes = buffer('primitive boxes', count * aabbBytes);
    const centroidBounds = buffer('centroid bounds', 24);
    const keys = [buffer('keys a', count * 4), buffer('keys b', count * 4)] as const;
    const values = [buffer('values a', count * 4), buffer('values b', count * 4)] as const;
    const sortCounts = buffer('sort counts', sortCountLength * 4);
    const blockSums = buffer('scan block sums', Math.ceil(Math.max(count, sortCountLength) / SCAN_BLOCK) * 4);
    const state = buffer('state', stateBytes);
    const dispatchArgs = buffer('dispatch args', ARGS.bytes, GPUBufferUsage.INDIRECT);
    const clusterNodes = buffer('cluster nodes', count * 4);
    const clusters = buffer('clusters', count * clusterBytes);
    const mergedNodes = buffer('merged nodes', count * 4);
    const merged = buffer('merged clusters', count * clusterBytes);
    const nearest = buffer('nearest', count * 4);
    const keep = buffer('keep', count * 4);
    const plocNodes = buffer('ploc nodes', Math.max(1, count - 1) * plocNodeBytes);
    const levelEnd = buffer('level ends', count * 4);
    const nodePlaces = buffer('node places', Math.max(1, count - 1) * 8);
    const stateRead = device.createBuffer({ label: 'gpu bvh state read', size: stateBytes, usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST });
    scratch.push(stateRead);
    // The outputs outlive the build: the caller owns them.
    const nodes = device.createBuffer({ label: 'gpu bvh nodes', size: 2 * count * bvhNode.stride, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC | GPUBufferUsage.COPY_DST });
    const triIndices = device.createBuffer({ label: 'gpu bvh tri indices', size: Math.max(16, count * 4), usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC | GPUBufferUsage.COPY_DST });

    const kn = this.kernels;
    const shared: Record<string, NamedResource> = {
      build_params: params, ploc_params: params, emit_params: params,
      positions: positionBuffer, prim_boxes: primBoxes, centroid_bounds: centroidBounds,
      morton_keys: keys[0], morton_values: values[0], sorted_prims: values[0],
      state, dispatch_args: dispatchArgs, cluster_nodes: clusterNodes, clusters, merged_nodes: mergedNodes, merged, nearest,
      nodes: plocNodes, keep, level_end: levelEnd, node_places: nodePlaces, bvh_out: nodes, tri_indices: triIndices,
    };
    const group = (kernel: ComputeKernel, extra: Record<string, NamedResource> = {}) => ({ 0: kernel.bindGroup(0, { ...shared, ...extra }) });
    const plocScan = { scan_data: keep, scan_block_sums: blockSums, scan_length: { buffer: state, offset: 0, size: 4 } };
    const sort = this.radixSortGroups(count, keys, values, sortCounts, blockSums, scratch);
    const g = {
      primitiveBoxes: group(kn.primitiveBoxes), mortonCodes: group(kn.mortonCodes),
      init: group(kn.init), nearest: group(kn.nearest), merge: group(kn.merge), compact: group(kn.compact), finalize: group(kn.finalize), tail: group(kn.tail),
      plocReduce: group(kn.scanReduce, plocScan), plocBlockSums: group(kn.scanBlockSums, plocScan), plocApply: group(kn.scanApply, plocScan),
      emitRoot: group(kn.emitRoot), emitStep: group(kn.emitStep), emitLevel: group(kn.emitLevel),
    };

    const perKernel = this.options.timing === 'kernels';
    const timer = device.features.has('timestamp-query') ? new GpuTimer(device, perKernel ? KERNEL_TIMER_CAPACITY : 64) : undefined;
    const rec = new Recorder(timer, perKernel);
    const groupsOf = (items: number, per: number) => Math.ceil(items / per);
    const iterations = (n: number) => {
      for (let i = 0; i < n; i++) {
        rec.indirect(kn.nearest, g.nearest, dispatchArgs, ARGS.clusters);
        rec.indirect(kn.merge, g.merge, dispatchArgs, ARGS.clusters);
        rec.indirect(kn.scanReduce, g.plocReduce, dispatchArgs, ARGS.scanBlocks);
        rec.indirect(kn.scanBlockSums, g.plocBlockSums, dispatchArgs, ARGS.single);
        rec.indirect(kn.scanApply, g.plocApply, dispatchArgs, ARGS.scanBlocks);
        rec.indirect(kn.compact, g.compact, dispatchArgs, ARGS.clusters);
        rec.dispatch(kn.finalize, g.finalize, 1);
      }
    };
    const readState = async (encoder: GPUCommandEncoder) => {
      encoder.copyBufferToBuffer(state, 0, stateRead, 0, stateBytes);
      device.queue.submit([encoder.finish()]);
      await stateRead.mapAsync(GPUMapMode.READ);
      const words = new Uint32Array(stateRead.getMappedRange().slice(0));
      stateRead.unmap();
      const layout = structLayout(types, 'BuildState');
      return { clusterCount: words[layout.word('cluster_count')]!, iterations: words[layout.word('iteration_count')]!, pairs: words[layout.word('pair_count')]! };
    };

    device.pushErrorScope('validation');
    try {
      const startMs = performance.now();
      // Centroid bounds start empty: +max and -max as ordered images (shaders/build/morton.wgsl).
      device.queue.writeBuffer(centroidBounds, 0, new Uint32Array([0xffffffff, 0xffffffff, 0xffffffff, 0, 0, 0]));
      let encoder = device.createCommandEncoder({ label: 'gpu bvh build' });
      rec.begin(encoder, 'sort');
      rec.dispatch(kn.primitiveBoxes, g.primitiveBoxes, groupsOf(count, THREADS));
      rec.dispatch(kn.mortonCodes, g.mortonCodes, groupsOf(count, THREADS));
      this.encodeRadixSort(rec, sort);
      rec.dispatch(kn.init, g.init, groupsOf(count, THREADS));
      rec.end();
      // PLOC (r = 16) took 40 and 45 iterations on the Dragon at 11k and 48k triangles (2.9 log2 n),
      // 3.5–4.7 log2(n) on random soups and spheres of 3k–100k: the count falls by 20–45 % an
      // iteration, less in the tail, which ploc_tail does at once from TAIL_CLUSTERS down.
      // Iterations past that dispatch nothing but cost a few microseconds each; a batch too short
      // costs a read-back (wall time, not GPU time).
      let batch = this.options.batchIterations || (count <= TAIL_CLUSTERS ? 0 : Math.ceil(3 * Math.log2(count / TAIL_CLUSTERS)) + 8);
      let batchNumber = 0;
      let s: Awaited<ReturnType<typeof readState>>;
      for (;;) {
        rec.begin(encoder, `cluster ${++batchNumber}`);
        iterations(batch);
        // Direct: it writes the dispatch sizes (and does nothing unless 1 < clusters <= TAIL_CLUSTERS).
        rec.dispatch(kn.tail, g.tail, 1);
        rec.end();
        s = await readState(encoder);
        if (s.clusterCount <= 1) break;
        encoder = device.createCommandEncoder({ label: 'gpu bvh build (more iterations)' });
        batch = this.options.batchIterations || LATER_BATCH;
      }
      encoder = device.createCommandEncoder({ label: 'gpu bvh output' });
      rec.begin(encoder, 'output');
      rec.dispatch(kn.emitRoot, g.emitRoot, 1);
      for (let level = 0; level < s.iterations; level++) {
        rec.dispatch(kn.emitStep, g.emitStep, 1);
        rec.indirect(kn.emitLevel, g.emitLevel, dispatchArgs, ARGS.emit);
      }
      rec.end();
      timer?.resolve(encoder);
      const done = await readState(encoder);
      const timed = timer ? await timer.read() : [];
      const passes = sumBy(timed, (name) => name.split('|')[0]!);
      const kernels = perKernel && timer ? sumBy(timed, (name) => name.split('|')[1]!) : undefined;
      const wallMs = performance.now() - startMs;
      const error = await device.popErrorScope();
      if (error) throw new Error(`GPU BVH build: WebGPU rejected a command: ${error.message}`);
      return {
        nodes,
        triIndices,
        nodeCount: 2 + 2 * done.pairs,
        triangleCount: count,
        iterations: done.iterations,
        gpuMs: timer ? passes.reduce((sum, p) => sum + p.ms, 0) : undefined,
        passes: passes.map(({ name, ms }) => ({ name, ms })),
        ...(kernels ? { kernels } : {}),
        wallMs,
      };
    } finally {
      timer?.destroy();
      for (const b of scratch) if (b !== positions) b.destroy();
    }
  }
}

type Groups = Record<number, GPUBindGroup>;

interface RadixSortGroups {
  readonly blocks: number;
  readonly countLength: number;
  readonly passes: readonly { histogram: Groups; scatter: Groups }[];
  readonly reduce: Groups;
  readonly blockSums: Groups;
  readonly apply: Groups;
}

/** Passes of one build with kernel timing: about 11 per clustering iteration and level, well within. */
const KERNEL_TIMER_CAPACITY = 2048;

/**
 * Records dispatches into compute passes: one timestamped pass per stage, or with `perKernel` one per
 * dispatch, named `stage|entry point` so the times can be summed either way.
 */
class Recorder {
  private encoder: GPUCommandEncoder | undefined;
  private stage = '';
  private pass: GPUComputePassEncoder | undefined;

  constructor(
    private readonly timer: GpuTimer | undefined,
    private readonly perKernel: boolean,
  ) {}

  begin(encoder: GPUCommandEncoder, stage: string): void {
    this.encoder = encoder;
    this.stage = stage;
    if (!this.perKernel) this.pass = this.open(stage, stage);
  }

  dispatch(kernel: ComputeKernel, groups: Groups, x: number): void {
    const pass = this.passFor(kernel);
    kernel.dispatch(pass, groups, x);
    if (this.perKernel) pass.end();
  }

  indirect(kernel: ComputeKernel, groups: Groups, args: GPUBuffer, offset: number): void {
    const pass = this.passFor(kernel);
    pass.setPipeline(kernel.pipeline);
    pass.setBindGroup(0, groups[0]!);
    pass.dispatchWorkgroupsIndirect(args, offset);
    if (this.perKernel) pass.end();
  }

  end(): void {
    this.pass?.end();
    this.pass = undefined;
  }

  private passFor(kernel: ComputeKernel): GPUComputePassEncoder {
    if (!this.perKernel) return this.pass!;
    const entry = kernel.label.slice(kernel.label.indexOf(':') + 1);
    return this.open(`${this.stage}|${entry}`, `${this.stage} ${entry}`);
  }

  private open(timerName: string, label: string): GPUComputePassEncoder {
    return this.encoder!.beginComputePass({ label: `gpu bvh ${label}`, ...(this.timer ? { timestampWrites: this.timer.timestampWrites(timerName) } : {}) });
  }
}

/** Sums timed passes by a key of their names, in the order keys first appear, counting them. */
function sumBy(timed: readonly { name: string; ms: number }[], key: (name: string) => string): { name: string; ms: number; dispatches: number }[] {
  const sums = new Map<string, { name: string; ms: number; dispatches: number }>();
  for (const t of timed) {
    const k = key(t.name);
    const s = sums.get(k) ?? { name: k, ms: 0, dispatches: 0 };
    s.ms += t.ms;
    s.dispatches++;
    sums.set(k, s);
  }
  return [...sums.values()];
}

function checkFinite(positions: Float32Array, floats: number): void {
  for (let i = 0; i < floats; i++) {
    const v = positions[i]!;
    if (v - v !== 0) throw new LanternError(`triangle ${Math.floor(i / 9)} has a non-finite vertex coordinate`, 'check the mesh for NaN or infinite positions');
  }
}

/**
 * Reads a GPU-built BVH back into the CPU form (bvh/types.ts), for the CPU oracle, statistics and
 * the debug views. Its stats' buildMs is the GPU time (wall clock without timestamp queries).
 */
export async function readBackBvh(device: GPUDevice, built: GpuBvh): Promise<Bvh> {
  const layout = structLayout(reflectModule('build/emit').defs, 'BvhNode');
  const nodeBytes = built.nodeCount * layout.stride;
  const staging = device.createBuffer({ label: 'gpu bvh read-back', size: nodeBytes + built.triangleCount * 4, usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST });
  try {
    const encoder = device.createCommandEncoder({ label: 'gpu bvh read-back' });
    encoder.copyBufferToBuffer(built.nodes, 0, staging, 0, nodeBytes);
    encoder.copyBufferToBuffer(built.triIndices, 0, staging, nodeBytes, built.triangleCount * 4);
    device.queue.submit([encoder.finish()]);
    await staging.mapAsync(GPUMapMode.READ);
    const bytes = staging.getMappedRange().slice(0);
    const f = new Float32Array(bytes, 0, nodeBytes / 4);
    const u = new Uint32Array(bytes, 0, nodeBytes / 4);
    const n = built.nodeCount, stride = layout.strideWords;
    const lo = layout.word('aabb_min', 'vec3f'), hi = layout.word('aabb_max', 'vec3f');
    const lf = layout.word('left_first', 'u32'), tc = layout.word('tri_count', 'u32');
    const bounds = new Float32Array(n * 6), leftFirst = new Uint32Array(n), triCount = new Uint32Array(n);
    for (let i = 0; i < n; i++) {
      const r = i * stride;
      for (let a = 0; a < 3; a++) {
        bounds[i * 6 + a] = f[r + lo + a]!;
        bounds[i * 6 + 3 + a] = f[r + hi + a]!;
      }
      leftFirst[i] = u[r + lf]!;
      triCount[i] = u[r + tc]!;
    }
    const triIndices = new Uint32Array(bytes, nodeBytes, built.triangleCount).slice();
    const buildMs = built.gpuMs ?? built.wallMs;
    const partial: Bvh = {
      nodeCount: n, bounds, leftFirst, triCount, triIndices,
      stats: { buildMs, nodeCount: n - 1, leafCount: 0, maxDepth: 0, meanLeafDepth: 0, sahCost: 0, triangleCount: built.triangleCount },
    };
    const s = bvhStats(partial);
    return { ...partial, stats: { buildMs, nodeCount: s.nodeCount, leafCount: s.leafCount, maxDepth: s.maxDepth, meanLeafDepth: s.meanLeafDepth, sahCost: s.sahCost, triangleCount: built.triangleCount } };
  } finally {
    staging.destroy();
  }
}
