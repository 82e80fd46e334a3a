/**
 * The white furnace: a closed cube seen from inside, every face with albedo a = 0.8 and emitted
 * radiance Le = 1 toward the inside. Radiance is then the same everywhere and solves L = Le + a·L, so
 * every pixel converges to Le / (1 - a) = 5. With at most B bounces it is the partial geometric sum
 * Σ_{k=0..B} a^k. Any energy gained or lost by sampling, MIS weights or Russian roulette shows here.
 */
import type { Vec3 } from '../../math/vec3.ts';
import { MeshBuilder } from '../../scene/builder.ts';
import { placeEachOnce } from '../../scene/instances.ts';
import { diffuse, type Scene } from '../../scene/types.ts';

export const FURNACE_ALBEDO = 0.8;
export const FURNACE_EMISSION = 1.0;

/** The radiance every pixel converges to with at most `maxBounces` bounces (Infinity: 5). */
export function furnaceRadiance(maxBounces: number): number {
  const a = FURNACE_ALBEDO;
  return (FURNACE_EMISSION * (1 - a ** (maxBounces + 1))) / (1 - a);
}

export function whiteFurnace(): Scene {
  const b = new MeshBuilder('furnace');
  const m = b.material(diffuse('furnace', [FURNACE_ALBEDO, FURNACE_ALBEDO, FURNACE_ALBEDO], [FURNACE_EMISSION, FURNACE_EMISSION, FURNACE_EMISSION]));
  // Unit cube [-1, 1]^3; each face wound so that its geometric normal points into the cube.
  const p = (x: number, y: number, z: number): Vec3 => [x, y, z];
  b.quad(m, p(-1, -1, -1), p(-1, -1, 1), p(1, -1, 1), p(1, -1, -1)); // floor y = -1, normal +y
  b.quad(m, p(-1, 1, -1), p(1, 1, -1), p(1, 1, 1), p(-1, 1, 1)); // ceiling y = +1, normal -y
  b.quad(m, p(-1, -1, -1), p(-1, 1, -1), p(-1, 1, 1), p(-1, -1, 1)); // x = -1, normal +x
  b.quad(m, p(1, -1, -1), p(1, -1, 1), p(1, 1, 1), p(1, 1, -1)); // x = +1, normal -x
  b.quad(m, p(-1, -1, -1), p(1, -1, -1), p(1, 1, -1), p(-1, 1, -1)); // z = -1, normal +z
  b.quad(m, p(-1, -1, 1), p(-1, 1, 1), p(1, 1, 1), p(1, -1, 1)); // z = +1, normal -z
  const meshes = [b.build()];
  return {
    name: 'furnace',
    meshes,
    instances: placeEachOnce(meshes),
    materials: b.materials,
    camera: { position: [0.2, -0.1, -0.3], forward: [0.3, 0.2, 1], up: [0, 1, 0], vfovDegrees: 90 },
  };
}
