/**
 * The wide layouts (bvh/wide.ts) against the binary oracle (bvh/traverse.ts): same closest hit
 * (same leaf, same t; ties aside), same any-hit answer; the quantised CWBVH boxes contain every
 * primitive under them; the leaves are the binary tree's, each exactly once; the packing and the
 * statistics.
 */
import { describe, expect, it } from 'vitest';
import { buildBvh } from './build.ts';
import { emptyBvh } from './levels.ts';
import { intersectPrimitive, prepareRay, T_MISS, type Ray } from './ray.ts';
import { degenerateSoup, makeRandom, quadGrid, randomSoup, testRays, uvSphere } from './test-scenes.ts';
import { traceClosest, traverseAny } from './traverse.ts';
import { computeTriangleBoxes } from './triangle-boxes.ts';
import {
  BVH4_LEAF_BIT, BVH4_NODE_WORDS, buildWideBvh, CWBVH_NODE_WORDS, WIDE_COLLAPSES, cwbvhChildBoxes, packWide, traceWide, traceWideAny, WIDE_EMPTY, WIDE_LAYOUTS, WIDE_MAX_LEAF, wideRecords, type WideBvh,
} from './wide.ts';

const scenes: Record<string, () => Float32Array> = {
  'random soup': () => randomSoup(2000, 2),
  'quad grid (flat boxes)': () => quadGrid(24),
  'uv sphere': () => uvSphere(16, 32, 3),
  'degenerate soup': degenerateSoup,
  'huge coordinates': () => randomSoup(800, 9, 1e37),
  'small coordinates': () => randomSoup(800, 4, 1e-8),
};


/** Leaf references under each node, as (first, count) lists, by walking the packed words. */
function leafRefs(wide: WideBvh, node: number): [number, number][] {
  const out: [number, number][] = [];
  const w = wide.nodes;
  if (wide.layout === 'bvh4') {
    for (let s = 0; s < 4; s++) {
      const ref = w[node * BVH4_NODE_WORDS + 24 + s]!;
      if (ref === WIDE_EMPTY) continue;
      if ((ref & BVH4_LEAF_BIT) !== 0) out.push([ref & ((1 << 27) - 1), ((ref >>> 27) & 15) + 1]);
      else out.push(...leafRefs(wide, ref));
    }
    return out;
  }
  for (const c of cwbvhSlots(wide, node)) {
    if (c.child !== undefined) out.push(...leafRefs(wide, c.child));
    else if (c.leaf) out.push(c.leaf);
  }
  return out;
}

/** A CWBVH node's used slots: an interior child's index or a leaf's (first, count). */
function cwbvhSlots(wide: WideBvh, node: number): { slot: number; child?: number; leaf?: [number, number] }[] {
  const o = node * CWBVH_NODE_WORDS, w = wide.nodes;
  const imask = w[o + 3]! >>> 24;
  const out: { slot: number; child?: number; leaf?: [number, number] }[] = [];
  let rank = 0;
  for (let s = 0; s < 8; s++) {
    const meta = (w[o + 6 + (s >> 2)]! >>> (8 * (s & 3))) & 0xff;
    if ((imask >> s) & 1) out.push({ slot: s, child: w[o + 4]! + rank++ });
    else if (meta !== 0) out.push({ slot: s, leaf: [wide.leafTable[w[o + 5]! + (meta >> 5)]!, meta & 31] });
  }
  return out;
}

