/**
 * The hybrid recipe (renderer/recipes/hybrid.ts): its raster first hit is the ray tracer's first hit, and
 * its light adds up to the analytic answer of the white furnace, where
 *   L = Le + direct (a·Le) + a · GI(B bounces) = Σ_{k=0..B+1} a^k Le
 * in expectation at every pixel, whatever the GI buffer's scale and with or without its filter.
 */
import { beforeAll, describe, expect, it } from 'vitest';
import { builtinScene } from '../../src/loaders/builtin/index.ts';
import { furnaceRadiance } from '../../src/loaders/builtin/furnace.ts';
import { primaryRay } from '../../src/gpu/view.ts';
import { prepareScene } from '../../src/renderer/prepare.ts';
import { Renderer } from '../../src/renderer/renderer.ts';
import { DEFAULT_SETTINGS } from '../../src/renderer/settings.ts';
import { haltonJitter } from '../../src/renderer/recipes/hybrid.ts';
import { traceScene } from '../../src/bvh/levels.ts';
import { renderProgressive } from '../../src/renderer/progressive.ts';
import { IDENTITY } from '../../src/math/mat4.ts';
import { metallicRoughness, type Material, type Scene } from '../../src/scene/types.ts';
import { testGpu } from './gpu-context.ts';

const SIZE = 24;
let renderer: Renderer;

beforeAll(async () => {
  renderer = await Renderer.create(await testGpu());
  await renderer.compile({ recipe: 'hybrid' });
  await renderer.resize(SIZE, SIZE);
});

/** Mean radiance (per channel mean) over `frames` hybrid frames, every pixel. */
async function meanOfFrames(frames: number): Promise<{ mean: number; pixels: Float64Array }> {
  const pixels = new Float64Array(SIZE * SIZE);
  for (let f = 0; f < frames; f++) {
    renderer.renderFrame(1);
    const img = await renderer.readFrame();
    for (let i = 0; i < SIZE * SIZE; i++) pixels[i]! += (img.radiance[i * 3]! + img.radiance[i * 3 + 1]! + img.radiance[i * 3 + 2]!) / 3 / frames;
  }
  return { mean: pixels.reduce((a, b) => a + b, 0) / pixels.length, pixels };
}

describe('hybrid recipe: the white furnace', () => {
  for (const [giScale, giFilter, giBounces] of [[1, false, 2], [0.5, true, 2], [0.25, false, 1]] as const) {
    it(`converges to Σ a^k up to B + 1 bounces (GI scale ${giScale}, filter ${giFilter}, B = ${giBounces})`, async () => {
      await renderer.setScene(builtinScene('furnace'));
      renderer.setCamera(builtinScene('furnace').camera);
      renderer.updateSettings({ recipe: 'hybrid', maxBounces: 8, seed: 3, torch: { enabled: false }, hybrid: { ...DEFAULT_SETTINGS.hybrid, giScale, giFilter, giBounces, giSamples: 2, lightSamples: 2, taa: false } });
      renderer.resetHistory();
      const { mean, pixels } = await meanOfFrames(12);
      const expected = furnaceRadiance(giBounces + 1);
      expect(mean).toBeGreaterThan(expected * 0.98);
      expect(mean).toBeLessThan(expected * 1.02);
      // No part of the image strays either (no seam, no hole, no light lost at edges): 6 × 6 blocks.
      for (let by = 0; by < SIZE; by += 6) {
        for (let bx = 0; bx < SIZE; bx += 6) {
          let sum = 0;
          for (let y = by; y < by + 6; y++) for (let x = bx; x < bx + 6; x++) sum += pixels[y * SIZE + x]!;
          expect(Math.abs(sum / 36 - expected)).toBeLessThan(0.1 * expected);
        }
      }
    });
  }
});

describe('hybrid recipe: raster first hit', () => {
  it('sees at every pixel the surface a camera ray through the jittered point hits (the CPU oracle)', async () => {
    const scene = builtinScene('cornell');
    const prepared = prepareScene(scene);
    await renderer.setScene(prepared);
    renderer.setCamera(scene.camera);
    // Emission only: the image is the emitter where the first hit is the light, black elsewhere.
    renderer.updateSettings({ recipe: 'hybrid', maxBounces: 0, torch: { enabled: false }, hybrid: { ...DEFAULT_SETTINGS.hybrid, taa: false } });
    renderer.resetHistory();
    renderer.renderFrame(1);
    const img = await renderer.readFrame();
    const [jx, jy] = haltonJitter(0);
    let agree = 0;
    for (let y = 0; y < SIZE; y++) {
      for (let x = 0; x < SIZE; x++) {
        const ray = primaryRay(scene.camera, SIZE, SIZE, x + 0.5 + jx, y + 0.5 + jy);
        const hit = traceScene(prepared.scene, prepared.triangles, prepared.bvh, prepared.levels, { origin: ray.origin, direction: ray.direction });
        const material = hit ? prepared.triangles.materialIds[hit.triangle]! : -1;
        const emits = material >= 0 && scene.materials[material]!.emission.some((c) => c > 0);
        const seen = img.radiance[(y * SIZE + x) * 3]! > 0;
        if (emits === seen) agree++;
      }
    }
    expect(agree).toBe(SIZE * SIZE);
  });
});

