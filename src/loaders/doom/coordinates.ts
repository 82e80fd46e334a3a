/**
 * The one place where Doom map coordinates become Lantern world coordinates.
 *
 * Doom: x east, y north, heights up (a right-handed frame with z = height). Lantern: y up. We keep
 * Doom's scale (1 map unit ≈ 1 inch) and map (x, y, height) to (x, height, −y): a rotation by −90°
 * about the x axis (determinant +1), so handedness, windings and cross products carry over, and a
 * polygon that is counter-clockwise on the map, seen from above, has its normal along +y.
 */
import type { Vec3 } from '../../math/vec3.ts';

/** World position of map point (x, y) at `height`. */
export function toWorld(x: number, y: number, height: number): Vec3 {
  return [x, height, -y];
}

/** World direction of a map angle in degrees (0 = east, 90 = north), horizontal. */
export function directionFromAngle(degrees: number): Vec3 {
  const a = (degrees * Math.PI) / 180;
  // `+ 0` turns −0 (angle 0) into 0, which reads better in messages and tests.
  return [Math.cos(a), 0, -Math.sin(a) + 0];
}

/** Doom flats are 64×64 and tile on the world grid, anchored at map (0, 0). */
export const FLAT_SIZE = 64;

/**
 * Texture coordinates of a floor or ceiling at map point (x, y). Doom's span drawer (R_MapPlane,
 * R_DrawSpan) reads flat texel (column, row) = (x mod 64, (−y) mod 64): columns run east, rows run
 * south, so north is up in the flat image seen from above, and floors and ceilings use the same
 * mapping. Lantern's uv (0, 0) is the image's top-left texel and wraps, so uv = (x, −y) / 64.
 * `originU`/`originV` (whole numbers of tiles) may be subtracted to keep the numbers small: tiling
 * makes that invisible, and float32 uvs stay precise far from the map origin.
 */
export function flatUv(x: number, y: number, originU = 0, originV = 0): [number, number] {
  return [x / FLAT_SIZE - originU, -y / FLAT_SIZE - originV];
}
