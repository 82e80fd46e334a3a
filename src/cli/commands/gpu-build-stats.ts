/**
 * `lantern bvh-stats --builder gpu`: the GPU BVH builder (gpu/build, PLOC) on a scene's triangles,
 * its GPU-timed build (median of --gpu-repeats builds after one warm-up, upload excluded) and SAH
 * cost, with leaves collapsed (what it hands the renderer) and without (PLOC's one triangle per
 * leaf), side by side with the CPU binned-SAH build.
 */
import { LanternError } from '../../errors.ts';
import type { Bvh } from '../../bvh/types.ts';
import { GpuBvhBuilder, readBackBvh, type GpuBvh } from '../../gpu/build/gpu-bvh-builder.ts';
import { bvhStats } from '../../bvh/stats.ts';
import type { TriangleList } from '../../scene/triangles.ts';
import type { CliContext } from '../context.ts';
import { acquireNodeGpu } from '../dawn.ts';
import { median } from '../../math/median.ts';

/** The builders `--builder` names. */
export const BUILDERS = ['cpu', 'gpu'] as const;
export type BuilderName = (typeof BUILDERS)[number];
/** `--gpu-timing`: GpuBvhBuildOptions.timing. */
export const GPU_TIMINGS = ['stages', 'kernels'] as const;

export function parseBuilders(value: string): BuilderName[] {
  const names = value.split(',').map((s) => s.trim()).filter(Boolean);
  const bad = names.filter((n) => !(BUILDERS as readonly string[]).includes(n));
  if (names.length === 0 || bad.length > 0) throw new LanternError(`--builder takes a comma-separated list of ${BUILDERS.join(', ')}; got '${value}'`);
  return [...new Set(names as BuilderName[])];
}

export interface GpuBuildReport {
  readonly adapter: string;
  readonly builder: 'ploc';
  readonly searchRadius: number;
  readonly maxLeafSize: number;
  readonly repeats: number;
  /** Median GPU time of the timed builds (timestamped passes, upload excluded); null without timestamp queries. */
  readonly gpuMs: number | null;
  readonly gpuMsRuns: readonly number[];
  /** Median wall clock of the timed builds, read-backs of the loop's cluster count included. */
  readonly wallMs: number;
  /** Each stage of the median build: sort, clustering batches, output. */
  readonly passes: readonly { name: string; ms: number }[];
  /** With --gpu-timing kernels: each kernel's GPU time and dispatches in the median build (one pass each, gaps left out). */
  readonly kernels?: readonly { name: string; ms: number; dispatches: number }[];
  readonly iterations: number;
  readonly nodes: number;
  readonly leaves: number;
  readonly maxDepth: number;
  readonly meanLeafSize: number;
  /** With subtrees of <= maxLeafSize triangles collapsed into leaves by the SAH (what the renderer would trace). */
  readonly sahCost: number;
  /** PLOC's own tree: one triangle per leaf. */
  readonly sahCostOneTrianglePerLeaf: number;
  readonly cpuBuildMs: number;
  readonly cpuSahCost: number;
  /** sahCost / cpuSahCost. */
  readonly sahRatio: number;
}

async function buildOnce(device: GPUDevice, builder: GpuBvhBuilder, positions: Float32Array, count: number, keepTree: boolean): Promise<{ built: GpuBvh; bvh?: Bvh }> {
  const built = await builder.build(positions, count);
  try {
    return keepTree ? { built, bvh: await readBackBvh(device, built) } : { built };
  } finally {
    built.nodes.destroy();
    built.triIndices.destroy();
  }
}

