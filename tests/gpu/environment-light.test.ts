/**
 * The environment as a light, end to end through the integrator (path.wgsl, NEE + MIS):
 * - a diffuse sphere of albedo a in a constant environment L, seen from outside: a convex body sees
 *   only the environment, so every pixel on it is a·L after exactly one bounce, and every pixel off it L;
 * - white furnaces per material kind: white metal and clear glass spheres show L everywhere (energy
 *   conserved), a white glTF dielectric ≈ L and never above;
 * - the sun: a diffuse floor under the Hosek–Wilkie sky with maxBounces 1 has radiance
 *   ρ/π·(E_sun + E_sky), E_sun = L_sun·Ω_sun·sin e and E_sky the baked sky's irradiance, integrated here.
 */
import { describe, expect, it } from 'vitest';
import { packEnvironment } from '../../src/gpu/pack/environment-pack.ts';
import { IDENTITY } from '../../src/math/mat4.ts';
import { SkyModel, SUN_ANGULAR_RADIUS_DEG } from '../../src/scene/sky.ts';
import { uvSphere } from '../../src/scene/shapes.ts';
import type { Environment } from '../../src/scene/environment.ts';
import { diffuse, type Material, type Scene } from '../../src/scene/types.ts';
import { floorScene, grey, lum, regionStats, renderScene, se, topDownCamera } from './scene-render.ts';

const L = 2;
const SIZE = 16;
/** Camera on +z looking at the unit sphere at the origin: the sphere fills about 70 % of the image height. */
const CAMERA = { position: [0, 0, 4] as [number, number, number], forward: [0, 0, -1] as [number, number, number], up: [0, 1, 0] as [number, number, number], vfovDegrees: 40 };

function sphereScene(material: Material, environment: Environment = { kind: 'constant', radiance: grey(L) }): Scene {
  return {
    name: `sphere (${material.name})`,
    meshes: [uvSphere('sphere', 1, 128, 64)],
    instances: [{ id: 0, mesh: 0, worldFromObject: IDENTITY }],
    materials: [material],
    camera: CAMERA,
    environment,
  };
}

/** Whether the ray through image point (x, y) (pixels, square image) hits the unit sphere (a slightly smaller one when shrink < 1). */
function rayHitsSphere(x: number, y: number, radius: number): boolean {
  const t = Math.tan((CAMERA.vfovDegrees * Math.PI) / 360);
  const d = [(2 * x / SIZE - 1) * t, -(2 * y / SIZE - 1) * t, -1];
  const n = Math.hypot(d[0]!, d[1]!, d[2]!);
  // Distance from the origin to the line through (0, 0, 4) along d.
  const o = [0, 0, 4];
  const tc = -(o[0]! * d[0]! + o[1]! * d[1]! + o[2]! * d[2]!) / (n * n);
  const c = [o[0]! + tc * d[0]!, o[1]! + tc * d[1]!, o[2]! + tc * d[2]!];
  return Math.hypot(c[0]!, c[1]!, c[2]!) < radius;
}

/**
 * Pixels entirely on the sphere (all four corners hit a sphere a little smaller than the
 * tessellated one, whose silhouette is inside the true sphere) and entirely off it.
 */
function classifyPixels(): { on: number[]; off: number[] } {
  const on: number[] = [], off: number[] = [];
  for (let py = 0; py < SIZE; py++) {
    for (let px = 0; px < SIZE; px++) {
      const corners = [[px, py], [px + 1, py], [px, py + 1], [px + 1, py + 1]] as const;
      if (corners.every(([x, y]) => rayHitsSphere(x, y, 0.99))) on.push(py * SIZE + px);
      else if (corners.every(([x, y]) => !rayHitsSphere(x, y, 1.01))) off.push(py * SIZE + px);
    }
  }
  return { on, off };
}

/** glTF metallic-roughness with the glTF defaults (as loaders/builtin/materials.ts). */
function gltf(name: string, metallic: number, roughness: number): Material {
  return {
    kind: 'metallic-roughness', name, emission: [0, 0, 0], baseColor: [1, 1, 1], opacity: 1, metallic, roughness, ior: 1.5, specular: 1,
    specularColor: [1, 1, 1], transmission: 0, thickness: 0, attenuationDistance: Infinity, attenuationColor: [1, 1, 1],
  };
}

