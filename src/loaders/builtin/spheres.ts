/**
 * The classic sphere tutorial scene (after *Ray Tracing in One Weekend*'s chapters on materials and
 * the positionable camera): a blue diffuse, a glass and a gold-coloured fuzzy metal sphere on a huge
 * yellowish ground sphere, under a white-to-blue gradient sky, with one emissive sphere above as a
 * lamp (it adds highlights and a soft shadow). Everything is an analytic sphere.
 */
import { placeEachOnce } from '../../scene/instances.ts';
import { diffuse, metallicRoughness, type Material, type Scene } from '../../scene/types.ts';
import { fuzzToRoughness } from './rtiow.ts';
import { lookAt, sphereMesh } from './sphere-mesh.ts';

/**
 * The lamp's radiance. It subtends Ω ≈ π·0.35²/1.7² ≈ 0.13 sr from the spheres, so it adds
 * irradiance E ≈ 8 · 0.13 ≈ 1.1 against the sky's ≈ π·0.85 ≈ 2.7: a clear highlight and shadow
 * without burning out the tops of the spheres.
 */
export const SPHERES_LAMP_RADIANCE = 8;

export function spheresScene(): Scene {
  const materials: Material[] = [
    diffuse('ground', [0.8, 0.8, 0.0]),
    diffuse('blue diffuse', [0.1, 0.2, 0.5]),
    { kind: 'dielectric', name: 'glass', emission: [0, 0, 0], ior: 1.5, roughness: 0, tint: [1, 1, 1], attenuationDistance: Infinity, attenuationColor: [1, 1, 1] },
    metallicRoughness('fuzzy metal', { baseColor: [0.8, 0.6, 0.2], metallic: 1, roughness: fuzzToRoughness(0.3) }),
    { kind: 'emissive', name: 'lamp', emission: [SPHERES_LAMP_RADIANCE, SPHERES_LAMP_RADIANCE, SPHERES_LAMP_RADIANCE * 0.9] },
  ];
  const meshes = [
    sphereMesh('spheres', [
      { center: [0, -100.5, -1], radius: 100, material: 0 },
      { center: [0, 0, -1.2], radius: 0.5, material: 1 },
      { center: [-1, 0, -1], radius: 0.5, material: 2 },
      { center: [1, 0, -1], radius: 0.5, material: 3 },
      { center: [0.4, 1.6, -2.2], radius: 0.35, material: 4 },
    ]),
  ];
  return {
    name: 'spheres',
    meshes,
    instances: placeEachOnce(meshes),
    materials,
    camera: lookAt([-2, 2, 1], [0, 0, -1], 40),
    environment: { kind: 'gradient', zenith: [0.5, 0.7, 1.0], horizon: [0.75, 0.85, 1.0], ground: [1, 1, 1] },
  };
}
