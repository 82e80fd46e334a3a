/**
 * The benchmark's diffuse rays, made the way tinybvh's speed test makes them: one per primary ray that
 * hit something (misses make none), leaving the hit point along the primitive's geometric normal
 * turned to face the incoming ray, offset by 1e-4 × the scene's bounding-box diagonal along that
 * normal, in a cosine-distributed direction about it. Made on the CPU from the traced primary hits:
 * a deterministic, compacted ray set (the same rays in the same order every run), and it is set-up,
 * not what is timed.
 */
import { T_MISS } from '../bvh/ray.ts';
import { seededRandom } from '../math/seeded-random.ts';
import { PRIMITIVE_KIND, type TriangleList } from '../scene/triangles.ts';

/** Word offsets of the Ray and HitRecord structs (from the WGSL, by reflection). */
export interface RayWords {
  readonly stride: number;
  readonly origin: number;
  readonly direction: number;
  readonly tMin: number;
  readonly tMax: number;
}
export interface HitWords {
  readonly stride: number;
  readonly t: number;
  readonly triangle: number;
}

/** Source index of a miss (shaders' NO_TRIANGLE). */
const NO_TRIANGLE = 0xffffffff;
/** The origin's offset along the normal, in units of the scene's bounding-box diagonal. */
export const DIFFUSE_OFFSET = 1e-4;

export interface DiffuseRays {
  /** Ray records (the Ray layout), `count` of them. */
  readonly rays: Float32Array;
  readonly count: number;
}

/** How many of the first `count` hit records hit something. */
export function countHits(hits: ArrayBuffer, count: number, words: HitWords): number {
  const u32 = new Uint32Array(hits);
  let n = 0;
  for (let i = 0; i < count; i++) if (u32[i * words.stride + words.triangle] !== NO_TRIANGLE) n++;
  return n;
}

/**
 * The geometric normal (not normalised) of `prim` at `p`: (v1 − v0) × (v2 − v0) for a triangle, from
 * the centre for a sphere, from the nearest axis point for a capsule.
 */
function geometricNormal(triangles: TriangleList, prim: number, p: readonly [number, number, number], out: Float64Array): void {
  const q = triangles.positions, o = prim * 9;
  const kind = triangles.kinds[prim];
  if (kind === PRIMITIVE_KIND.sphere) {
    for (let k = 0; k < 3; k++) out[k] = p[k]! - q[o + k]!;
    return;
  }
  if (kind === PRIMITIVE_KIND.capsule) {
    const ax = q[o + 3]! - q[o]!, ay = q[o + 4]! - q[o + 1]!, az = q[o + 5]! - q[o + 2]!;
    const len2 = ax * ax + ay * ay + az * az;
    const s = len2 > 0 ? Math.min(1, Math.max(0, ((p[0] - q[o]!) * ax + (p[1] - q[o + 1]!) * ay + (p[2] - q[o + 2]!) * az) / len2)) : 0;
    out[0] = p[0] - (q[o]! + s * ax);
    out[1] = p[1] - (q[o + 1]! + s * ay);
    out[2] = p[2] - (q[o + 2]! + s * az);
    return;
  }
  const e1x = q[o + 3]! - q[o]!, e1y = q[o + 4]! - q[o + 1]!, e1z = q[o + 5]! - q[o + 2]!;
  const e2x = q[o + 6]! - q[o]!, e2y = q[o + 7]! - q[o + 1]!, e2z = q[o + 8]! - q[o + 2]!;
  out[0] = e1y * e2z - e1z * e2y;
  out[1] = e1z * e2x - e1x * e2z;
  out[2] = e1x * e2y - e1y * e2x;
}

/**
 * Diffuse rays from the primary rays and their hits (read back from the GPU), in primary-ray order.
 * `diagonal` is the scene's bounding-box diagonal; `seed` fixes the directions.
 */
