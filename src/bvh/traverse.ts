/**
 * The CPU reference traversal: the same algorithms as shaders/scene/bvh.wgsl (trace_closest and
 * trace_any), step for step, so hits and the visited-node / tested-triangle counts agree with the
 * GPU (up to f32 rounding). Plus a brute-force closest hit over all triangles, the oracle's oracle.
 *
 * Primitives are triangles, or of the kinds `kinds` gives (scene/triangles.ts: spheres, capsules);
 * "triangle" in the names below means any primitive.
 *
 * Counting convention (the GPU's counters must follow it):
 * - nodesVisited: nodes whose record the loop fetched (root included), or 1 when the root box is
 *   missed and the loop never starts;
 * - trianglesTested: ray/triangle tests run.
 */
import { intersectAabb, intersectPrimitive, prepareRay, T_MISS, type Barycentrics, type Ray } from './ray.ts';
import type { Bvh } from './types.ts';

/** A closest hit found without a BVH. */
export interface TriangleHit {
  readonly t: number;
  /** Barycentric weights of v1 and v2. */
  readonly u: number;
  readonly v: number;
  /** Source triangle index (into the positions array). */
  readonly triangle: number;
}

export interface Hit extends TriangleHit {
  /** Position of the triangle in leaf order (what the GPU reports before mapping to the source). */
  readonly leafIndex: number;
  readonly nodesVisited: number;
  readonly trianglesTested: number;
}

/** Closest-hit traversal result that keeps the work counts for missed rays too. */
export interface ClosestTrace {
  readonly hit: Hit | null;
  readonly nodesVisited: number;
  readonly trianglesTested: number;
}

export interface AnyTrace {
  /** Whether some triangle lies at tMin < t < tMax. */
  readonly hit: boolean;
  readonly nodesVisited: number;
  readonly trianglesTested: number;
}

/**
 * Closest hit with an ordered stack: at an interior node both children are slab-tested against the
 * closest hit so far, the nearer is visited next and the farther is pushed if it was hit (ties go
 * left). Popped nodes are not re-tested against a closer hit found meanwhile (the GPU does the same).
 */
export function traceClosest(bvh: Bvh, positions: Float32Array, ray: Ray, kinds?: Uint8Array): ClosestTrace {
  const r = prepareRay(ray);
  const { bounds, leftFirst, triCount, triIndices } = bvh;
  const bary: Barycentrics = { u: 0, v: 0 };
  let tBest = r.tMax, bestLeaf = -1, bestU = 0, bestV = 0;
  let nodesVisited = 1, trianglesTested = 0;
  if (intersectAabb(bounds, 0, r, tBest) === T_MISS) return { hit: null, nodesVisited, trianglesTested };
  nodesVisited = 0;
  const stack: number[] = [];
  let node = 0;
  for (;;) {
    nodesVisited++;
    const count = triCount[node]!;
    if (count > 0) {
      const first = leftFirst[node]!;
      for (let i = first; i < first + count; i++) {
        trianglesTested++;
        const t = intersectPrimitive(positions, kinds, triIndices[i]!, r, r.tMin, tBest, bary);
        if (t < tBest) {
          tBest = t;
          bestLeaf = i;
          bestU = bary.u;
          bestV = bary.v;
        }
      }
      if (stack.length === 0) break;
      node = stack.pop()!;
      continue;
    }
    let near = leftFirst[node]!, far = near + 1;
    let tNear = intersectAabb(bounds, near, r, tBest), tFar = intersectAabb(bounds, far, r, tBest);
    if (tFar < tNear) {
      const n = near, t = tNear;
      near = far;
      far = n;
      tNear = tFar;
      tFar = t;
    }
    if (tNear === T_MISS) {
      if (stack.length === 0) break;
      node = stack.pop()!;
      continue;
    }
    if (tFar !== T_MISS) stack.push(far);
    node = near;
  }
  const hit =
    bestLeaf < 0
      ? null
      : { t: tBest, u: bestU, v: bestV, triangle: triIndices[bestLeaf]!, leafIndex: bestLeaf, nodesVisited, trianglesTested };
  return { hit, nodesVisited, trianglesTested };
}

/** The closest hit at tMin < t < tMax, or null. See traceClosest for counts on misses. */
export function traverseClosest(bvh: Bvh, positions: Float32Array, ray: Ray, kinds?: Uint8Array): Hit | null {
  return traceClosest(bvh, positions, ray, kinds).hit;
}

/**
 * Any hit at tMin < t < tMax (shadow rays), stopping at the first found. Children are visited in
 * storage order, left first, without ordering by distance: any hit ends the search, so ordering
 * buys little (as trace_any in bvh.wgsl).
 */
export function traverseAny(bvh: Bvh, positions: Float32Array, ray: Ray, kinds?: Uint8Array): AnyTrace {
  const r = prepareRay(ray);
  const { bounds, leftFirst, triCount, triIndices } = bvh;
  const bary: Barycentrics = { u: 0, v: 0 };
  let nodesVisited = 1, trianglesTested = 0;
  if (intersectAabb(bounds, 0, r, r.tMax) === T_MISS) return { hit: false, nodesVisited, trianglesTested };
  nodesVisited = 0;
  const stack: number[] = [];
  let node = 0;
  for (;;) {
    nodesVisited++;
    const count = triCount[node]!;
    if (count > 0) {
      const first = leftFirst[node]!;
      for (let i = first; i < first + count; i++) {
        trianglesTested++;
        if (intersectPrimitive(positions, kinds, triIndices[i]!, r, r.tMin, r.tMax, bary) < r.tMax) return { hit: true, nodesVisited, trianglesTested };
      }
    } else {
      const left = leftFirst[node]!;
      const hitLeft = intersectAabb(bounds, left, r, r.tMax) !== T_MISS;
      const hitRight = intersectAabb(bounds, left + 1, r, r.tMax) !== T_MISS;
      if (hitLeft && hitRight) stack.push(left + 1);
      if (hitLeft || hitRight) {
        node = hitLeft ? left : left + 1;
        continue;
      }
    }
    if (stack.length === 0) return { hit: false, nodesVisited, trianglesTested };
    node = stack.pop()!;
  }
}

/**
 * Brute-force closest hit over every triangle in source order, no BVH. Because a hit must beat the
 * best so far strictly, the smallest t wins and, among equal t, the lowest source index.
 */
export function intersectAll(positions: Float32Array, ray: Ray, kinds?: Uint8Array): TriangleHit | null {
  const r = prepareRay(ray);
  const bary: Barycentrics = { u: 0, v: 0 };
  let best: TriangleHit | null = null;
  let tBest = r.tMax;
  for (let tri = 0, n = positions.length / 9; tri < n; tri++) {
    const t = intersectPrimitive(positions, kinds, tri, r, r.tMin, tBest, bary);
    if (t < tBest) {
      tBest = t;
      best = { t, u: bary.u, v: bary.v, triangle: tri };
    }
  }
  return best;
}