const GLASS: Material = { kind: 'dielectric', name: 'clear glass', emission: [0, 0, 0], ior: 1.5, roughness: 0, tint: [1, 1, 1], attenuationDistance: Infinity, attenuationColor: [1, 1, 1] };

describe('a diffuse sphere in a constant environment', () => {
  const { on, off } = classifyPixels();

  it('has pixels on and off the sphere to test', () => {
    expect(on.length).toBeGreaterThan(60);
    expect(off.length).toBeGreaterThan(60);
  });

  for (const lightSampling of ['mis', 'bsdf'] as const) {
    it(`converges to a·L on the sphere and L off it (${lightSampling})`, async () => {
      const a = 0.5;
      const acc = await renderScene(sphereScene(diffuse('grey', grey(a)), { kind: 'constant', radiance: grey(L) }), { width: SIZE, height: SIZE, spp: 128, maxBounces: 16, lightSampling, seed: 3 });
      let worst = 0;
      for (const i of on) worst = Math.max(worst, Math.abs(lum(acc, i) - a * L) / Math.max(se(acc, i), 1e-4));
      const sphere = regionStats(acc, on);
      console.log(`${lightSampling}: sphere mean ${sphere.mean.toFixed(4)} ± ${sphere.se.toFixed(4)} (expected ${a * L}), worst |z| ${worst.toFixed(2)}`);
      expect(Math.abs(sphere.mean - a * L) / (a * L)).toBeLessThan(0.01);
      // (BSDF sampling of a Lambertian sphere under a constant sky has zero variance: every sample is a·L.)
      expect(Math.abs(sphere.mean - a * L)).toBeLessThan(4 * sphere.se + 1e-5);
      // ~130 pixels: |z| > 5 has probability ~1e-4 over the set if the estimator is unbiased.
      expect(worst).toBeLessThan(5);
      // Off the sphere: the camera ray sees the environment directly, with no noise at all.
      for (const i of off) expect(lum(acc, i)).toBeCloseTo(L, 5);
      // The test's power: a sphere that reflected a² (two bounces) or 1 would be caught at once.
      expect(Math.abs(sphere.mean - a * a * L)).toBeGreaterThan(20 * sphere.se + 0.1);
    });
  }
});

describe('white furnaces per material kind (uniform environment L, many bounces)', () => {
  const { on, off } = classifyPixels();
  const all = [...on, ...off];
  const cases: { material: Material; tolerance: number; neverAbove?: boolean }[] = [
    { material: gltf('white metal, roughness 0.5', 1, 0.5), tolerance: 0.02 },
    { material: GLASS, tolerance: 0.02 },
    { material: gltf('white glTF dielectric, roughness 0.5', 0, 0.5), tolerance: 0.02, neverAbove: true },
  ];
  for (const { material, tolerance, neverAbove } of cases) {
    it(`${material.name}: L everywhere within ${tolerance * 100} %${neverAbove ? ', never above' : ''}`, async () => {
      const acc = await renderScene(sphereScene(material), { width: SIZE, height: SIZE, spp: 128, maxBounces: 64, seed: 5 });
      const sphere = regionStats(acc, on);
      const image = regionStats(acc, all);
      console.log(`${material.name}: sphere ${sphere.mean.toFixed(4)} ± ${sphere.se.toFixed(4)}, image ${image.mean.toFixed(4)} (L = ${L})`);
      expect(Math.abs(sphere.mean - L) / L).toBeLessThan(tolerance);
      for (const i of on) expect(Math.abs(lum(acc, i) - L) / L, `pixel ${i}`).toBeLessThan(tolerance + 5 * se(acc, i) / L);
      if (neverAbove) expect(sphere.mean).toBeLessThan(L + 3 * sphere.se);
    });
  }
});

