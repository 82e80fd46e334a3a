import { describe, expect, it } from 'vitest';
import { buildBvh } from './build.ts';
import { BVH_LAYOUTS } from './layouts.ts';
import { BVH_NODE_BYTES, bvhStats, formatBvhStats } from './stats.ts';
import { degenerateSoup, randomSoup } from './test-scenes.ts';

describe('bvhStats', () => {
  it('recomputes the build statistics and adds histogram and memory', () => {
    const positions = randomSoup(3000, 4);
    const bvh = buildBvh(positions);
    const s = bvhStats(bvh, { triangleBytes: 48 });
    expect(s.nodeCount).toBe(bvh.stats.nodeCount);
    expect(s.leafCount).toBe(bvh.stats.leafCount);
    expect(s.maxDepth).toBe(bvh.stats.maxDepth);
    expect(s.sahCost).toBeCloseTo(bvh.stats.sahCost, 9);
    expect(s.nodeCount).toBe(2 * s.leafCount - 1);
    const histogramLeaves = s.leafSizeHistogram.reduce((a, b) => a + b, 0);
    const histogramTriangles = s.leafSizeHistogram.reduce((a, count, size) => a + count * size, 0);
    expect(histogramLeaves).toBe(s.leafCount);
    expect(histogramTriangles).toBe(3000);
    expect(s.meanLeafSize).toBeCloseTo(3000 / s.leafCount, 12);
    expect(s.nodeBytes).toBe(bvh.nodeCount * BVH_NODE_BYTES);
    expect(s.triangleBytes).toBe(3000 * 48);
    expect(s.bytesPerTriangle).toBeCloseTo((s.nodeBytes + s.triangleBytes) / 3000, 12);
    expect(s.buildMs).toBe(bvh.stats.buildMs);
  });

  it('uses the given SAH costs', () => {
    const bvh = buildBvh(randomSoup(1000, 5), { traversalCost: 2, intersectionCost: 3 });
    expect(bvhStats(bvh, { traversalCost: 2, intersectionCost: 3 }).sahCost).toBeCloseTo(bvh.stats.sahCost, 9);
    expect(bvhStats(bvh).sahCost).not.toBeCloseTo(bvh.stats.sahCost, 3);
  });

  it('formats a few readable lines', () => {
    const text = formatBvhStats(buildBvh(degenerateSoup(), { maxLeafSize: 16 }));
    const lines = text.split('\n');
    expect(lines).toHaveLength(3);
    expect(lines[0]).toMatch(/^BVH: [\d,]+ nodes, [\d,]+ leaves, depth \d+ \(mean leaf depth [\d.]+\), SAH cost [\d.]+$/);
    expect(lines[1]).toMatch(/^ {2}leaf sizes: 1:[\d,]+ .*\(mean [\d.]+\)$/);
    expect(lines[2]).toMatch(/^ {2}node memory: [\d.]+ MiB \([\d.]+ bytes\/triangle\); built in [\d,]+ ms$/);
  });
});

describe('BVH layouts', () => {
  it('each builds a valid tree whose statistics use its own node size', () => {
    const positions = randomSoup(500, 9);
    expect(BVH_LAYOUTS.map((l) => l.name)).toContain('binary-sah');
    for (const layout of BVH_LAYOUTS) {
      const bvh = layout.build(positions);
      const s = layout.stats(bvh, { nodeBytes: layout.nodeBytes });
      expect(s.triangleCount).toBe(500);
      if (layout.name === 'binary-sah') {
        expect(s.nodeBytes).toBe(bvh.nodeCount * layout.nodeBytes);
        expect(s.sahCost).toBeCloseTo(bvh.stats.sahCost, 9);
      } else {
        // A wide tree: fewer nodes than the binary one, more bytes each, a header record and (CWBVH) 4 bytes a leaf.
        expect(s.nodeCount).toBeLessThan(bvh.stats.nodeCount / 2);
        expect(s.nodeBytes).toBeGreaterThanOrEqual(s.nodeCount * layout.nodeBytes);
        expect(s.nodeBytes).toBeLessThanOrEqual(s.nodeCount * layout.nodeBytes + 4 * s.leafCount + 96);
        expect(s.sahCost).toBeLessThan(bvh.stats.sahCost);
      }
      expect(s.leafSizeHistogram.reduce((a, n, k) => a + n * k, 0)).toBe(500);
    }
  });
});
