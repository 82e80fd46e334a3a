/** Axis-aligned bounding boxes as [min, max] pairs of Vec3, for scene-level bookkeeping. */
import type { Vec3 } from './vec3.ts';

export interface Aabb {
  readonly min: Vec3;
  readonly max: Vec3;
}

/** Bounds of a flat xyz position array; an empty array gives an inverted (empty) box. */
export function boundsOfPositions(positions: Float32Array): Aabb {
  let x0 = Infinity, y0 = Infinity, z0 = Infinity;
  let x1 = -Infinity, y1 = -Infinity, z1 = -Infinity;
  for (let i = 0; i + 2 < positions.length; i += 3) {
    const x = positions[i]!, y = positions[i + 1]!, z = positions[i + 2]!;
    if (x < x0) x0 = x;
    if (y < y0) y0 = y;
    if (z < z0) z0 = z;
    if (x > x1) x1 = x;
    if (y > y1) y1 = y;
    if (z > z1) z1 = z;
  }
  return { min: [x0, y0, z0], max: [x1, y1, z1] };
}

export function unionAabb(a: Aabb, b: Aabb): Aabb {
  return {
    min: [Math.min(a.min[0], b.min[0]), Math.min(a.min[1], b.min[1]), Math.min(a.min[2], b.min[2])],
    max: [Math.max(a.max[0], b.max[0]), Math.max(a.max[1], b.max[1]), Math.max(a.max[2], b.max[2])],
  };
}

export const isEmptyAabb = (a: Aabb): boolean => !(a.min[0] <= a.max[0] && a.min[1] <= a.max[1] && a.min[2] <= a.max[2]);
