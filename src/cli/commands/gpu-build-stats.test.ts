import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../../expect-lantern-error.ts';
import { formatGpuBuildReport, parseBuilders, type GpuBuildReport } from './gpu-build-stats.ts';

describe('--builder', () => {
  it('takes cpu, gpu or both, in any order, once each', () => {
    expect(parseBuilders('cpu')).toEqual(['cpu']);
    expect(parseBuilders('gpu, cpu,gpu')).toEqual(['gpu', 'cpu']);
  });
  it('refuses anything else, naming what it takes', () => {
    expectLanternError(() => parseBuilders(''), /cpu, gpu; got ''/);
    expectLanternError(() => parseBuilders('cpu,ploc'), /got 'cpu,ploc'/);
  });
});

describe('the GPU build report', () => {
  const report: GpuBuildReport = {
    adapter: 'test GPU', builder: 'ploc', searchRadius: 16, maxLeafSize: 8, repeats: 5, gpuMs: 4.5, gpuMsRuns: [4.4, 4.5, 4.6], wallMs: 9.25,
    passes: [{ name: 'sort', ms: 1 }, { name: 'cluster 1', ms: 3 }, { name: 'output', ms: 0.5 }], iterations: 55, nodes: 1_000_001, leaves: 500_001,
    maxDepth: 30, meanLeafSize: 1.74, sahCost: 40, sahCostOneTrianglePerLeaf: 52, cpuBuildMs: 900, cpuSahCost: 38, sahRatio: 40 / 38,
  };
  it('puts time and SAH cost beside the CPU build', () => {
    const text = formatGpuBuildReport(report);
    expect(text).toMatch(/built in 4\.50 ms GPU \(median of 5; sort 1\.00, cluster 1 3\.00, output 0\.50\), 9\.25 ms wall/);
    expect(text).toMatch(/SAH cost 40\.00 \(one triangle per leaf: 52\.00\); CPU binned SAH 38\.00 in 900\.00 ms: ratio 1\.053/);
    expect(formatGpuBuildReport({ ...report, gpuMs: null })).toMatch(/built in 9\.25 ms wall \(no timestamp queries\)/);
  });
});
