/**
 * Spheres and capsules rendered, against answers known in closed form:
 * - in a uniform environment of radiance 1, one convex diffuse object of albedo ρ has radiance ρ
 *   everywhere (it sees only the sky), and lossless glass objects, nested or not, leave every pixel
 *   at exactly 1 (energy conservation): the glass is traced from both sides;
 * - the ground sphere of radius 1000 under a camera at distance 10 (Ray Tracing in One Weekend's
 *   set-up) is a convex diffuse object too: acne (self-shadowing) would darken pixels below ρ, holes
 *   would show the sky (1) below the horizon;
 * - a spherical light of radiance Le and radius R, its centre at height D over a diffuse floor, gives
 *   the floor point at distance d from the centre the irradiance π·Le·R²·cos θ / d² (the sphere is
 *   wholly above the horizon), so radiance ρ·Le·R²·D / d³; sampled by solid angle (MIS) and found by
 *   BSDF rays alone, both must converge to it.
 */
import { describe, expect, it } from 'vitest';
import { traverseClosest } from '../../src/bvh/traverse.ts';
import { cameraBasis } from '../../src/gpu/view.ts';
import { IDENTITY } from '../../src/math/mat4.ts';
import type { Vec3 } from '../../src/math/vec3.ts';
import { prepareScene, type PreparedScene } from '../../src/renderer/prepare.ts';
import type { Material, Mesh, Scene } from '../../src/scene/types.ts';
import { floorScene, grey, lum, pixelFootprint, renderScene, se, squareMean, topDownCamera } from './scene-render.ts';

const SIZE = 24;
const glass: Material = { kind: 'dielectric', name: 'glass', emission: [0, 0, 0], ior: 1.5, roughness: 0, tint: [1, 1, 1], attenuationDistance: Infinity, attenuationColor: [1, 1, 1] };
const white = (albedo: number): Material => ({ kind: 'diffuse', name: 'diffuse', albedo: grey(albedo), emission: [0, 0, 0] });

function analyticMesh(spheres: [Vec3, number][], capsules: [Vec3, Vec3, number][] = [], material = 0): Mesh {
  return {
    name: 'shapes',
    positions: new Float32Array(0),
    indices: new Uint32Array(0),
    materialIds: new Uint32Array(0),
    spheres: { centers: new Float32Array(spheres.flatMap(([c]) => c)), radii: new Float32Array(spheres.map(([, r]) => r)), materialIds: new Uint32Array(spheres.length).fill(material) },
    capsules: { endpoints: new Float32Array(capsules.flatMap(([a, b]) => [...a, ...b])), radii: new Float32Array(capsules.map(([, , r]) => r)), materialIds: new Uint32Array(capsules.length).fill(material) },
  };
}

function furnaceScene(mesh: Mesh, material: Material, camera: Scene['camera']): Scene {
  return { name: 'analytic furnace', meshes: [mesh], instances: [{ id: 0, mesh: 0, worldFromObject: IDENTITY }], materials: [material], camera, environment: { kind: 'constant', radiance: [1, 1, 1] } };
}

/** Pixels whose whole footprint (centre and corners) sees primitive hits (true) or misses (false) only, by the CPU oracle. */
function classify(prepared: PreparedScene, width: number, height: number): ('hit' | 'miss' | 'edge')[] {
  const b = cameraBasis(prepared.scene.camera, width / height);
  const { positions, kinds } = prepared.triangles;
  const probe = (x: number, y: number) => {
    const nx = (2 * x) / width - 1, ny = 1 - (2 * y) / height;
    const d: Vec3 = [0, 1, 2].map((k) => b.forward[k]! + nx * b.right[k]! + ny * b.up[k]!) as unknown as Vec3;
    return traverseClosest(prepared.bvh, positions, { origin: b.position, direction: d }, kinds) !== null;
  };
  const out: ('hit' | 'miss' | 'edge')[] = [];
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const seen = [probe(x + 0.5, y + 0.5), probe(x, y), probe(x + 1, y), probe(x, y + 1), probe(x + 1, y + 1)];
      out.push(seen.every(Boolean) ? 'hit' : seen.some(Boolean) ? 'edge' : 'miss');
    }
  }
  return out;
}