describe.each(WIDE_LAYOUTS)('%s', (layout) => {
  const cases = [...Object.entries(scenes).map(([name, make]) => [name, make, 'sah'] as const), ...(['random soup', 'uv sphere'] as const).map((name) => [name, scenes[name]!, 'greedy'] as const)];
  for (const [name, make, collapse] of cases) {
    it(`finds the binary traversal's closest hit and any hit: ${name}, ${collapse} collapse`, () => {
      const positions = make();
      const bvh = buildBvh(positions);
      const wide = buildWideBvh(bvh, layout, { collapse });
      const rnd = makeRandom(11);
      let hits = 0, ties = 0;
      for (const ray of testRays(positions, 500, 5)) {
        const binary = traceClosest(bvh, positions, ray).hit;
        const trace = traceWide(wide, positions, ray);
        const got = trace.hit;
        expect(trace.nodesVisited).toBeGreaterThanOrEqual(1);
        expect(got === null, `hit/miss for ray ${JSON.stringify(ray)}`).toBe(binary === null);
        if (layout === 'bvh4') expect(traceWide(wide, positions, ray, undefined, { sortChildren: false }).hit?.t).toBe(got?.t);
        if (got && binary) {
          hits++;
          expect(got.t).toBe(binary.t);
          expect(wide.triIndices[got.leafIndex]).toBe(got.triangle);
          if (got.leafIndex !== binary.leafIndex) {
            // A tie: the wide tree's primitive is really hit at the same t.
            expect(intersectPrimitive(positions, undefined, got.triangle, prepareRay(ray), ray.tMin ?? 0, T_MISS, { u: 0, v: 0 })).toBe(binary.t);
            ties++;
          } else expect([got.u, got.v]).toEqual([binary.u, binary.v]);
        }
        // Any hit, also on rays cut just before and after the closest hit (shadow rays).
        const shadow: Ray = binary && rnd() < 0.5 ? { ...ray, tMax: binary.t * (rnd() < 0.5 ? 0.999 : 1.001) } : ray;
        expect(traceWideAny(wide, positions, shadow).hit).toBe(traverseAny(bvh, positions, shadow).hit);
      }
      expect(hits).toBeGreaterThan(100);
      if (name !== 'degenerate soup') expect(ties).toBeLessThan(hits / 100);
    });
  }

  it.each(WIDE_COLLAPSES)('keeps the binary leaves, each leaf position exactly once, and fewer nodes and a lower SAH cost (%s collapse)', (collapse) => {
    const positions = randomSoup(2000, 3);
    const bvh = buildBvh(positions);
    const wide = buildWideBvh(bvh, layout, { collapse });
    const seen = new Uint8Array(bvh.triIndices.length);
    for (const [first, count] of leafRefs(wide, 0)) {
      expect(count).toBeGreaterThanOrEqual(1);
      expect(count).toBeLessThanOrEqual(WIDE_MAX_LEAF[layout]);
      for (let i = first; i < first + count; i++) seen[i]!++;
    }
    expect(seen.every((n) => n === 1)).toBe(true);
    expect(wide.triIndices).toBe(bvh.triIndices);
    expect(wide.stats.nodeCount).toBe(wide.nodeCount);
    expect(wide.nodeCount).toBeLessThan(bvh.stats.nodeCount / (layout === 'bvh4' ? 2.5 : 5));
    expect(wide.stats.sahCost).toBeLessThan(bvh.stats.sahCost);
    expect(wide.stats.meanChildren).toBeGreaterThan(layout === 'bvh4' ? 2.8 : 4);
    expect(wide.stats.stackNeeded).toBeLessThanOrEqual(64);
  });

  it('traces a one-leaf tree and an empty one', () => {
    const one = new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0]);
    const wide = buildWideBvh(buildBvh(one), layout);
    expect(wide.nodeCount).toBe(1);
    const hit = traceWide(wide, one, { origin: [0.2, 0.2, 1], direction: [0, 0, -1] });
    expect(hit.hit?.t).toBe(1);
    expect(hit.nodesVisited).toBe(1);
    expect(traceWideAny(wide, one, { origin: [0.2, 0.2, 1], direction: [0, 0, 1] }).hit).toBe(false);
    const empty = buildWideBvh(emptyBvh(), layout);
    expect(traceWide(empty, new Float32Array(0), { origin: [0, 0, 0], direction: [1, 0, 0] })).toEqual({ hit: null, nodesVisited: 1, trianglesTested: 0 });
  });

  it('collapses by the SAH programme to a cost no higher than the greedy collapse (whose tree is one it considers)', () => {
    for (const seed of [3, 4, 5]) {
      const bvh = buildBvh(randomSoup(1500, seed));
      const sah = buildWideBvh(bvh, layout, { collapse: 'sah' }).stats, greedy = buildWideBvh(bvh, layout, { collapse: 'greedy' }).stats;
      expect(sah.sahCost).toBeLessThanOrEqual(greedy.sahCost * (1 + 1e-12));
    }
  });

  it.each(WIDE_COLLAPSES)('halves a leaf too large for its reference into pieces of the same box (%s collapse)', (collapse) => {
    // 40 coincident-centroid triangles cannot be split: one leaf of 40, over both layouts' limits.
    const tris: number[] = [];
    for (let i = 0; i < 40; i++) tris.push(-1, -1, i * 0.01, 1, -1, i * 0.01, 0, 1, -i * 0.01);
    const positions = new Float32Array(tris);
    const bvh = buildBvh(positions, { maxDepth: 0 });
    expect(bvh.triCount[0]).toBe(40);
    const wide = buildWideBvh(bvh, layout, { collapse });
    const refs = leafRefs(wide, 0);
    expect(refs.reduce((n, [, c]) => n + c, 0)).toBe(40);
    expect(Math.max(...refs.map(([, c]) => c))).toBeLessThanOrEqual(WIDE_MAX_LEAF[layout]);
    const ray: Ray = { origin: [0.01, -0.5, 5], direction: [0, 0, -1] };
    expect(traceWide(wide, positions, ray).hit?.t).toBe(traceClosest(bvh, positions, ray).hit?.t);
  });

  it('packs a header, the nodes and the leaf table into node records', () => {
    const wide = buildWideBvh(buildBvh(randomSoup(300, 8)), layout);
    const base = 37, stride = 8;
    const words = packWide(wide, base, stride);
    expect(words.length).toBe(wideRecords(wide, stride) * stride);
    const nodesWord = words[0]! - base * stride, tableWord = words[1]! - base * stride;
    expect(nodesWord).toBe(stride);
    expect(words.slice(nodesWord, nodesWord + wide.nodes.length)).toEqual(wide.nodes);
    expect(words.slice(tableWord, tableWord + wide.leafTable.length)).toEqual(wide.leafTable);
    expect(tableWord % 4).toBe(0);
    expect(words[2]).toBe(layout === 'bvh4' ? 0 : 1);
  });
});

