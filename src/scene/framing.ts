/**
 * A camera that frames a box: the default view for any scene that brings no camera of its own (a
 * glTF file without cameras, the studio). Three-quarter view from the front-right and a little
 * above, so an object reads as a solid rather than as a silhouette.
 */
import type { Aabb } from '../math/aabb.ts';
import { add, cross, length, normalize, scale, sub, type Vec3 } from '../math/vec3.ts';
import type { Camera } from './types.ts';

export interface FramingOptions {
  /** Default 40. */
  readonly vfovDegrees?: number;
  /** Where the camera sits seen from the centre: azimuth from +z toward +x, degrees. Default 35. */
  readonly azimuthDegrees?: number;
  /** Elevation above the horizon, degrees. Default 20. */
  readonly elevationDegrees?: number;
  /** The bounds fill at most 1/margin of the frame's half-height. Default 1.1. */
  readonly margin?: number;
}

/**
 * Puts the camera on the chosen direction at the distance where every corner of `bounds` lies inside
 * the vertical field of view with the margin. The horizontal extent is held to the same angle, so the
 * framing also holds for images up to aspect 1 (square) and is generous for wide ones.
 */
export function frameBounds(bounds: Aabb, options: FramingOptions = {}): Camera {
  const vfov = options.vfovDegrees ?? 40;
  const a = ((options.azimuthDegrees ?? 35) * Math.PI) / 180;
  const e = ((options.elevationDegrees ?? 20) * Math.PI) / 180;
  const toCamera: Vec3 = [Math.sin(a) * Math.cos(e), Math.sin(e), Math.cos(a) * Math.cos(e)];
  const centre = scale(add(bounds.min, bounds.max), 0.5);
  // A flat or point-like model still needs a non-zero distance.
  const radius = length(sub(bounds.max, centre)) || 1;
  const forward = scale(toCamera, -1);
  const right = normalize(cross(forward, [0, 1, 0]));
  const up = cross(right, forward);
  const tanHalf = Math.tan(((vfov / 2) * Math.PI) / 180) / (options.margin ?? 1.1);
  // A corner at (x, y) across the view and z along it, seen from distance d: |x|, |y| ≤ tanHalf·(d + z).
  let distance = 1.05 * radius; // at least outside the bounding sphere
  for (const cx of [bounds.min[0], bounds.max[0]]) {
    for (const cy of [bounds.min[1], bounds.max[1]]) {
      for (const cz of [bounds.min[2], bounds.max[2]]) {
        const q = sub([cx, cy, cz], centre);
        const x = Math.abs(q[0] * right[0] + q[1] * right[1] + q[2] * right[2]);
        const y = Math.abs(q[0] * up[0] + q[1] * up[1] + q[2] * up[2]);
        const z = q[0] * forward[0] + q[1] * forward[1] + q[2] * forward[2];
        distance = Math.max(distance, Math.max(x, y) / tanHalf - z);
      }
    }
  }
  return { position: add(centre, scale(toCamera, distance)), forward, up: [0, 1, 0], vfovDegrees: vfov };
}

/** Whether the point p lies inside the camera's view pyramid for an image of the given aspect (width / height). */
export function inView(camera: Camera, p: Vec3, aspect: number): boolean {
  const { position, forward, up, vfovDegrees } = camera;
  const f = normalize(forward);
  const r = normalize(cross(f, up));
  const u = cross(r, f);
  const q = sub(p, position);
  const z = q[0] * f[0] + q[1] * f[1] + q[2] * f[2];
  const t = Math.tan((vfovDegrees * Math.PI) / 360);
  const along = (v: Vec3) => Math.abs(q[0] * v[0] + q[1] * v[1] + q[2] * v[2]);
  return z > 0 && along(u) <= t * z && along(r) <= t * aspect * z;
}
