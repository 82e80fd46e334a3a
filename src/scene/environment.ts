/**
 * What rays that leave the scene see. +y is up in every Lantern scene. The GPU form (a lat-long map
 * plus a sun disk, with importance-sampling tables) is made by gpu/pack/environment-pack.ts.
 */
import type { Vec3 } from '../math/vec3.ts';

/** A lat-long (equirectangular) image of linear radiance, row-major, top row (+y, zenith) first. */
export interface EnvironmentImage {
  readonly name: string;
  readonly width: number;
  readonly height: number;
  readonly rgb: Float32Array;
}

export type Environment =
  | { readonly kind: 'none' }
  | { readonly kind: 'constant'; readonly radiance: Vec3 }
  | { readonly kind: 'gradient'; readonly zenith: Vec3; readonly horizon: Vec3; readonly ground: Vec3 }
  | { readonly kind: 'sky'; readonly sunElevationDeg: number; readonly sunAzimuthDeg: number; readonly turbidity: number; readonly groundAlbedo: number; readonly intensity: number }
  | { readonly kind: 'map'; readonly image: EnvironmentImage; readonly rotationDeg: number; readonly intensity: number };
