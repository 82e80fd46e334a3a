/**
 * The grid's CPU traversal (bvh/grid.ts) against the BVH oracle (bvh/traverse.ts) on the same
 * primitives: every ray must find the same record (leaf, t, barycentrics), closest and any hit, on
 * random soups, on tile maps with their own grid and with an automatic one, for rays from outside and
 * inside, along the axes, along cell boundaries, and with short t_max.
 */
import { describe, expect, it } from 'vitest';
import { buildBvh } from './build.ts';
import { buildGrid, triangleOverlapsBox, type Grid } from './grid.ts';
import { tileMapScene } from './grid-test-scenes.ts';
import { traceGrid, traceGridAny } from './grid.ts';
import { intersectPrimitive, prepareRay, type Ray } from './ray.ts';
import { randomSoup, makeRandom } from './test-scenes.ts';
import { traceClosest, traverseAny } from './traverse.ts';
import type { Bvh } from './types.ts';
import { flattenTriangles } from '../scene/triangles.ts';
import type { Vec3 } from '../math/vec3.ts';

interface Case {
  readonly positions: Float32Array;
  readonly kinds: Uint8Array | undefined;
  readonly bvh: Bvh;
  readonly grid: Grid;
}

function soupCase(count: number, seed: number, scale: number): Case {
  const positions = randomSoup(count, seed, scale);
  const bvh = buildBvh(positions);
  return { positions, kinds: undefined, bvh, grid: buildGrid(positions, undefined, bvh.triIndices) };
}

function tileCase(hinted: boolean, tile = 2, subdivideTiles = true): Case {
  const scene = tileMapScene({ n: 32, tile, seed: 3 });
  const tris = flattenTriangles(hinted ? scene : { ...scene, tileGrid: undefined });
  const bvh = buildBvh(tris.positions, {}, tris.kinds);
  return { positions: tris.positions, kinds: tris.kinds, bvh, grid: buildGrid(tris.positions, tris.kinds, bvh.triIndices, hinted ? scene.tileGrid : undefined, { subdivideTiles }) };
}

/** Rays of every awkward kind over the grid's box. */
function raysFor(c: Case, count: number, seed: number): Ray[] {
  const rnd = makeRandom(seed);
  const { lo, hi, cellSize, dims } = c.grid;
  const rays: Ray[] = [];
  const inside = (): Vec3 => [0, 1, 2].map((k) => lo[k]! + rnd() * (hi[k]! - lo[k]!)) as unknown as Vec3;
  const dir = (): Vec3 => [rnd() * 2 - 1, rnd() * 2 - 1, rnd() * 2 - 1];
  for (let i = 0; i < count; i++) {
    const kind = i % 8;
    let origin = inside(), direction = dir(), tMin: number | undefined, tMax: number | undefined;
    if (kind === 1) {
      // From outside the box, toward a point inside.
      const target = inside();
      origin = [0, 1, 2].map((k) => lo[k]! - (hi[k]! - lo[k]!) + rnd() * 3 * (hi[k]! - lo[k]!)) as unknown as Vec3;
      direction = [target[0] - origin[0], target[1] - origin[1], target[2] - origin[2]];
    } else if (kind === 2) {
      // Along an axis, exact zeros elsewhere (either sign).
      const axis = i % 3;
      direction = [0, 0, 0].map((_, k) => (k === axis ? (rnd() < 0.5 ? -1 : 1) : 0)) as unknown as Vec3;
    } else if (kind === 3) {
      // On a cell boundary plane (and grazing it: the direction in the plane).
      const axis = (i >> 3) % 3;
      const o = [...origin];
      o[axis] = lo[axis]! + Math.floor(rnd() * (dims[axis]! + 1)) * cellSize[axis]!;
      origin = o as unknown as Vec3;
      const d = [...direction];
      d[axis] = rnd() < 0.5 ? 0 : d[axis]!;
      direction = d as unknown as Vec3;
    } else if (kind === 4) {
      // Through a cell corner line: origin on two boundary planes.
      const o = [...origin];
      for (const axis of [0, 2]) o[axis] = lo[axis]! + Math.floor(rnd() * (dims[axis]! + 1)) * cellSize[axis]!;
      origin = o as unknown as Vec3;
    } else if (kind === 5) {
      // A short segment (t_max), as shadow rays.
      tMax = rnd() * 4;
    } else if (kind === 6) {
      tMin = rnd() * 2;
      tMax = tMin + rnd() * 20;
    }
    rays.push({ origin: origin.map(Math.fround) as unknown as Vec3, direction: direction.map(Math.fround) as unknown as Vec3, ...(tMin !== undefined ? { tMin } : {}), ...(tMax !== undefined ? { tMax } : {}) });
  }
  return rays;
}

