/**
 * CPU twins of the GPU's ray/box and ray/triangle tests (shaders/scene/intersect.wgsl), operation
 * for operation, so the CPU oracle takes the same decisions as the GPU up to rounding: the GPU
 * computes in f32, these in float64, and tests compare with a tolerance.
 *
 * No infinities anywhere: WGSL may assume none occur at run time, so "missed" is the finite
 * sentinel T_MISS and near-zero direction components are clamped before inversion.
 */
import { orthonormalFrame, type Vec3 } from '../math/vec3.ts';
import { PRIMITIVE_KIND } from '../scene/triangles.ts';

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
  // As the GPU computes it: bound · inv − origin · inv (one fma per slab there).
  const ox = ray.ox * ray.ix, oy = ray.oy * ray.iy, oz = ray.oz * ray.iz;
  const tx0 = bounds[b]! * ray.ix - ox, tx1 = bounds[b + 3]! * ray.ix - ox;
  const ty0 = bounds[b + 1]! * ray.iy - oy, ty1 = bounds[b + 4]! * ray.iy - oy;
  const tz0 = bounds[b + 2]! * ray.iz - oz, tz1 = bounds[b + 5]! * ray.iz - oz;
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

/**
 * Ray/sphere, in the numerically careful form of Haines et al. 2019 ("Precision Improvements for
 * Ray/Sphere Intersection", Ray Tracing Gems ch. 7): with f = o − c, the roots of
 * a·t² + 2b·t + c = 0 (a = d·d, b = f·d, c = f·f − r²) use the discriminant
 * b² − a·c = a·(r² − |f − (b/a)·d|²), which keeps its precision when the sphere is huge or far, and
 * the stable pair t = c/q, q/a with q = −b − sign(b)·√(b² − a·c). The nearer root beyond tMin wins,
 * so a ray inside the sphere (glass) finds the far side. Returns t, or T_MISS; writes the surface uv
 * (scene/types.ts SphereSet) to `out`.
 */
export function intersectSphere(positions: ArrayLike<number>, prim: number, ray: PreparedRay, tMin: number, tBest: number, out: Barycentrics): number {
  const o = prim * 9;
  const cx = positions[o]!, cy = positions[o + 1]!, cz = positions[o + 2]!, r = positions[o + 3]!;
  const { dx, dy, dz } = ray;
  const fx = ray.ox - cx, fy = ray.oy - cy, fz = ray.oz - cz;
  const a = dx * dx + dy * dy + dz * dz;
  const b = fx * dx + fy * dy + fz * dz;
  const lx = fx - (b / a) * dx, ly = fy - (b / a) * dy, lz = fz - (b / a) * dz;
  const disc = a * (r * r - (lx * lx + ly * ly + lz * lz));
  if (!(disc >= 0)) return T_MISS;
  const q = -b - (b >= 0 ? 1 : -1) * Math.sqrt(disc);
  if (q === 0) return T_MISS;
  const c = fx * fx + fy * fy + fz * fz - r * r;
  const t0 = c / q, t1 = q / a;
  const tNear = Math.min(t0, t1), tFar = Math.max(t0, t1);
  const t = tNear > tMin ? tNear : tFar;
  if (!(t > tMin && t < tBest)) return T_MISS;
  const nx = fx + t * dx, ny = fy + t * dy, nz = fz + t * dz;
  sphereUv(nx, ny, nz, out);
  return t;
}

/** u = longitude / 2π around +y from +z, v = colatitude / π from +y, of the direction (x, y, z) (any length). */
export function sphereUv(x: number, y: number, z: number, out: Barycentrics): void {
  const u = Math.atan2(x, z) / (2 * Math.PI);
  out.u = u < 0 ? u + 1 : u;
  out.v = Math.atan2(Math.hypot(x, z), y) / Math.PI;
}

/**
 * Ray/capsule: the union of a cylinder of radius r around a–b, cut to the slab between them, and the
 * spheres at both ends, each kept only where it is the capsule's boundary (the cylinder's roots with
 * their axial coordinate y in [0, L], sphere a's with y <= 0, sphere b's with y >= L). The nearest
 * root in (tMin, tBest) wins, so rays from inside find the exit. The cylinder's quadratic uses the
 * same stable form as the sphere's. uv: u around the axis (in the frame math/vec3.ts orthonormalFrame(axis)), v
 * = y / L clamped to [0, 1].
 */
