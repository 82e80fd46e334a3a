/**
 * The two-level acceleration structure of a scene with moving instances (Instance.moves), on the CPU:
 * - the static world: one BVH over the world-space primitives of every instance that does not move
 *   (the single-level BVH of a frozen scene, the fastest thing to trace for what never moves);
 * - one bottom-level BVH per mesh that a moving instance uses, over its primitives in object space,
 *   built once and shared by every instance of the mesh (refitted when the mesh morphs);
 * - a top-level tree over the moving instances' world boxes (bvh/tlas.ts), rebuilt whenever one
 *   moves. Rays trace the static world first, then the top level (pruned by the static hit).
 *
 * GPU instance 0 is the static world (identity transform); moving instance k of `dynamic` is GPU
 * instance k + 1. A scene where nothing moves has no levels: its one BVH is the static world. Pure.
 */
import { buildBvh, type Bvh } from './build.ts';
import { refitBvh } from './refit.ts';
import { buildTlas, type Tlas } from './tlas.ts';
import { f32Down, f32Up } from './triangle-boxes.ts';
import { traceClosest, type ClosestTrace, type Hit } from './traverse.ts';
import { traceGrid, type Grid } from './grid.ts';
import { traceWide, type WideBvh } from './wide.ts';
import { intersectAabb, prepareRay, T_MISS, type Ray } from './ray.ts';
import { IDENTITY, invertAffine, transformDirection, transformPoint, type Mat4 } from '../math/mat4.ts';
import { flattenTriangles, PRIMITIVE_FLOATS, type TriangleList } from '../scene/triangles.ts';
import type { Mesh, Scene } from '../scene/types.ts';

/** A mesh's primitives in object space and their BVH (leaf order indexes `triangles`). */
export interface MeshBlas {
  readonly mesh: number;
  readonly triangles: TriangleList;
  readonly bvh: Bvh;
}

export interface SceneLevels {
  /** Scene instance index of GPU instance k + 1 (the moving instances, in scene order). */
  readonly dynamic: readonly number[];
  /** By mesh index: the bottom level of every mesh a moving instance uses. */
  readonly blas: ReadonlyMap<number, MeshBlas>;
  /** 6 floats per GPU instance: its world box (instance 0: the static world's; empty when it has nothing). The top level is built over all but instance 0. */
  readonly boxes: Float32Array;
  readonly tlas: Tlas;
  /** Milliseconds of the last top-level build. */
  readonly tlasMs: number;
}

/** The scene of one identity instance of mesh `index` (what its object-space primitives are flattened from). */
export function meshScene(scene: Scene, index: number, mesh: Mesh = scene.meshes[index]!): Scene {
  const meshes = [...scene.meshes];
  meshes[index] = mesh;
  return { ...scene, meshes, instances: [{ id: 0, mesh: index, worldFromObject: IDENTITY }] };
}

export function buildMeshBlas(scene: Scene, index: number, mesh?: Mesh): MeshBlas {
  const triangles = flattenTriangles(meshScene(scene, index, mesh));
  return { mesh: index, triangles, bvh: buildBvh(triangles.positions, {}, triangles.kinds) };
}

/** The mesh's primitives after it morphed: written again in object space, its BVH refitted. */
export function refitMeshBlas(scene: Scene, blas: MeshBlas, mesh: Mesh): MeshBlas {
  const fresh = flattenTriangles(meshScene(scene, blas.mesh, mesh));
  return { ...blas, triangles: fresh, bvh: refitBvh(blas.bvh, fresh.positions, fresh.kinds) };
}

/**
 * The static world's BVH: over the primitives of instances that do not move (all of them when none
 * does), its leaf order indexing the scene's whole flattened list, so it traces against
 * `triangles.positions` as a single-level BVH does.
 */
export function buildStaticBvh(scene: Scene, triangles: TriangleList): Bvh {
  const input = staticPrimitives(scene, triangles);
  return input ? withSourceIndices(buildBvh(input.positions, {}, input.kinds), input.keep) : emptyBvh();
}

/** `buildStaticBvh` with another builder (build-parallel.ts's, on workers); the same tree. */
export async function buildStaticBvhWith(scene: Scene, triangles: TriangleList, build: (positions: Float32Array, kinds: Uint8Array) => Promise<Bvh>): Promise<Bvh> {
  const input = staticPrimitives(scene, triangles);
  return input ? withSourceIndices(await build(input.positions, input.kinds), input.keep) : emptyBvh();
}