describe('the sun and sky light a diffuse floor', () => {
  it('radiance ρ/π·(E_sun + E_sky) with 1 bounce', async () => {
    const rho = 0.5;
    const elevation = 35;
    const env = { kind: 'sky', sunElevationDeg: elevation, sunAzimuthDeg: 60, turbidity: 3, groundAlbedo: 0.3, intensity: 1e-3 } as const;
    const scene = floorScene('floor under the sky', [diffuse('floor', grey(rho))], { environment: env, camera: topDownCamera([0, 0], 2, 1) });

    // E_sun = L_sun Ω sin e (the sun's disk is 0.27°: cos varies by < 1e-4 over it).
    const model = new SkyModel(env);
    const omega = 2 * Math.PI * (1 - Math.cos((SUN_ANGULAR_RADIUS_DEG * Math.PI) / 180));
    const eSun = model.sunRadiance.map((l) => l * env.intensity * omega * Math.sin((elevation * Math.PI) / 180));
    // E_sky: the baked lat-long sky (what the GPU looks up) times cos θ over the upper hemisphere, texel by texel.
    const tex = packEnvironment(env).environment_map;
    const eSky = [0, 0, 0];
    for (let j = 0; j < tex.height; j++) {
      const ct0 = Math.cos((j / tex.height) * Math.PI), ct1 = Math.cos(((j + 1) / tex.height) * Math.PI);
      if (ct1 < 0) break;
      const cosTheta = (ct0 + ct1) / 2;
      const texelOmega = (2 * Math.PI / tex.width) * (ct0 - ct1);
      for (let i = 0; i < tex.width; i++) for (let c = 0; c < 3; c++) eSky[c]! += tex.rgb[(j * tex.width + i) * 3 + c]! * env.intensity * cosTheta * texelOmega;
    }
    const expected = [0, 1, 2].map((c) => (rho / Math.PI) * (eSun[c]! + eSky[c]!));
    console.log(`E_sun ${eSun.map((v) => v.toFixed(3))}, E_sky ${eSky.map((v) => v.toFixed(3))}, expected floor radiance ${expected.map((v) => v.toFixed(4))}`);
    // Power: the sky alone is a sizeable part, so leaving either term out is caught.
    expect(eSky[1]! / (eSun[1]! + eSky[1]!)).toBeGreaterThan(0.1);
    expect(eSun[1]! / (eSun[1]! + eSky[1]!)).toBeGreaterThan(0.5);

    const acc = await renderScene(scene, { width: 8, height: 8, spp: 256, maxBounces: 1, seed: 9 });
    const n = acc.width * acc.height;
    const mean = [0, 0, 0];
    for (let i = 0; i < n; i++) for (let c = 0; c < 3; c++) mean[c]! += acc.radiance[i * 3 + c]! / n;
    const all = regionStats(acc, [...Array(n).keys()]);
    console.log(`floor radiance ${mean.map((v) => v.toFixed(4))} ± ${all.se.toFixed(4)} (luminance)`);
    for (let c = 0; c < 3; c++) expect(Math.abs(mean[c]! - expected[c]!) / expected[c]!, `channel ${c}`).toBeLessThan(0.03);
  });
});

describe('Renderer.setEnvironment', () => {
  it('relights a scene exactly as if it had been built with that environment (same seed)', async () => {
    const options = { width: 8, height: 8, spp: 8, maxBounces: 4, seed: 13 };
    const sky = { kind: 'sky', sunElevationDeg: 30, sunAzimuthDeg: 20, turbidity: 4, groundAlbedo: 0.3, intensity: 1e-3 } as const;
    const grey50 = diffuse('grey', grey(0.5));
    const dark = await renderScene(sphereScene(grey50, { kind: 'none' }), options);
    for (const v of dark.radiance) expect(v).toBe(0);
    const relit = await renderScene(sphereScene(grey50, { kind: 'none' }), options, async (r) => {
      await r.setEnvironment(sky);
    });
    const built = await renderScene(sphereScene(grey50, sky), options);
    let worst = 0, total = 0;
    for (let i = 0; i < relit.radiance.length; i++) {
      worst = Math.max(worst, Math.abs(relit.radiance[i]! - built.radiance[i]!));
      total += built.radiance[i]!;
    }
    expect(total).toBeGreaterThan(0);
    expect(worst).toBeLessThanOrEqual(1e-6 * (total / relit.radiance.length));
  });
});