/** Compares both traversals on every ray; returns the number of hits (so a test can require enough). */
function agree(c: Case, rays: readonly Ray[]): number {
  const failures: string[] = [];
  let hits = 0, anyHits = 0, grazing = 0;
  rays.forEach((ray, i) => {
    const bvh = traceClosest(c.bvh, c.positions, ray, c.kinds).hit;
    const grid = traceGrid(c.grid, c.positions, ray, c.kinds).hit;
    // A ray lying in the plane of a box face (a zero direction component, the origin on the face)
    // meets the BVH's box there at t = 0 only (bvh/ray.ts safeInverse), so the BVH misses a
    // triangle edge on that face that the triangle test would hit; the grid's cells have no such
    // blind face. An edge hit is right to rounding either way.
    // The grid then finds that edge where the BVH finds a farther hit or none (never the other way).
    // Only rays made to start on a cell (tile) boundary plane (raysFor kinds 3 and 4) may do this.
    // So does the grid for a triangle that only touches, along an edge in that plane, the cells on
    // the plane's other side (grid.ts onlyGrazes): whichever finds the edge finds it nearer.
    const onEdge = (h: typeof grid) => h !== null && (c.kinds?.[h.triangle] ?? 0) === 0 && Math.min(h.u, h.v, 1 - h.u - h.v) < 1e-9;
    const edgeFirst = (a: typeof grid, b: typeof grid) => onEdge(a) && (!b || a!.t <= b.t * (1 + 1e-12));
    if ((i % 8 === 3 || i % 8 === 4) && (edgeFirst(grid, bvh) || edgeFirst(bvh, grid))) {
      grazing++;
      return;
    }
    if (bvh) hits++;
    const same = bvh === null ? grid === null : grid !== null && grid.t === bvh.t && (grid.leafIndex === bvh.leafIndex ? grid.u === bvh.u && grid.v === bvh.v : tiesAt(c, ray, grid.triangle, bvh.t));
    if (!same) failures.push(`ray ${i} ${JSON.stringify(ray)}: bvh ${bvh ? `${bvh.leafIndex} at ${bvh.t}` : 'miss'}, grid ${grid ? `${grid.leafIndex} at ${grid.t}` : 'miss'}`);
    const anyB = traverseAny(c.bvh, c.positions, ray, c.kinds).hit, anyG = traceGridAny(c.grid, c.positions, ray, c.kinds).hit;
    if (anyB) anyHits++;
    if (anyB !== anyG) failures.push(`ray ${i}: any hit: bvh ${anyB}, grid ${anyG}`);
    // Any hit is the closest hit's existence.
    if (anyG !== (grid !== null)) failures.push(`ray ${i}: grid any ${anyG} but closest ${grid ? 'hit' : 'miss'}`);
  });
  expect(failures.slice(0, 8)).toEqual([]);
  expect(anyHits).toBe(hits);
  expect(grazing).toBeLessThan(0.25 * rays.length);
  console.log(`${rays.length} rays: ${hits} hits, ${grazing} grazing a boundary plane's edges`);
  return hits;
}

/** Two primitives at exactly the same distance (a quad's diagonal): either is the right answer. */
function tiesAt(c: Case, ray: Ray, source: number, t: number): boolean {
  return intersectPrimitive(c.positions, c.kinds, source, prepareRay(ray), ray.tMin ?? 0, Infinity, { u: 0, v: 0 }) === t;
}