export function intersectCapsule(positions: ArrayLike<number>, prim: number, ray: PreparedRay, tMin: number, tBest: number, out: Barycentrics): number {
  const o = prim * 9;
  const ax = positions[o]!, ay = positions[o + 1]!, az = positions[o + 2]!;
  const bx = positions[o + 3]!, by = positions[o + 4]!, bz = positions[o + 5]!, r = positions[o + 6]!;
  const { dx, dy, dz } = ray;
  const L = Math.hypot(bx - ax, by - ay, bz - az);
  const wx = L > 0 ? (bx - ax) / L : 0, wy = L > 0 ? (by - ay) / L : 1, wz = L > 0 ? (bz - az) / L : 0;
  const fx = ray.ox - ax, fy = ray.oy - ay, fz = ray.oz - az;
  const fw = fx * wx + fy * wy + fz * wz, dw = dx * wx + dy * wy + dz * wz;
  let best = tBest;
  const consider = (t: number, lo: number, hi: number) => {
    const y = fw + t * dw;
    if (t > tMin && t < best && y >= lo && y <= hi) best = t;
  };
  if (L > 0) {
    // Components across the axis.
    const px = dx - dw * wx, py = dy - dw * wy, pz = dz - dw * wz;
    const gx = fx - fw * wx, gy = fy - fw * wy, gz = fz - fw * wz;
    const a = px * px + py * py + pz * pz;
    if (a > 0) {
      const b = gx * px + gy * py + gz * pz;
      const lx = gx - (b / a) * px, ly = gy - (b / a) * py, lz = gz - (b / a) * pz;
      const disc = a * (r * r - (lx * lx + ly * ly + lz * lz));
      if (disc >= 0) {
        const q = -b - (b >= 0 ? 1 : -1) * Math.sqrt(disc);
        if (q !== 0) {
          const c = gx * gx + gy * gy + gz * gz - r * r;
          consider(c / q, 0, L);
          consider(q / a, 0, L);
        }
      }
    }
  }
  for (const [end, lo, hi] of [[0, -Infinity, 0], [L, L, Infinity]] as const) {
    const sx = fx - end * wx, sy = fy - end * wy, sz = fz - end * wz;
    const a = dx * dx + dy * dy + dz * dz;
    const b = sx * dx + sy * dy + sz * dz;
    const lx = sx - (b / a) * dx, ly = sy - (b / a) * dy, lz = sz - (b / a) * dz;
    const disc = a * (r * r - (lx * lx + ly * ly + lz * lz));
    if (!(disc >= 0)) continue;
    const q = -b - (b >= 0 ? 1 : -1) * Math.sqrt(disc);
    if (q === 0) continue;
    const c = sx * sx + sy * sy + sz * sz - r * r;
    consider(c / q, lo, hi);
    consider(q / a, lo, hi);
  }
  if (!(best < tBest)) return T_MISS;
  const [t1, t2] = orthonormalFrame([wx, wy, wz]);
  const hx = fx + best * dx, hy = fy + best * dy, hz = fz + best * dz;
  const u = Math.atan2(hx * t2[0] + hy * t2[1] + hz * t2[2], hx * t1[0] + hy * t1[1] + hz * t1[2]) / (2 * Math.PI);
  out.u = u < 0 ? u + 1 : u;
  out.v = L > 0 ? Math.min(1, Math.max(0, (fw + best * dw) / L)) : 0.5;
  return best;
}


/**
 * The test for primitive `prim` of kind kinds[prim] (every primitive a triangle without `kinds`), as
 * intersect_primitive in shaders/scene/intersect.wgsl. `out` gets barycentrics for a triangle and the
 * surface uv for a sphere or capsule.
 */
export function intersectPrimitive(positions: ArrayLike<number>, kinds: Uint8Array | undefined, prim: number, ray: PreparedRay, tMin: number, tBest: number, out: Barycentrics): number {
  const kind = kinds ? kinds[prim]! : PRIMITIVE_KIND.triangle;
  if (kind === PRIMITIVE_KIND.triangle) return intersectTriangle(positions, prim, ray, tMin, tBest, out);
  if (kind === PRIMITIVE_KIND.sphere) return intersectSphere(positions, prim, ray, tMin, tBest, out);
  return intersectCapsule(positions, prim, ray, tMin, tBest, out);
}
