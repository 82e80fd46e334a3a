/**
 * A mesh of analytic spheres and no triangles, for the sphere scenes (spheres, rtiow, orb,
 * golden-grid, hex-grid): each sphere a centre, a radius and a material, drawn exactly, never
 * tessellated. Also the camera helpers they share.
 */
import { normalize, sub, dot, type Vec3 } from '../../math/vec3.ts';
import type { Camera, Mesh } from '../../scene/types.ts';

export interface Sphere {
  readonly center: Vec3;
  readonly radius: number;
  /** Index into the scene's materials. */
  readonly material: number;
}

export function sphereMesh(name: string, spheres: readonly Sphere[]): Mesh {
  return {
    name,
    positions: new Float32Array(0),
    indices: new Uint32Array(0),
    materialIds: new Uint32Array(0),
    spheres: {
      centers: new Float32Array(spheres.flatMap((s) => [...s.center])),
      radii: new Float32Array(spheres.map((s) => s.radius)),
      materialIds: new Uint32Array(spheres.map((s) => s.material)),
    },
  };
}

/** A camera at `from` looking at `to` (y up); with `focusOn` (and an aperture radius) a thin lens focused on that point. */
export function lookAt(from: Vec3, to: Vec3, vfovDegrees: number, lens?: { readonly apertureRadius: number; readonly focusOn: Vec3 }, exposureStops?: number): Camera {
  const forward = normalize(sub(to, from));
  return {
    position: from,
    forward,
    up: [0, 1, 0],
    vfovDegrees,
    // The plane in focus is measured along forward (ThinLens.focusDistance), not along the ray to the point.
    ...(lens ? { lens: { apertureRadius: lens.apertureRadius, focusDistance: dot(sub(lens.focusOn, from), forward) } } : {}),
    ...(exposureStops !== undefined ? { exposureStops } : {}),
  };
}