/** Every classified pixel within 5 standard errors (plus 1 %) of its expected value, and the means within 1 %. */
async function expectFurnace(scene: Scene, objectValue: number, spp: number, maxBounces: number) {
  const prepared = prepareScene(scene);
  const classes = classify(prepared, SIZE, SIZE);
  const acc = await renderScene(prepared, { width: SIZE, height: SIZE, spp, maxBounces });
  const bad: string[] = [];
  let hits = 0, hitSum = 0;
  classes.forEach((c, i) => {
    if (c === 'edge') return;
    const expected = c === 'hit' ? objectValue : 1;
    const value = lum(acc, i);
    if (c === 'hit') {
      hits++;
      hitSum += value;
    }
    if (Math.abs(value - expected) > 5 * se(acc, i) + 0.01 * expected) bad.push(`pixel ${i % SIZE},${Math.floor(i / SIZE)} (${c}): ${value.toFixed(4)} ± ${se(acc, i).toFixed(4)}, expected ${expected}`);
  });
  expect(hits).toBeGreaterThan(SIZE * SIZE * 0.15);
  expect(bad.slice(0, 8)).toEqual([]);
  expect(Math.abs(hitSum / hits - objectValue)).toBeLessThan(0.01 * objectValue);
}

describe('analytic primitives in a uniform environment', () => {
  it('a diffuse sphere has radiance ρ', async () => {
    await expectFurnace(furnaceScene(analyticMesh([[[0, 0, 0], 1]]), white(0.8), { position: [0, 0.5, 4], forward: [0, -0.5, -4], up: [0, 1, 0], vfovDegrees: 40 }), 0.8, 128, 8);
  });

  it('a diffuse capsule has radiance ρ', async () => {
    await expectFurnace(furnaceScene(analyticMesh([], [[[-1, -0.3, 0], [1, 0.4, -0.2], 0.6]]), white(0.6), { position: [0.3, 1, 4], forward: [-0.3, -1, -4], up: [0, 1, 0], vfovDegrees: 50 }), 0.6, 128, 8);
  });

  it('lossless glass spheres and capsules, one inside another, leave every pixel at 1', async () => {
    const mesh = analyticMesh(
      [[[0, 0, 0], 1], [[0.2, 0.1, 0], 0.4], [[-1.6, 0.3, -1], 0.5]],
      [[[0.8, -0.8, 0.8], [1.8, 0.6, 0.2], 0.3]],
    );
    await expectFurnace(furnaceScene(mesh, glass, { position: [0, 0.4, 5], forward: [0, -0.4, -5], up: [0, 1, 0], vfovDegrees: 45 }), 1, 128, 32);
  });

  it('the ground sphere of radius 1000, seen from (13, 2, 3), has neither acne nor holes', async () => {
    const scene = furnaceScene(analyticMesh([[[0, -1000, 0], 1000]]), white(0.5), { position: [13, 2, 3], forward: [-13, -2, -3], up: [0, 1, 0], vfovDegrees: 20 });
    await expectFurnace(scene, 0.5, 64, 4);
  });
});

describe('a spherical light', () => {
  const R = 0.5, D = 2, Le = 10, rho = 0.5, half = 1.2, height = 1.2;
  const scene = floorScene('sphere light', [white(rho), { kind: 'emissive', name: 'bulb', emission: [Le, Le, Le] }], { camera: topDownCamera([0, 0], height, half) }, [analyticMesh([[[0, D, 0], R]], [], 1)]);
  const withLight: Scene = { ...scene, instances: [...scene.instances, { id: 1, mesh: 1, worldFromObject: IDENTITY }] };
  const expected = (x: number, z: number) => (rho * Le * R * R * D) / Math.pow(x * x + z * z + D * D, 1.5);

  for (const lightSampling of ['mis', 'bsdf'] as const) {
    it(`lights the floor with π·Le·R²·cos θ / d² (${lightSampling})`, async () => {
      const acc = await renderScene(withLight, { width: 16, height: 16, spp: lightSampling === 'mis' ? 128 : 1024, maxBounces: 1, lightSampling });
      const bad: string[] = [];
      let sum = 0, want = 0;
      for (let py = 0; py < 16; py++) {
        for (let px = 0; px < 16; px++) {
          const i = py * 16 + px;
          const e = squareMean(expected, pixelFootprint([0, 0], half, 16, px, py));
          sum += lum(acc, i);
          want += e;
          if (Math.abs(lum(acc, i) - e) > 5 * se(acc, i) + 0.01 * e) bad.push(`pixel ${px},${py}: ${lum(acc, i).toFixed(4)} ± ${se(acc, i).toFixed(4)}, expected ${e.toFixed(4)}`);
        }
      }
      expect(bad.slice(0, 8)).toEqual([]);
      // MIS converges fast; BSDF rays alone are noisier.
      expect(Math.abs(sum - want) / want).toBeLessThan(lightSampling === 'mis' ? 0.01 : 0.02);
    });
  }
});
