/**
 * What rays that leave the scene see: none, a constant, a three-colour gradient, the Hosek–Wilkie sky
 * with its sun, or a lat-long HDR map. docs/environment.md states every convention; in short:
 *
 * - +y is up. Radiance is linear RGB (Rec. 709 primaries) in the scene's radiance units.
 * - Lat-long images: row-major, top row = +y (zenith) first. The image centre (u = 0.5, v = 0.5) is
 *   the direction -z (straight ahead of Lantern's default camera) and u grows toward +x, so a
 *   panorama appears unmirrored: u = 0.5 + atan2(x, -z) / 2π, v = acos(y) / π. Mitsuba 3 and
 *   Blender centre their maps elsewhere (the rotations that match them: docs/environment.md).
 * - Azimuths are measured about +y from +z toward +x, in degrees (a sun at azimuth 0 lies toward +z,
 *   at 90 toward +x). Elevations are degrees above the horizon (the xz plane).
 * - `rotationDeg` turns a map about +y in the same sense (+z toward +x).
 */
import type { Vec3 } from '../math/vec3.ts';

/** A lat-long (equirectangular) image of linear radiance, row-major, top row (+y, zenith) first. */
export interface EnvironmentImage {
  readonly name: string;
  readonly width: number;
  readonly height: number;
  /** width × height × 3 floats, linear RGB radiance. */
  readonly rgb: Float32Array;
}

/** What rays that leave the scene see. +y is up in every Lantern scene. */
export type Environment =
  | { readonly kind: 'none' }
  /** The same radiance in every direction. */
  | { readonly kind: 'constant'; readonly radiance: Vec3 }
  /**
   * Radiance blended by the direction's height y: horizon → zenith as y goes 0 → 1, horizon → ground
   * as y goes 0 → -1 (linear in y, so continuous at the horizon).
   */
  | { readonly kind: 'gradient'; readonly zenith: Vec3; readonly horizon: Vec3; readonly ground: Vec3 }
  /**
   * The Hosek–Wilkie (2012) clear sky with a sun disk. sunElevationDeg in [-90, 90] (the sky model is
   * fitted for 0–90; below 0 the sky is evaluated at 0 and the sun is hidden), sunAzimuthDeg from +z
   * toward +x, turbidity in [1, 10], groundAlbedo in [0, 1]. `intensity` multiplies sky and sun,
   * whose radiance is in W m⁻² sr⁻¹ (Y × 683 = luminance in cd/m²): daylight is ~10⁴ times brighter
   * than a unit-radiance studio light, so scenes usually set intensity ~1e-4 or expose for it.
   */
  | {
      readonly kind: 'sky';
      readonly sunElevationDeg: number;
      readonly sunAzimuthDeg: number;
      readonly turbidity: number;
      readonly groundAlbedo: number;
      readonly intensity: number;
    }
  /** An HDR panorama, turned by rotationDeg about +y (+z toward +x) and multiplied by intensity. */
  | { readonly kind: 'map'; readonly image: EnvironmentImage; readonly rotationDeg: number; readonly intensity: number };

export type EnvironmentKind = Environment['kind'];

/** The unit direction at the given elevation and azimuth (degrees; azimuth from +z toward +x). */
export function directionFromElevationAzimuth(elevationDeg: number, azimuthDeg: number): Vec3 {
  const e = (elevationDeg * Math.PI) / 180;
  const a = (azimuthDeg * Math.PI) / 180;
  return [Math.sin(a) * Math.cos(e), Math.sin(e), Math.cos(a) * Math.cos(e)];
}

/** Lat-long coordinates (u, v) in [0, 1]² of a unit direction (see the file header). */
export function latLongFromDirection(d: Vec3): [number, number] {
  let u = 0.5 + Math.atan2(d[0], -d[2]) / (2 * Math.PI);
  if (u >= 1) u -= 1;
  const v = Math.acos(Math.min(1, Math.max(-1, d[1]))) / Math.PI;
  return [u, v];
}

/** The unit direction at lat-long coordinates (u, v); the inverse of latLongFromDirection. */
export function directionFromLatLong(u: number, v: number): Vec3 {
  const phi = 2 * Math.PI * (u - 0.5);
  const theta = Math.PI * v;
  const s = Math.sin(theta);
  return [s * Math.sin(phi), Math.cos(theta), -s * Math.cos(phi)];
}