export async function gpuBuildReport(list: TriangleList, cpu: Bvh, repeats: number, output: Pick<CliContext, 'note' | 'dawnOutput'>, timing: (typeof GPU_TIMINGS)[number] = 'stages'): Promise<GpuBuildReport> {
  if (list.kindCounts.sphere + list.kindCounts.capsule > 0) {
    throw new LanternError('the GPU BVH builder handles triangles only; this scene has spheres or capsules', 'run bvh-stats with --builder cpu');
  }
  const gpu = await acquireNodeGpu({ onNote: output.note, onDawnOutput: output.dawnOutput });
  try {
    const { device } = gpu;
    const builder = await GpuBvhBuilder.create(device, { timing });
    const single = await GpuBvhBuilder.create(device, { maxLeafSize: 1 });
    const { positions, count } = list;
    // A warm-up build (first dispatches, allocations), then the timed ones.
    await buildOnce(device, builder, positions, count, false);
    const runs: GpuBvh[] = [];
    let tree: Bvh | undefined;
    for (let r = 0; r < repeats; r++) {
      const { built, bvh } = await buildOnce(device, builder, positions, count, r === 0);
      runs.push(built);
      tree ??= bvh;
    }
    const oneTriangle = (await buildOnce(device, single, positions, count, true)).bvh!;
    const gpuRuns = runs.map((r) => r.gpuMs).filter((ms): ms is number => ms !== undefined);
    const byTime = [...runs].sort((a, b) => (a.gpuMs ?? a.wallMs) - (b.gpuMs ?? b.wallMs));
    const mid = byTime[(byTime.length - 1) >> 1]!;
    const s = bvhStats(tree!);
    return {
      adapter: gpu.adapterName,
      builder: 'ploc',
      searchRadius: builder.options.searchRadius,
      maxLeafSize: builder.options.maxLeafSize,
      repeats,
      gpuMs: gpuRuns.length > 0 ? median(gpuRuns) : null,
      gpuMsRuns: gpuRuns,
      wallMs: median(runs.map((r) => r.wallMs)),
      passes: mid.passes,
      ...(mid.kernels ? { kernels: mid.kernels } : {}),
      iterations: mid.iterations,
      nodes: s.nodeCount,
      leaves: s.leafCount,
      maxDepth: s.maxDepth,
      meanLeafSize: s.meanLeafSize,
      sahCost: s.sahCost,
      sahCostOneTrianglePerLeaf: bvhStats(oneTriangle).sahCost,
      cpuBuildMs: cpu.stats.buildMs,
      cpuSahCost: cpu.stats.sahCost,
      sahRatio: s.sahCost / cpu.stats.sahCost,
    };
  } finally {
    gpu.device.destroy();
  }
}

export function formatGpuBuildReport(r: GpuBuildReport): string {
  const ms = (x: number) => `${x.toFixed(2)} ms`;
  const time = r.gpuMs !== null ? `${ms(r.gpuMs)} GPU (median of ${r.repeats}; ${r.passes.map((p) => `${p.name} ${p.ms.toFixed(2)}`).join(', ')}), ${ms(r.wallMs)} wall` : `${ms(r.wallMs)} wall (no timestamp queries)`;
  return [
    `gpu-ploc on ${r.adapter}: PLOC (radius ${r.searchRadius}), ${r.iterations} iterations, subtrees of <= ${r.maxLeafSize} collapsed by the SAH`,
    `  built in ${time}`,
    `  ${r.nodes.toLocaleString('en-US')} nodes, ${r.leaves.toLocaleString('en-US')} leaves (mean ${r.meanLeafSize.toFixed(2)} triangles), depth ${r.maxDepth}`,
    `  SAH cost ${r.sahCost.toFixed(2)} (one triangle per leaf: ${r.sahCostOneTrianglePerLeaf.toFixed(2)}); CPU binned SAH ${r.cpuSahCost.toFixed(2)} in ${ms(r.cpuBuildMs)}: ratio ${r.sahRatio.toFixed(3)}`,
    ...(r.kernels ? [`  by kernel (one pass each): ${r.kernels.map((k) => `${k.name} ${k.ms.toFixed(3)} (${k.dispatches}×)`).join(', ')}`] : []),
  ].join('\n');
}
