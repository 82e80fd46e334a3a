/**
 * `lantern bench --protocol`: presets that reproduce another tracer's published workload exactly, so
 * the two figures compare like for like. Two so far, tinybvh's speed test (v1.6.7) on the Stanford
 * Dragon: the bare mesh (no studio floor or lights), a fixed viewing direction, the camera at the
 * distance that frames every vertex (`framing`) or at 0.4 × that distance (`closeup`), 45° vertical
 * field of view at 16:9, primary rays in 8 × 8 tiles, and one cosine-distributed diffuse ray per
 * primary hit.
 */
import { boundsOfPositions } from '../math/aabb.ts';
import { cross, dot, normalize, scale, sub, add, type Vec3 } from '../math/vec3.ts';
import type { Camera } from '../scene/types.ts';

export const BENCH_PROTOCOLS = ['tinybvh-closeup', 'tinybvh-framing'] as const;
export type BenchProtocol = (typeof BENCH_PROTOCOLS)[number];

/** tinybvh's viewing direction, before normalising. */
const TINYBVH_FORWARD: Vec3 = [-0.35, -0.25, -1];
const TINYBVH_VFOV_DEGREES = 45;
const TINYBVH_ASPECT = 16 / 9;
/** Every vertex projects inside this fraction of the image's half-extents at the framing distance. */
const TINYBVH_FILL = 0.95;
const TINYBVH_CLOSEUP = 0.4;

/** What a protocol fixes: the camera for its mesh, and the image's aspect. */
export interface ProtocolView {
  readonly camera: Camera;
  readonly aspect: number;
  /** The look-at point (the bounding box's centre) and the framing distance, for the report. */
  readonly target: Vec3;
  readonly framingDistance: number;
}

/**
 * The smallest distance d along −forward from `target` at which every point of `positions` (xyz
 * triples) projects inside `fill` of the image's half-extents: for a point at p − target = (x, y, z)
 * in the camera's (right, up, forward) basis, its depth is z + d, and it is inside when
 * |x| ≤ fill·tan(hfov/2)·(z + d) and |y| ≤ fill·tan(vfov/2)·(z + d).
 */
export function framingDistance(positions: Float32Array, target: Vec3, forward: Vec3, vfovDegrees: number, aspect: number, fill: number): number {
  const f = normalize(forward);
  const r = normalize(cross(f, [0, 1, 0]));
  const u = cross(r, f);
  const tanY = fill * Math.tan((vfovDegrees * Math.PI) / 360);
  const tanX = tanY * aspect;
  let d = 0;
  for (let i = 0; i < positions.length; i += 3) {
    const p: Vec3 = [positions[i]! - target[0], positions[i + 1]! - target[1], positions[i + 2]! - target[2]];
    const z = dot(p, f);
    d = Math.max(d, Math.abs(dot(p, r)) / tanX - z, Math.abs(dot(p, u)) / tanY - z);
  }
  return d;
}

/** The camera of a tinybvh protocol for a mesh's positions (world space). */
export function tinybvhView(protocol: BenchProtocol, positions: Float32Array): ProtocolView {
  const bounds = boundsOfPositions(positions);
  const target = scale(add(bounds.min, bounds.max), 0.5);
  const forward = normalize(TINYBVH_FORWARD);
  const framing = framingDistance(positions, target, forward, TINYBVH_VFOV_DEGREES, TINYBVH_ASPECT, TINYBVH_FILL);
  const distance = protocol === 'tinybvh-closeup' ? TINYBVH_CLOSEUP * framing : framing;
  const position = sub(target, scale(forward, distance));
  return { camera: { position, forward, up: [0, 1, 0], vfovDegrees: TINYBVH_VFOV_DEGREES }, aspect: TINYBVH_ASPECT, target, framingDistance: framing };
}