describe('grid traversal equals the BVH oracle', () => {
  it('random soups, small and large triangles', () => {
    for (const [count, seed, scale] of [[500, 1, 1], [2000, 2, 0.2], [200, 3, 4]] as const) {
      const c = soupCase(count, seed, scale);
      expect(agree(c, raysFor(c, 2000, seed))).toBeGreaterThan(60);
    }
  });

  it('a tile map on its own grid, one cell a tile (the 64 × 1 × 64 hint as given), walls listed only where they are', () => {
    const c = tileCase(true, 2, false);
    expect(c.grid.stats.source).toBe('tile map');
    expect(c.grid.dims).toEqual([32, 1, 32]);
    expect(agree(c, raysFor(c, 4000, 11))).toBeGreaterThan(2000);
    // A tile holds its own floor, ceiling and at most four wall faces (plus neighbours' faces on its
    // edges): a wall quad is not listed in every cell its box touches beyond that.
    expect(c.grid.stats.maxItems).toBeLessThanOrEqual(12);
  });

  it('a tile map on its tiles split into sub-cells (the default), still on the tile lattice', () => {
    const c = tileCase(true);
    expect(c.grid.stats.source).toBe('tile map');
    // Whole sub-cells per tile on each axis: tile edges are cell boundaries.
    [2, 2.5, 2].forEach((tile, k) => {
      const split = tile / c.grid.cellSize[k]!;
      expect(Math.abs(split - Math.round(split))).toBeLessThan(1e-5);
      expect(c.grid.lo[k]! / c.grid.cellSize[k]! - Math.round(c.grid.lo[k]! / c.grid.cellSize[k]!)).toBeCloseTo(0, 5);
    });
    expect(c.grid.stats.cells).toBeGreaterThan(32 * 32);
    expect(agree(c, raysFor(c, 3000, 12))).toBeGreaterThan(1500);
  });

  it('a tile map on an automatic grid, and with a non-integer tile size', () => {
    for (const c of [tileCase(false), tileCase(true, 1.37)]) expect(agree(c, raysFor(c, 3000, 5))).toBeGreaterThan(1500);
  });

  it('a hint smaller than the world is widened by whole cells to cover it', () => {
    const positions = randomSoup(300, 9, 1);
    const bvh = buildBvh(positions);
    const grid = buildGrid(positions, undefined, bvh.triIndices, { origin: [0, 0, 0], cellSize: [0.5, 0.5, 0.5], dims: [2, 2, 2] });
    for (let k = 0; k < 3; k++) {
      expect(grid.lo[k]! <= bvh.bounds[k]!).toBe(true);
      expect(grid.hi[k]! >= bvh.bounds[3 + k]!).toBe(true);
      // Still on the hint's lattice.
      expect(Math.abs(grid.lo[k]! / 0.5 - Math.round(grid.lo[k]! / 0.5))).toBeLessThan(1e-6);
    }
    const c = { positions, kinds: undefined, bvh, grid };
    agree(c, raysFor(c, 1000, 4));
  });

  it('stops walking at the first cell holding the closest hit', () => {
    // A row of unit quads facing -x at x = 1.5, 3.5, ...: a ray along +x hits the first and visits two cells.
    const quads: number[] = [];
    for (let i = 0; i < 8; i++) {
      const x = 1.5 + 2 * i;
      quads.push(x, -1, -1, x, 1, -1, x, 1, 1, x, -1, -1, x, 1, 1, x, -1, 1);
    }
    const positions = new Float32Array(quads);
    const bvh = buildBvh(positions);
    const grid = buildGrid(positions, undefined, bvh.triIndices, { origin: [0, -1, -1], cellSize: [1, 2, 2], dims: [16, 1, 1] }, { subdivideTiles: false });
    const r = traceGrid(grid, positions, { origin: [0.25, 0.1, 0.2], direction: [1, 0, 0] });
    expect(r.hit?.t).toBeCloseTo(1.25, 6);
    expect(r.nodesVisited).toBe(2);
    // Each quad is listed in the two cells its plane bounds (x = 1.5 is inside cell 1 only), no others.
    expect(grid.stats.items).toBe(16);
  });
});

describe('triangle/box overlap', () => {
  it('agrees with dense sampling of the triangle', () => {
    const rnd = makeRandom(21);
    let overlaps = 0;
    for (let i = 0; i < 400; i++) {
      const p = Array.from({ length: 9 }, () => rnd() * 4 - 2);
      const c: Vec3 = [rnd() - 0.5, rnd() - 0.5, rnd() - 0.5], h: Vec3 = [0.3 + rnd() * 0.4, 0.3 + rnd() * 0.4, 0.3 + rnd() * 0.4];
      const got = triangleOverlapsBox(p, 0, c, h);
      // Sampling may miss a sliver of overlap, never find one that is not there.
      let sampled = false;
      for (let a = 0; a <= 60 && !sampled; a++) {
        for (let b = 0; a + b <= 60 && !sampled; b++) {
          const s = a / 60, t = b / 60;
          const q = [0, 1, 2].map((k) => p[k]! + s * (p[3 + k]! - p[k]!) + t * (p[6 + k]! - p[k]!));
          sampled = q.every((x, k) => Math.abs(x - c[k]!) <= h[k]!);
        }
      }
      if (sampled) expect(got).toBe(true);
      if (got) overlaps++;
    }
    expect(overlaps).toBeGreaterThan(50);
    expect(overlaps).toBeLessThan(400);
  });
});
