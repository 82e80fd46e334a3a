/**
 * CPU twins of the GPU's ray/box and ray/triangle tests (shaders/scene/intersect.wgsl), operation
 * for operation, so the CPU oracle takes the same decisions as the GPU up to rounding: the GPU
 * computes in f32, these in float64, and tests compare with a tolerance.
 *
 * No infinities anywhere: WGSL may assume none occur at run time, so "missed" is the finite
 * sentinel T_MISS and near-zero direction components are clamped before inversion.
 */
import type { Vec3 } from '../math/vec3.ts';

/** "No hit yet" / "box missed": beyond any scene distance, and finite (lib/constants.wgsl). */
export const T_MISS = 3.0e38;
/** Direction components closer to zero than this are replaced by ±this before taking 1/d. */
export const INV_DIR_EPSILON = 1e-12;
/** |det| below this means the ray is parallel to the triangle's plane (or the triangle is degenerate). */
export const DET_EPSILON = 1e-30;

export interface Ray {
  readonly origin: Vec3;
  /** Need not be unit length; t is measured in units of |direction|. */
  readonly direction: Vec3;
  /** Hits must have t > tMin (default 0). */
  readonly tMin?: number;
  /** Hits must have t < tMax (default T_MISS). */
  readonly tMax?: number;
}

/** A ray with its safe inverse direction precomputed, as the traversal loops use it. */
export interface PreparedRay {
  readonly ox: number; readonly oy: number; readonly oz: number;
  readonly dx: number; readonly dy: number; readonly dz: number;
  readonly ix: number; readonly iy: number; readonly iz: number;
  readonly tMin: number;
  readonly tMax: number;
}

/**
 * 1/d with d kept at least INV_DIR_EPSILON away from zero, as WGSL safe_inverse does: the sign
 * comes from d >= 0, so both +0 and -0 count as positive and become +1e12. An axis-parallel ray then
 * gets slab distances of ±1e12·(distance to the plane) on that axis: huge, finite, correctly signed
 * for every box whose slab does not contain the origin.
 */
export function safeInverse(d: number): number {
  const sign = d >= 0 ? 1 : -1;
  const safe = Math.abs(d) < INV_DIR_EPSILON ? sign * INV_DIR_EPSILON : d;
  return 1 / safe;
}

export function prepareRay(ray: Ray): PreparedRay {
  const [ox, oy, oz] = ray.origin;
  const [dx, dy, dz] = ray.direction;
  return {
    ox, oy, oz, dx, dy, dz,
    ix: safeInverse(dx), iy: safeInverse(dy), iz: safeInverse(dz),
    tMin: ray.tMin ?? 0,
    tMax: ray.tMax ?? T_MISS,
  };
}

/**
 * Slab test of box `node` of a flat min-xyz/max-xyz array. Per axis the ray is inside the slab for
 * t between (min - o)/d and (max - o)/d (in either order); it is inside the box where all three
 * intervals overlap, [tNear, tFar]. Returns tNear (negative when the origin is inside; used to
 * order children) when that overlap is non-empty, not wholly behind the origin, and starts before
 * tBest; otherwise T_MISS.
 */
export function intersectAabb(bounds: ArrayLike<number>, node: number, ray: PreparedRay, tBest: number): number {
  const b = node * 6;
  const tx0 = (bounds[b]! - ray.ox) * ray.ix, tx1 = (bounds[b + 3]! - ray.ox) * ray.ix;
  const ty0 = (bounds[b + 1]! - ray.oy) * ray.iy, ty1 = (bounds[b + 4]! - ray.oy) * ray.iy;
  const tz0 = (bounds[b + 2]! - ray.oz) * ray.iz, tz1 = (bounds[b + 5]! - ray.oz) * ray.iz;
  const tNear = Math.max(Math.max(Math.min(tx0, tx1), Math.min(ty0, ty1)), Math.min(tz0, tz1));
  const tFar = Math.min(Math.min(Math.max(tx0, tx1), Math.max(ty0, ty1)), Math.max(tz0, tz1));
  return tNear <= tFar && tFar >= 0 && tNear < tBest ? tNear : T_MISS;
}

/** Barycentrics of the last hit reported by intersectTriangle. */
export interface Barycentrics {
  /** Weight of v1. */
  u: number;
  /** Weight of v2. */
  v: number;
}

/**
 * Möller–Trumbore. Writing the hit point as o + t·d = v0 + u·e1 + v·e2 (e1 = v1 - v0, e2 = v2 - v0)
 * gives a 3x3 linear system in (t, u, v); Cramer's rule with scalar triple products solves it:
 *   p = d × e2, det = e1 · p (zero when d lies in the triangle's plane),
 *   s = o - v0, u = (s · p)/det, q = s × e1, v = (d · q)/det, t = (e2 · q)/det.
 * u and v are tested as soon as they are known, so most misses stop early. Returns t when
 * u >= 0, v >= 0, u + v <= 1 and tMin < t < tBest (writing u, v to `out`), otherwise T_MISS.
 * Triangle `tri` of `positions` (9 floats per triangle) is tested; edges are formed in float64.
 */
export function intersectTriangle(positions: ArrayLike<number>, tri: number, ray: PreparedRay, tMin: number, tBest: number, out: Barycentrics): number {
  const o = tri * 9;
  const v0x = positions[o]!, v0y = positions[o + 1]!, v0z = positions[o + 2]!;
  const e1x = positions[o + 3]! - v0x, e1y = positions[o + 4]! - v0y, e1z = positions[o + 5]! - v0z;
  const e2x = positions[o + 6]! - v0x, e2y = positions[o + 7]! - v0y, e2z = positions[o + 8]! - v0z;
  const { dx, dy, dz } = ray;
  // p = cross(d, e2)
  const px = dy * e2z - dz * e2y, py = dz * e2x - dx * e2z, pz = dx * e2y - dy * e2x;
  const det = e1x * px + e1y * py + e1z * pz;
  if (Math.abs(det) < DET_EPSILON) return T_MISS;
  const invDet = 1 / det;
  const sx = ray.ox - v0x, sy = ray.oy - v0y, sz = ray.oz - v0z;
  const u = (sx * px + sy * py + sz * pz) * invDet;
  if (u < 0 || u > 1) return T_MISS;
  // q = cross(s, e1)
  const qx = sy * e1z - sz * e1y, qy = sz * e1x - sx * e1z, qz = sx * e1y - sy * e1x;
  const v = (dx * qx + dy * qy + dz * qz) * invDet;
  if (v < 0 || u + v > 1) return T_MISS;
  const t = (e2x * qx + e2y * qy + e2z * qz) * invDet;
  if (t > tMin && t < tBest) {
    out.u = u;
    out.v = v;
    return t;
  }
  return T_MISS;
}