/** The primitives of the static world, and which entries of the whole list they are (absent: all); undefined when there are none. */
function staticPrimitives(scene: Scene, triangles: TriangleList): { positions: Float32Array; kinds: Uint8Array; keep?: number[] } | undefined {
  const moving = scene.instances.map((inst) => inst.moves === true);
  if (!moving.some(Boolean)) return { positions: triangles.positions, kinds: triangles.kinds };
  const keep: number[] = [];
  for (let t = 0; t < triangles.count; t++) if (!moving[triangles.instanceIds[t]!]) keep.push(t);
  if (keep.length === 0) return undefined;
  const positions = new Float32Array(keep.length * PRIMITIVE_FLOATS);
  const kinds = new Uint8Array(keep.length);
  keep.forEach((t, i) => {
    positions.set(triangles.positions.subarray(t * PRIMITIVE_FLOATS, (t + 1) * PRIMITIVE_FLOATS), i * PRIMITIVE_FLOATS);
    kinds[i] = triangles.kinds[t]!;
  });
  return { positions, kinds, keep };
}

const withSourceIndices = (bvh: Bvh, keep: number[] | undefined): Bvh => (keep ? { ...bvh, triIndices: bvh.triIndices.map((i) => keep[i]!) } : bvh);

/** The static world of a scene where everything moves: a root leaf of nothing, its box inverted (no ray enters it). */
export function emptyBvh(): Bvh {
  const bounds = new Float32Array(12);
  bounds.set([3.4e38, 3.4e38, 3.4e38, -3.4e38, -3.4e38, -3.4e38, 3.4e38, 3.4e38, 3.4e38, -3.4e38, -3.4e38, -3.4e38]);
  return {
    nodeCount: 2,
    bounds,
    leftFirst: new Uint32Array(2),
    triCount: new Uint32Array(2),
    triIndices: new Uint32Array(0),
    stats: { buildMs: 0, nodeCount: 1, leafCount: 1, maxDepth: 0, meanLeafDepth: 0, sahCost: 0, triangleCount: 0 },
  };
}

/** Whether a BVH has anything in it (an empty one's root box is inverted). */
const isEmpty = (bvh: Pick<Bvh, 'bounds'>) => !(bvh.bounds[0]! <= bvh.bounds[3]!);

/** The world box of `box` (6 floats at `o`) under `m`: its eight corners transformed. */
export function transformBox(box: ArrayLike<number>, o: number, m: Mat4, out: Float32Array, oo: number): void {
  let lx = Infinity, ly = Infinity, lz = Infinity, hx = -Infinity, hy = -Infinity, hz = -Infinity;
  if (!(box[o]! <= box[o + 3]!)) {
    out.set([Infinity, Infinity, Infinity, -Infinity, -Infinity, -Infinity], oo);
    return;
  }
  for (let c = 0; c < 8; c++) {
    const x = box[o + (c & 1 ? 3 : 0)]!, y = box[o + 1 + (c & 2 ? 3 : 0)]!, z = box[o + 2 + (c & 4 ? 3 : 0)]!;
    const wx = m[0]! * x + m[4]! * y + m[8]! * z + m[12]!, wy = m[1]! * x + m[5]! * y + m[9]! * z + m[13]!, wz = m[2]! * x + m[6]! * y + m[10]! * z + m[14]!;
    lx = Math.min(lx, wx); ly = Math.min(ly, wy); lz = Math.min(lz, wz);
    hx = Math.max(hx, wx); hy = Math.max(hy, wy); hz = Math.max(hz, wz);
  }
  // Rounded outward to f32, so the stored box holds the exact one.
  out[oo] = f32Down(lx);
  out[oo + 1] = f32Down(ly);
  out[oo + 2] = f32Down(lz);
  out[oo + 3] = f32Up(hx);
  out[oo + 4] = f32Up(hy);
  out[oo + 5] = f32Up(hz);
}

/** World boxes of every GPU instance and the top level over them. */
export function buildTopLevel(scene: Scene, staticBvh: Bvh, dynamic: readonly number[], blas: ReadonlyMap<number, MeshBlas>, previous?: Tlas): { boxes: Float32Array; tlas: Tlas; tlasMs: number } {
  const boxes = new Float32Array((dynamic.length + 1) * 6);
  transformBox(staticBvh.bounds, 0, IDENTITY, boxes, 0);
  dynamic.forEach((ii, k) => {
    const inst = scene.instances[ii]!;
    transformBox(blas.get(inst.mesh)!.bvh.bounds, 0, inst.worldFromObject, boxes, (k + 1) * 6);
  });
  // The static world is traced first, on its own (traceScene, trace_closest): the top level holds
  // only the moving instances.
  const t0 = performance.now();
  const moving = boxes.slice();
  moving.set([Infinity, Infinity, Infinity, -Infinity, -Infinity, -Infinity], 0);
  const tlas = buildTlas(moving, previous);
  return { boxes, tlas, tlasMs: performance.now() - t0 };
}

/** The levels of `scene`, or undefined when nothing in it moves. */
export function buildLevels(scene: Scene, staticBvh: Bvh): SceneLevels | undefined {
  const dynamic = scene.instances.flatMap((inst, i) => (inst.moves ? [i] : []));
  if (dynamic.length === 0) return undefined;
  const blas = new Map<number, MeshBlas>();
  for (const ii of dynamic) {
    const mesh = scene.instances[ii]!.mesh;
    if (!blas.has(mesh)) blas.set(mesh, buildMeshBlas(scene, mesh));
  }
  return { dynamic, blas, ...buildTopLevel(scene, staticBvh, dynamic, blas) };
}

