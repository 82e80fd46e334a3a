/**
 * A caustic study: a solid glass orb over a polished, checkered floor, lit by one small emissive
 * sphere high to the left in a dim room. The orb focuses the lamp into a bright spot on the floor to
 * its right, inside its own shadow, where the camera sees it; the floor mirrors the orb, and the
 * checks show the refraction through it. A path
 * tracer finds the caustic only by paths that leave the floor, pass through the glass and happen to
 * hit the lamp, so it is the slowest part of the image to converge: what the scene is for.
 */
import { placeEachOnce } from '../../scene/instances.ts';
import { floorSquare } from '../../scene/shapes.ts';
import { metallicRoughness, type Material, type Scene, type Texture } from '../../scene/types.ts';
import { lookAt, sphereMesh } from './sphere-mesh.ts';

/**
 * The lamp: radius 0.3 at about 4.9 from the floor under the orb, 45° up, so it subtends
 * Ω ≈ π·0.3²/4.9² ≈ 0.012 sr and gives E ≈ 300 · 0.012 · cos 45° ≈ 2.5 there; the light tiles'
 * diffuse base (0.7 × 0.72) returns Lo ≈ 0.5·2.5/π ≈ 0.4, mid-grey at exposure 0, and the caustic
 * several times more. (A first version at 120, behind the orb, left the image dark: its shadow
 * covered the foreground.)
 */
export const ORB_LAMP_RADIANCE = 300;
const ORB_RADIUS = 1;

/** Light and dark tiles, one texel each, sampled nearest. */
function checker(): Texture {
  const rgba = new Uint8Array([220, 220, 220, 255, 90, 90, 90, 255, 90, 90, 90, 255, 220, 220, 220, 255]);
  return { name: 'checker', width: 2, height: 2, rgba, filter: 'nearest' };
}

export function orbScene(): Scene {
  const materials: Material[] = [
    // A dielectric coat (F0 4 %) over a diffuse base: a clear reflection of the orb, and a surface the caustic lands on.
    metallicRoughness('polished floor', { baseColor: [0.7, 0.7, 0.7], metallic: 0, roughness: 0.08, baseColorTexture: { texture: 0 } }),
    { kind: 'dielectric', name: 'glass orb', emission: [0, 0, 0], ior: 1.5, roughness: 0, tint: [1, 1, 1], attenuationDistance: Infinity, attenuationColor: [1, 1, 1] },
    { kind: 'emissive', name: 'lamp', emission: [ORB_LAMP_RADIANCE, ORB_LAMP_RADIANCE * 0.95, ORB_LAMP_RADIANCE * 0.85] },
  ];
  const meshes = [
    floorSquare('floor', 20, 20, 0),
    sphereMesh('orb and lamp', [
      { center: [0, ORB_RADIUS, 0], radius: ORB_RADIUS, material: 1 },
      { center: [-3.5, 3.5, 0], radius: 0.3, material: 2 },
    ]),
  ];
  return {
    name: 'orb',
    meshes,
    instances: placeEachOnce(meshes),
    materials,
    textures: [checker()],
    camera: lookAt([0.4, 2.4, 5.5], [0.4, 0.6, 0], 35),
    // A faint fill so that what the lamp does not reach is dark grey, not black.
    environment: { kind: 'constant', radiance: [0.05, 0.05, 0.06] },
  };
}
