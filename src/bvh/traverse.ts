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
import { intersectAabb, intersectPrimitive, prepareRay, T_MISS, type Barycentrics, type PreparedRay, type Ray } from './ray.ts';
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
 * Closest-hit state shared by the CPU traversals (binary, wide, grid): the best hit so far and the
 * counts. `triIndices` maps a leaf position to its source primitive.
 */
export class Closest {
  tBest: number;
  bestLeaf = -1;
  u = 0;
  v = 0;
  nodesVisited = 0;
  trianglesTested = 0;
  private readonly bary: Barycentrics = { u: 0, v: 0 };
  constructor(
    private readonly positions: Float32Array,
    private readonly kinds: Uint8Array | undefined,
    private readonly triIndices: Uint32Array,
    readonly r: PreparedRay,
  ) {
    this.tBest = r.tMax;
  }
  /** Tests the primitive at leaf position `leaf` against the best hit so far. */
  test(leaf: number): void {
    this.trianglesTested++;
    const t = intersectPrimitive(this.positions, this.kinds, this.triIndices[leaf]!, this.r, this.r.tMin, this.tBest, this.bary);
    if (t < this.tBest) {
      this.tBest = t;
      this.bestLeaf = leaf;
      this.u = this.bary.u;
      this.v = this.bary.v;
    }
  }
  /** Whether the primitive at leaf position `leaf` is hit at tMin < t < tMax (any-hit traversal: tBest stays tMax). */
  testAny(leaf: number): boolean {
    this.trianglesTested++;
    return intersectPrimitive(this.positions, this.kinds, this.triIndices[leaf]!, this.r, this.r.tMin, this.r.tMax, this.bary) < this.r.tMax;
  }
  leaf(first: number, count: number): void {
    for (let i = first; i < first + count; i++) this.test(i);
  }
  /** Any hit in the leaf. */
  leafAny(first: number, count: number): boolean {
    for (let i = first; i < first + count; i++) if (this.testAny(i)) return true;
    return false;
  }
  result(): ClosestTrace {
    const { nodesVisited, trianglesTested } = this;
    const hit: Hit | null =
      this.bestLeaf < 0 ? null : { t: this.tBest, u: this.u, v: this.v, triangle: this.triIndices[this.bestLeaf]!, leafIndex: this.bestLeaf, nodesVisited, trianglesTested };
    return { hit, nodesVisited, trianglesTested };
  }
  anyResult(hit: boolean): AnyTrace {
    return { hit, nodesVisited: this.nodesVisited, trianglesTested: this.trianglesTested };
  }
}

/**
 * The walk of both traversals, as trace_closest and trace_any in bvh.wgsl: a leaf's range goes to
 * `onLeaf`, which ends the walk by returning true. At an interior node both children are
 * slab-tested against state.tBest; the one visited next is the nearer hit child (`ordered`; ties go
 * left) or else the left child if it was hit, and the other is pushed if it was hit. Popped nodes
 * are not re-tested against a closer hit found meanwhile (the GPU does the same).
 */
function walkBvh(bvh: Bvh, state: Closest, ordered: boolean, onLeaf: (first: number, count: number) => boolean): void {
  const { bounds, leftFirst, triCount } = bvh;
  const r = state.r;
  state.nodesVisited = 1;
  if (intersectAabb(bounds, 0, r, state.tBest) === T_MISS) return;
  state.nodesVisited = 0;
  const stack: number[] = [];
  let node = 0;
  for (;;) {
    state.nodesVisited++;
    const count = triCount[node]!;
    if (count > 0) {
      if (onLeaf(leftFirst[node]!, count) || stack.length === 0) return;
      node = stack.pop()!;
      continue;
    }
    let near = leftFirst[node]!, far = near + 1;
    let tNear = intersectAabb(bounds, near, r, state.tBest), tFar = intersectAabb(bounds, far, r, state.tBest);
    if (ordered ? tFar < tNear : tNear === T_MISS) {
      const n = near, t = tNear;
      near = far;
      far = n;
      tNear = tFar;
      tFar = t;
    }
    if (tNear === T_MISS) {
      if (stack.length === 0) return;
      node = stack.pop()!;
      continue;
    }
    if (tFar !== T_MISS) stack.push(far);
    node = near;
  }
}

/** Closest hit with an ordered stack: the nearer hit child is visited next, the farther pushed (see walkBvh). */
export function traceClosest(bvh: Bvh, positions: Float32Array, ray: Ray, kinds?: Uint8Array): ClosestTrace {
  const state = new Closest(positions, kinds, bvh.triIndices, prepareRay(ray));
  walkBvh(bvh, state, true, (first, count) => {
    state.leaf(first, count);
    return false;
  });
  return state.result();
}

/** The closest hit at tMin < t < tMax, or null. See traceClosest for counts on misses. */
export function traverseClosest(bvh: Bvh, positions: Float32Array, ray: Ray, kinds?: Uint8Array): Hit | null {
  return traceClosest(bvh, positions, ray, kinds).hit;
}

/**
 * Any hit at tMin < t < tMax (shadow rays), stopping at the first found. Children are visited in
 * storage order, left first, without ordering by distance: any hit ends the search, so ordering
 * buys little (as trace_any in bvh.wgsl). The boxes are tested against tMax throughout (state.tBest
 * stays tMax when only leafAny tests).
 */
export function traverseAny(bvh: Bvh, positions: Float32Array, ray: Ray, kinds?: Uint8Array): AnyTrace {
  const state = new Closest(positions, kinds, bvh.triIndices, prepareRay(ray));
  let hit = false;
  walkBvh(bvh, state, false, (first, count) => (hit = state.leafAny(first, count)));
  return state.anyResult(hit);
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