export function diffuseRaysFromHits(primary: Float32Array, hits: ArrayBuffer, count: number, triangles: TriangleList, diagonal: number, ray: RayWords, hit: HitWords, seed = 1234): DiffuseRays {
  const hf = new Float32Array(hits), hu = new Uint32Array(hits);
  const hitCount = countHits(hits, count, hit);
  const out = new Float32Array(hitCount * ray.stride);
  const random = seededRandom(seed);
  const n = new Float64Array(3);
  const offset = DIFFUSE_OFFSET * diagonal;
  let j = 0;
  for (let i = 0; i < count; i++) {
    const prim = hu[i * hit.stride + hit.triangle]!;
    if (prim === NO_TRIANGLE) continue;
    const t = hf[i * hit.stride + hit.t]!;
    const r = i * ray.stride;
    const d: [number, number, number] = [primary[r + ray.direction]!, primary[r + ray.direction + 1]!, primary[r + ray.direction + 2]!];
    const p: [number, number, number] = [0, 1, 2].map((k) => primary[r + ray.origin + k]! + t * d[k]!) as [number, number, number];
    geometricNormal(triangles, prim, p, n);
    let len = Math.hypot(n[0]!, n[1]!, n[2]!);
    if (!(len > 0)) {
      // A degenerate primitive: face the incoming ray.
      n.set([-d[0], -d[1], -d[2]]);
      len = Math.hypot(...d);
    }
    // Facing the incoming ray.
    const flip = n[0]! * d[0] + n[1]! * d[1] + n[2]! * d[2] > 0 ? -1 / len : 1 / len;
    const nx = n[0]! * flip, ny = n[1]! * flip, nz = n[2]! * flip;
    // An orthonormal basis about n (Duff et al. 2017) and a cosine-distributed direction in it.
    const sign = nz >= 0 ? 1 : -1;
    const a = -1 / (sign + nz), b = nx * ny * a;
    const tx = 1 + sign * nx * nx * a, ty = sign * b, tz = -sign * nx;
    const bx = b, by = sign + ny * ny * a, bz = -ny;
    const u1 = random(), u2 = random();
    const radius = Math.sqrt(u1), phi = 2 * Math.PI * u2;
    const x = radius * Math.cos(phi), y = radius * Math.sin(phi), z = Math.sqrt(Math.max(0, 1 - u1));
    const o = j * ray.stride;
    out[o + ray.origin] = p[0] + offset * nx;
    out[o + ray.origin + 1] = p[1] + offset * ny;
    out[o + ray.origin + 2] = p[2] + offset * nz;
    out[o + ray.direction] = x * tx + y * bx + z * nx;
    out[o + ray.direction + 1] = x * ty + y * by + z * ny;
    out[o + ray.direction + 2] = x * tz + y * bz + z * nz;
    out[o + ray.tMin] = 0;
    out[o + ray.tMax] = T_MISS;
    j++;
  }
  return { rays: out, count: hitCount };
}

/** Spreads the low 10 bits of v so that two zero bits follow each (for a 30-bit Morton code). */
function spreadBits(v: number): number {
  let x = v & 0x3ff;
  x = (x | (x << 16)) & 0x030000ff;
  x = (x | (x << 8)) & 0x0300f00f;
  x = (x | (x << 4)) & 0x030c30c3;
  x = (x | (x << 2)) & 0x09249249;
  return x >>> 0;
}

/**
 * The rays reordered for coherence (`bench --reorder`): sorted by direction octant, then by the
 * Morton code of the origin within the rays' bounding box (10 bits an axis), so a workgroup's rays
 * start near each other and head the same way. What a wavefront tracer's sorting stage would do;
 * the sort itself (here on the CPU) is set-up and is not timed. Returns new records.
 */
export function reorderRays(rays: Float32Array, count: number, ray: RayWords): Float32Array {
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < count; i++) {
    for (let k = 0; k < 3; k++) {
      const v = rays[i * ray.stride + ray.origin + k]!;
      lo[k] = Math.min(lo[k]!, v);
      hi[k] = Math.max(hi[k]!, v);
    }
  }
  const keys = new Float64Array(count);
  for (let i = 0; i < count; i++) {
    const o = i * ray.stride;
    let octant = 0, morton = 0;
    for (let k = 0; k < 3; k++) {
      if (rays[o + ray.direction + k]! < 0) octant |= 1 << k;
      const extent = hi[k]! - lo[k]!;
      const q = extent > 0 ? Math.min(1023, Math.floor(((rays[o + ray.origin + k]! - lo[k]!) / extent) * 1024)) : 0;
      morton |= spreadBits(q) << k;
    }
    keys[i] = octant * 2 ** 30 + (morton >>> 0);
  }
  const order = Array.from({ length: count }, (_, i) => i).sort((a, b) => keys[a]! - keys[b]! || a - b);
  const out = new Float32Array(count * ray.stride);
  order.forEach((from, to) => out.set(rays.subarray(from * ray.stride, (from + 1) * ray.stride), to * ray.stride));
  return out;
}
