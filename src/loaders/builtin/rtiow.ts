/**
 * The final scene of Peter Shirley's *Ray Tracing in One Weekend* (v3 and v4, "A Final Render"): a
 * 22 × 22 field of small random spheres around three large ones (glass, brown diffuse, bronze metal)
 * on a huge ground sphere, under the book's white-to-blue sky, seen through a thin lens.
 *
 * Random choices follow the book's loop, in its order, drawn from mulberry32 (math/seeded-random.ts)
 * instead of the C library: the same seed always gives the same field. `rtiow` uses RTIOW_DEFAULT_SEED;
 * `rtiow:<seed>` (a whole number, 0 to 2^32 - 1) another one.
 */
import { LanternError } from '../../errors.ts';
import { length, sub, type Vec3 } from '../../math/vec3.ts';
import { seededRandom } from '../../math/seeded-random.ts';
import { placeEachOnce } from '../../scene/instances.ts';
import { diffuse, metallicRoughness, type Material, type Scene } from '../../scene/types.ts';
import { lookAt, sphereMesh, type Sphere } from './sphere-mesh.ts';

export const RTIOW_DEFAULT_SEED = 1;

/**
 * The book's fuzzy metal as GGX perceptual roughness. The book reflects, then adds fuzz × a point
 * uniform in the unit ball (v3's random_in_unit_sphere): for small fuzz the reflected direction tilts
 * by fuzz × the point's component across it, whose mean square is 2/5 (two of three axes of a uniform
 * ball, E[x²] = 1/5 each), so the lobe's RMS angle is fuzz·√(2/5). A microfacet lobe of GGX α tilts
 * the half vector by RMS ≈ α (for small α GGX and Beckmann agree in the core, Walter et al. 2007, and
 * Beckmann's E[tan²θm] = α²) and the reflected direction by twice that, 2α. Equal widths:
 * α = fuzz·√(2/5)/2 ≈ 0.316·fuzz, and perceptual roughness = √α. Fuzz 0.5 (the largest in the
 * scene) gives roughness 0.40; fuzz 0 a mirror. (v4 adds a unit vector instead: mean square 2/3,
 * α ≈ 0.41·fuzz, a little rougher.)
 */
export function fuzzToRoughness(fuzz: number): number {
  return Math.sqrt((fuzz * Math.sqrt(2 / 5)) / 2);
}

const glass = (name: string): Material => ({ kind: 'dielectric', name, emission: [0, 0, 0], ior: 1.5, roughness: 0, tint: [1, 1, 1], attenuationDistance: Infinity, attenuationColor: [1, 1, 1] });
const metal = (name: string, albedo: Vec3, fuzz: number): Material => metallicRoughness(name, { baseColor: albedo, metallic: 1, roughness: fuzzToRoughness(fuzz) });

/** The seed of a `rtiow:<seed>` parameter (undefined: the default). */
export function parseRtiowSeed(parameter: string | undefined): number {
  if (parameter === undefined) return RTIOW_DEFAULT_SEED;
  if (!/^\d+$/.test(parameter) || Number(parameter) > 0xffffffff) {
    throw new LanternError(`'rtiow:${parameter}': the seed must be a whole number from 0 to 4294967295`, 'for example rtiow:7');
  }
  return Number(parameter);
}

/** The book's final scene from a seed (a `rtiow:<seed>` parameter, or the default). */
export function rtiowScene(parameter?: string): Scene {
  const seed = parseRtiowSeed(parameter);
  const random = seededRandom(seed);
  const between = (lo: number, hi: number) => lo + (hi - lo) * random();
  const materials: Material[] = [diffuse('ground', [0.5, 0.5, 0.5]), glass('glass'), diffuse('large diffuse', [0.4, 0.2, 0.1]), metal('large metal', [0.7, 0.6, 0.5], 0)];
  const spheres: Sphere[] = [
    { center: [0, -1000, 0], radius: 1000, material: 0 },
    { center: [0, 1, 0], radius: 1, material: 1 },
    { center: [-4, 1, 0], radius: 1, material: 2 },
    { center: [4, 1, 0], radius: 1, material: 3 },
  ];
  for (let a = -11; a < 11; a++) {
    for (let b = -11; b < 11; b++) {
      const chooseMaterial = random();
      const center: Vec3 = [a + 0.9 * random(), 0.2, b + 0.9 * random()];
      if (length(sub(center, [4, 0.2, 0])) <= 0.9) continue;
      let material: number;
      if (chooseMaterial < 0.8) {
        const albedo: Vec3 = [random() * random(), random() * random(), random() * random()];
        material = materials.push(diffuse(`diffuse ${a},${b}`, albedo)) - 1;
      } else if (chooseMaterial < 0.95) {
        const albedo: Vec3 = [between(0.5, 1), between(0.5, 1), between(0.5, 1)];
        material = materials.push(metal(`metal ${a},${b}`, albedo, between(0, 0.5))) - 1;
      } else {
        material = 1; // every small glass sphere is the same glass
      }
      spheres.push({ center, radius: 0.2, material });
    }
  }
  const meshes = [sphereMesh('spheres', spheres)];
  return {
    name: parameter === undefined ? 'rtiow' : `rtiow:${seed}`,
    meshes,
    instances: placeEachOnce(meshes),
    materials,
    // The book's `aperture = 0.1` is the lens diameter (v4's defocus_angle 0.6° at distance 10 is the
    // same lens), and its focus distance is 10, not the 13.5 to the origin it looks at.
    camera: { ...lookAt([13, 2, 3], [0, 0, 0], 20), lens: { apertureRadius: 0.05, focusDistance: 10 } },
    // The book's sky: white below to (0.5, 0.7, 1.0) above, linear in the direction's y, 0.5·(y + 1).
    environment: { kind: 'gradient', zenith: [0.5, 0.7, 1.0], horizon: [0.75, 0.85, 1.0], ground: [1, 1, 1] },
  };
}
