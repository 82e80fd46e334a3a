import { describe, expect, it } from 'vitest';
import { buildBvh } from './build.ts';
import { maxNodeDepth, NO_DEPTH, nodeDepths, nodesAtDepth } from './depths.ts';
import { bvhStats } from './stats.ts';
import { randomSoup } from './test-scenes.ts';

describe('nodeDepths', () => {
  const bvh = buildBvh(randomSoup(2000, 11));
  const depths = nodeDepths(bvh);

  it('gives the root depth 0, children one more than their parent, and slot 1 none', () => {
    expect(depths[0]).toBe(0);
    expect(depths[1]).toBe(NO_DEPTH);
    for (let node = 0; node < bvh.nodeCount; node++) {
      if (node === 1 || bvh.triCount[node]! > 0) continue;
      const left = bvh.leftFirst[node]!;
      expect([depths[left], depths[left + 1]]).toEqual([depths[node]! + 1, depths[node]! + 1]);
    }
  });

  it('agrees with the statistics: deepest node, mean leaf depth, every node at some depth', () => {
    const stats = bvhStats(bvh);
    expect(maxNodeDepth(depths)).toBe(stats.maxDepth);
    let leafDepths = 0;
    for (let node = 0; node < bvh.nodeCount; node++) if (bvh.triCount[node]! > 0) leafDepths += depths[node]!;
    expect(leafDepths / stats.leafCount).toBeCloseTo(stats.meanLeafDepth, 12);
    let total = 0;
    for (let d = 0; d <= stats.maxDepth; d++) total += nodesAtDepth(depths, d).length;
    expect(total).toBe(stats.nodeCount);
    expect(Array.from(nodesAtDepth(depths, 0))).toEqual([0]);
    expect(Array.from(nodesAtDepth(depths, 1))).toEqual([2, 3]);
    expect(nodesAtDepth(depths, stats.maxDepth + 1).length).toBe(0);
  });
});
