/**
 * The materials scene: a row of spheres on a checkered floor under a sky, from a mirror through
 * rougher and rougher metal to gold, clear and frosted glass, glossy plastic and a Lambertian
 * reference, so that every case of the BSDF module is seen side by side (docs/materials.md renders
 * it). One sphere mesh, placed eight times by instances.
 */
import { fromTrs, translation } from '../../math/mat4.ts';
import type { Vec3 } from '../../math/vec3.ts';
import { floorSquare, uvSphere } from '../../scene/shapes.ts';
import { DAYLIGHT_EXPOSURE_STOPS } from '../../scene/sky.ts';
import { diffuse, metallicRoughness, type Instance, type Material, type Scene, type Texture } from '../../scene/types.ts';

const SPHERE_RADIUS = 1;
const SPACING = 2.3;
const FLOOR_HALF = 40;

const SILVER: Vec3 = [0.95, 0.93, 0.88];
/** Gold's F0 (linear sRGB), as commonly tabulated from its complex index of refraction. */
export const GOLD: Vec3 = [1.0, 0.766, 0.336];

/** The spheres, left to right, by material. */
export const MATERIAL_SPHERES: readonly Material[] = [
  metal('mirror', SILVER, 0),
  metal('metal, roughness 0.25', SILVER, 0.25),
  metal('metal, roughness 0.5', SILVER, 0.5),
  metal('metal, roughness 1', SILVER, 1),
  metal('gold, roughness 0.3', GOLD, 0.3),
  { kind: 'dielectric', name: 'glass', emission: [0, 0, 0], ior: 1.5, roughness: 0, tint: [1, 1, 1], attenuationDistance: Infinity, attenuationColor: [1, 1, 1] },
  { kind: 'dielectric', name: 'frosted glass', emission: [0, 0, 0], ior: 1.5, roughness: 0.35, tint: [1, 1, 1], attenuationDistance: Infinity, attenuationColor: [1, 1, 1] },
  plastic('red plastic', [0.7, 0.06, 0.05], 0.25),
  diffuse('diffuse reference', [0.8, 0.8, 0.8]),
];

function metal(name: string, color: Vec3, roughness: number): Material {
  return metallicRoughness(name, { baseColor: color, metallic: 1, roughness });
}

function plastic(name: string, color: Vec3, roughness: number): Material {
  return metallicRoughness(name, { baseColor: color, metallic: 0, roughness });
}

/** A two-tone checker, one texel per tile (sampled nearest, so the tiles stay sharp). */
function checker(): Texture {
  const n = 2;
  const rgba = new Uint8Array(n * n * 4);
  for (let y = 0; y < n; y++) {
    for (let x = 0; x < n; x++) {
      const v = (x + y) % 2 === 0 ? 200 : 120;
      rgba.set([v, v, v, 255], (y * n + x) * 4);
    }
  }
  return { name: 'checker', width: n, height: n, rgba, filter: 'nearest' };
}

export function materialsScene(): Scene {
  const floorMaterial = diffuse('floor', [0.8, 0.8, 0.8], [0, 0, 0], { albedoTexture: { texture: 0 } });
  const materials: Material[] = [floorMaterial, ...MATERIAL_SPHERES];
  const meshes = [floorSquare('floor', FLOOR_HALF, FLOOR_HALF / 2, 0), uvSphere('sphere', SPHERE_RADIUS, 96, 48)];
  const instances: Instance[] = [{ id: 0, name: 'floor', mesh: 0, worldFromObject: translation([0, 0, 0]) }];
  const count = MATERIAL_SPHERES.length;
  MATERIAL_SPHERES.forEach((m, i) => {
    const x = (i - (count - 1) / 2) * SPACING;
    instances.push({ id: i + 1, name: m.name, mesh: 1, material: i + 1, worldFromObject: fromTrs([x, SPHERE_RADIUS, 0], [0, 0, 0, 1], [1, 1, 1]) });
  });
  return {
    name: 'materials',
    meshes,
    instances,
    materials,
    textures: [checker()],
    camera: { position: [0, 4, 15], forward: [0, -0.22, -1], up: [0, 1, 0], vfovDegrees: 40, exposureStops: DAYLIGHT_EXPOSURE_STOPS },
    environment: { kind: 'sky', sunElevationDeg: 35, sunAzimuthDeg: 40, turbidity: 3, groundAlbedo: 0.3, intensity: 1 },
    metersPerUnit: 0.1,
  };
}