/**
 * Three analytic spheres under a constant sky (radiance 1): rough plastic-metal, a smooth mirror
 * metal and clear glass. Each is convex, so what it shows is its own response to a uniform sky: the
 * path tracer's converged image is the reference, and the hybrid recipe (rasterised boxes whose
 * fragments intersect the spheres; direct light from the sky by NEE, reflections weighted by the
 * lobes' Fresnel albedo, the glass lobe through the reflection ray) must agree over each sphere.
 */
describe('hybrid recipe: reflections and analytic primitives', () => {
  const materials: Material[] = [
    metallicRoughness('rough', { baseColor: [0.8, 0.5, 0.3], metallic: 0.4, roughness: 0.45 }),
    metallicRoughness('mirror', { baseColor: [0.95, 0.85, 0.6], metallic: 1, roughness: 0 }),
    { kind: 'dielectric', name: 'glass', ior: 1.5, roughness: 0, tint: [1, 1, 1], attenuationDistance: Infinity, attenuationColor: [1, 1, 1], emission: [0, 0, 0] } as Material,
  ];
  const centres: [number, number, number][] = [[-2.2, 0, 0], [0, 0, 0], [2.2, 0, 0]];
  const scene: Scene = {
    name: 'three spheres',
    meshes: [{
      name: 'spheres', positions: new Float32Array(0), indices: new Uint32Array(0), materialIds: new Uint32Array(0),
      spheres: { centers: new Float32Array(centres.flat()), radii: new Float32Array([1, 1, 1]), materialIds: new Uint32Array([0, 1, 2]) },
    }],
    instances: [{ id: 0, mesh: 0, worldFromObject: IDENTITY }],
    materials,
    camera: { position: [0, 0, 9], forward: [0, 0, -1], up: [0, 1, 0], vfovDegrees: 22 },
    environment: { kind: 'constant', radiance: [1, 1, 1] },
  };
  const W = 48, H = 16;
  /** Mean of channel means over the pixels well inside sphere k (by its projected disc). */
  const sphereMean = (radiance: Float32Array, k: number) => {
    const t = Math.tan((scene.camera.vfovDegrees * Math.PI) / 360);
    let sum = 0, n = 0;
    for (let y = 0; y < H; y++) {
      for (let x = 0; x < W; x++) {
        const dx = ((2 * (x + 0.5)) / W - 1) * t * (W / H), dy = -((2 * (y + 0.5)) / H - 1) * t;
        // Where the pixel's ray crosses the plane z = 0 (9 units ahead), from the disc's centre.
        const px = dx * 9 - centres[k]![0], py = dy * 9;
        if (Math.hypot(px, py) > 0.75) continue;
        sum += (radiance[(y * W + x) * 3]! + radiance[(y * W + x) * 3 + 1]! + radiance[(y * W + x) * 3 + 2]!) / 3;
        n++;
      }
    }
    expect(n).toBeGreaterThan(8);
    return sum / n;
  };

  it('agrees with the converged path tracer over each sphere', async () => {
    await renderer.resize(W, H);
    await renderer.setScene(scene);
    renderer.setCamera(scene.camera);
    renderer.updateSettings({ recipe: 'path', maxBounces: 8, seed: 5, torch: { enabled: false } });
    await renderProgressive(renderer, { spp: 64 });
    const reference = (await renderer.readAccumulation()).radiance;
    renderer.updateSettings({ recipe: 'hybrid', hybrid: { ...DEFAULT_SETTINGS.hybrid, giScale: 1, lightSamples: 4, reflectionBounces: 6, taa: false } });
    renderer.resetHistory();
    const frames = 8;
    const sum = new Float32Array(W * H * 3);
    for (let f = 0; f < frames; f++) {
      renderer.renderFrame(1);
      const img = await renderer.readFrame();
      for (let i = 0; i < sum.length; i++) sum[i]! += img.radiance[i]! / frames;
    }
    for (let k = 0; k < 3; k++) {
      const expected = sphereMean(reference, k);
      const got = sphereMean(sum, k);
      expect(Math.abs(got - expected), `${materials[k]!.name}: hybrid ${got.toFixed(4)}, path tracer ${expected.toFixed(4)}`).toBeLessThan(0.03 * expected);
    }
    await renderer.resize(SIZE, SIZE);
  });
});