/** Whether GPU instance 0 (the static world) has anything in it. */
export const hasStaticWorld = (staticBvh: Bvh): boolean => !isEmpty(staticBvh);

/** A closest hit of the two-level oracle: the source primitive (scene flattened list), and which GPU instance. */
export interface SceneHit {
  readonly t: number;
  readonly u: number;
  readonly v: number;
  /** Index into the scene's flattened list (scene/triangles.ts). */
  readonly triangle: number;
  /** GPU instance: 0 the static world, k + 1 moving instance k. */
  readonly instance: number;
  /** Nodes fetched on both levels (as trace_closest counts them). */
  readonly nodesVisited: number;
}

/**
 * The CPU oracle of two-level traversal: the top level visited near child first, each instance's
 * bottom level traced with the ray in its object space (t is preserved: the direction is transformed,
 * not normalised). Without levels, the static world alone. With `accel` (a grid, bvh/grid.ts, or a wide
 * tree, bvh/wide.ts), the static world is traced through it instead of its BVH (the same records: both
 * index the BVH's leaves).
 */
export function traceScene(scene: Scene, triangles: TriangleList, staticBvh: Bvh, levels: SceneLevels | undefined, ray: Ray, accel?: Grid | WideBvh): SceneHit | null {
  const tMax = ray.tMax ?? T_MISS;
  const traceStatic = (r: Ray): ClosestTrace =>
    accel === undefined ? traceClosest(staticBvh, triangles.positions, r, triangles.kinds) : 'layout' in accel ? traceWide(accel, triangles.positions, r, triangles.kinds) : traceGrid(accel, triangles.positions, r, triangles.kinds);
  if (!levels) {
    const r = traceStatic(ray);
    return r.hit ? { ...pick(r.hit), triangle: r.hit.triangle, instance: 0, nodesVisited: r.nodesVisited } : null;
  }
  let best: SceneHit | null = null;
  let bestT = tMax;
  let nodes = 0;
  const traceInstance = (g: number) => {
    if (g === 0) {
      const r = traceStatic({ ...ray, tMax: bestT });
      nodes += r.nodesVisited;
      if (r.hit) {
        bestT = r.hit.t;
        best = { ...pick(r.hit), triangle: r.hit.triangle, instance: 0, nodesVisited: 0 };
      }
      return;
    }
    const ii = levels.dynamic[g - 1]!;
    const inst = scene.instances[ii]!;
    const b = levels.blas.get(inst.mesh)!;
    const inv = invertAffine(inst.worldFromObject);
    const local: Ray = { origin: transformPoint(inv, ray.origin), direction: transformDirection(inv, ray.direction), tMin: ray.tMin ?? 0, tMax: bestT };
    const r = traceClosest(b.bvh, b.triangles.positions, local, b.triangles.kinds);
    nodes += r.nodesVisited;
    if (r.hit) {
      bestT = r.hit.t;
      const triangle = triangles.instanceFirstTriangle[ii]! + r.hit.triangle;
      // A mirroring instance's world triangles have v1 and v2 swapped (scene/triangles.ts), so their barycentrics swap.
      const swapped = triangles.swapped[triangle] === 1;
      best = { t: r.hit.t, u: swapped ? r.hit.v : r.hit.u, v: swapped ? r.hit.u : r.hit.v, triangle, instance: g, nodesVisited: 0 };
    }
  };
  // The static world first, then the top level over the moving instances, pruned by what it found.
  if (staticBvh.triIndices.length > 0) traceInstance(0);
  const { tlas } = levels;
  const pr = prepareRay(ray);
  const stack: number[] = [];
  let node = 0;
  nodes++;
  if (intersectAabb(tlas.bounds, 0, pr, bestT) !== T_MISS) {
    nodes--;
    for (;;) {
      nodes++;
      if (tlas.triCount[node]! > 0) {
        traceInstance(tlas.leftFirst[node]!);
      } else {
        const l = tlas.leftFirst[node]!;
        let near = l, far = l + 1;
        let tn = intersectAabb(tlas.bounds, near, pr, bestT), tf = intersectAabb(tlas.bounds, far, pr, bestT);
        if (tf < tn) {
          [near, far] = [far, near];
          [tn, tf] = [tf, tn];
        }
        if (tn !== T_MISS) {
          if (tf !== T_MISS) stack.push(far);
          node = near;
          continue;
        }
      }
      const next = stack.pop();
      if (next === undefined) break;
      node = next;
    }
  }
  const found = best as SceneHit | null;
  return found ? { ...found, nodesVisited: nodes } : null;
}

const pick = (h: Hit) => ({ t: h.t, u: h.u, v: h.v });