describe('cwbvh quantisation', () => {
  for (const [name, make] of Object.entries(scenes)) {
    it(`is conservative: every primitive lies inside each dequantised box above it: ${name}`, () => {
      const positions = make();
      const bvh = buildBvh(positions);
      const wide = buildWideBvh(bvh, 'cwbvh');
      const boxes = computeTriangleBoxes(positions);
      let checked = 0;
      const visit = (node: number) => {
        const deq = cwbvhChildBoxes(wide.nodes, node);
        for (const c of cwbvhSlots(wide, node)) {
          const b = deq.subarray(c.slot * 6, c.slot * 6 + 6);
          expect(b[0]! <= b[3]! && b[1]! <= b[4]! && b[2]! <= b[5]!).toBe(true);
          const leaves = c.child !== undefined ? leafRefs(wide, c.child) : [c.leaf!];
          for (const [first, count] of leaves) {
            for (let i = first; i < first + count; i++) {
              const src = wide.triIndices[i]!;
              for (let k = 0; k < 3; k++) {
                expect(boxes[src * 6 + k]!).toBeGreaterThanOrEqual(b[k]!);
                expect(boxes[src * 6 + 3 + k]!).toBeLessThanOrEqual(b[k + 3]!);
              }
              checked++;
            }
          }
          if (c.child !== undefined) visit(c.child);
        }
      };
      visit(0);
      expect(checked).toBeGreaterThan(positions.length / 9);
    });
  }

  it('is tight: a child box spans at most one quantisation step more than the exact box on each side', () => {
    const positions = randomSoup(1000, 12);
    const wide = buildWideBvh(buildBvh(positions), 'cwbvh');
    const boxes = computeTriangleBoxes(positions);
    for (let node = 0; node < wide.nodeCount; node++) {
      const deq = cwbvhChildBoxes(wide.nodes, node);
      const o = node * CWBVH_NODE_WORDS;
      for (const c of cwbvhSlots(wide, node)) {
        const exact = [Infinity, Infinity, Infinity, -Infinity, -Infinity, -Infinity];
        for (const [first, count] of c.child !== undefined ? leafRefs(wide, c.child) : [c.leaf!]) {
          for (let i = first; i < first + count; i++) {
            const src = wide.triIndices[i]!;
            for (let k = 0; k < 3; k++) {
              exact[k] = Math.min(exact[k]!, boxes[src * 6 + k]!);
              exact[k + 3] = Math.max(exact[k + 3]!, boxes[src * 6 + 3 + k]!);
            }
          }
        }
        for (let k = 0; k < 3; k++) {
          const step = 2 ** (((wide.nodes[o + 3]! >>> (8 * k)) & 0xff) - 127);
          expect(exact[k]! - deq[c.slot * 6 + k]!).toBeLessThanOrEqual(step * 1.0001);
          expect(deq[c.slot * 6 + 3 + k]! - exact[k + 3]!).toBeLessThanOrEqual(step * 1.0001);
        }
      }
    }
  });
});
