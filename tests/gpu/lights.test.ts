/**
 * Punctual lights (KHR_lights_punctual) through the integrator against closed forms, on a large
 * Lambertian floor of albedo ρ seen from straight above, one bounce (direct light only), no environment:
 * - point light of intensity I at height h: L(x) = ρ·I·cos³θ/(π h²), cos θ = h/√(h² + x²);
 * - spot light: the same inside the inner cone, exactly 0 outside the outer cone;
 * - directional light of irradiance E at angle θ from the vertical: ρ·E·cos θ/π everywhere;
 * - emissive triangles and a punctual light together (both halves of the one light table): the
 *   image lit by both is the sum of the images lit by each.
 * Each pixel's expected value is the closed form averaged over the pixel's square footprint (the
 * path tracer jitters uniformly inside the pixel); its only noise is that jitter.
 */
import { describe, expect, it } from 'vitest';
import { translation } from '../../src/math/mat4.ts';
import type { Accumulation } from '../../src/renderer/renderer.ts';
import type { Material, Mesh, PunctualLight } from '../../src/scene/types.ts';
import { diffuse } from '../../src/scene/types.ts';
import { floorScene, grey, lum, pixelFootprint, regionStats, renderScene, se, squareMean, topDownCamera } from './scene-render.ts';

const RHO = 0.5;
const SIZE = 16;
const H = 1;
/** The camera sees the floor square [−1, 1]² from height 3 (above the lights, which are not geometry). */
const HALF = 1;
const CAMERA = topDownCamera([0, 0], 3, HALF);
const FLOOR = diffuse('floor', grey(RHO));

function pointRadiance(intensity: number, h: number): (x: number, z: number) => number {
  return (x, z) => {
    const r2 = x * x + z * z + h * h;
    const cos = h / Math.sqrt(r2);
    return (RHO * intensity * cos * cos * cos) / (Math.PI * h * h);
  };
}

function renderLights(lights: PunctualLight[], spp = 32, lightSampling: 'mis' | 'bsdf' = 'mis'): Promise<Accumulation> {
  return renderScene(floorScene('floor under punctual lights', [FLOOR], { lights, camera: CAMERA }), { width: SIZE, height: SIZE, spp, maxBounces: 1, seed: 2, lightSampling });
}

/** |measured − expected| within 5 standard errors plus 0.5 % (float error; the jitter's noise can be ~0). */
function expectPixel(acc: Accumulation, i: number, expected: number, what: string): void {
  expect(Math.abs(lum(acc, i) - expected), `${what}: pixel ${i} = ${lum(acc, i)}, expected ${expected}`).toBeLessThanOrEqual(5 * se(acc, i) + 0.005 * expected + 1e-7);
}

describe('punctual lights on a diffuse floor (1 bounce)', () => {
  it('a point light: ρ·I·cos³θ/(π h²)', async () => {
    const I = 4;
    const acc = await renderLights([{ kind: 'point', name: 'point', position: [0, H, 0], color: [1, 1, 1], intensity: I, range: Infinity }]);
    const f = pointRadiance(I, H);
    for (let py = 0; py < SIZE; py++) for (let px = 0; px < SIZE; px++) expectPixel(acc, py * SIZE + px, squareMean(f, pixelFootprint([0, 0], HALF, SIZE, px, py)), 'point');
    // Power: under the light ρI/(πh²), at the image corner (x = z = 1) cos³θ = 3^(−3/2) of that.
    const centre = lum(acc, (SIZE / 2) * SIZE + SIZE / 2), corner = lum(acc, 0);
    expect(centre / corner).toBeGreaterThan(4);
    expect(centre).toBeCloseTo((RHO * I) / Math.PI, 1);
  });

  it('BSDF-only sampling still samples a point light (no BSDF ray can find it)', async () => {
    const I = 4;
    const acc = await renderLights([{ kind: 'point', name: 'point', position: [0, H, 0], color: [1, 1, 1], intensity: I, range: Infinity }], 32, 'bsdf');
    const f = pointRadiance(I, H);
    for (let py = 0; py < SIZE; py++) for (let px = 0; px < SIZE; px++) expectPixel(acc, py * SIZE + px, squareMean(f, pixelFootprint([0, 0], HALF, SIZE, px, py)), 'point, bsdf');
  });

  it('a spot light: a point light inside the inner cone, 0 outside the outer cone', async () => {
    const I = 4, inner = (20 * Math.PI) / 180, outer = (30 * Math.PI) / 180;
    const acc = await renderLights([{ kind: 'spot', name: 'spot', position: [0, H, 0], direction: [0, -1, 0], color: [1, 1, 1], intensity: I, range: Infinity, innerConeAngle: inner, outerConeAngle: outer }]);
    const f = pointRadiance(I, H);
    let inside = 0, outside = 0;
    for (let py = 0; py < SIZE; py++) {
      for (let px = 0; px < SIZE; px++) {
        const [x0, z0, x1, z1] = pixelFootprint([0, 0], HALF, SIZE, px, py);
        const near = Math.hypot(Math.max(0, x0, -x1), Math.max(0, z0, -z1)); // nearest footprint point to the axis
        const far = Math.hypot(Math.max(Math.abs(x0), Math.abs(x1)), Math.max(Math.abs(z0), Math.abs(z1)));
        const i = py * SIZE + px;
        if (far < H * Math.tan(inner)) {
          expectPixel(acc, i, squareMean(f, [x0, z0, x1, z1]), 'inside the inner cone');
          inside++;
        } else if (near > H * Math.tan(outer)) {
          expect(lum(acc, i), `outside the outer cone: pixel ${i}`).toBe(0);
          outside++;
        }
      }
    }
    expect(inside).toBeGreaterThanOrEqual(4);
    expect(outside).toBeGreaterThan(100);
  });

  it('a directional light: ρ·E·cos θ/π everywhere', async () => {
    const E = 3, theta = (50 * Math.PI) / 180;
    const acc = await renderLights([{ kind: 'directional', name: 'sun', direction: [Math.sin(theta), -Math.cos(theta), 0], color: [1, 1, 1], irradiance: E }], 4);
    const expected = (RHO * E * Math.cos(theta)) / Math.PI;
    for (let i = 0; i < SIZE * SIZE; i++) expect(lum(acc, i)).toBeCloseTo(expected, 5);
  });

  it('a coloured point light tints by channel', async () => {
    const acc = await renderLights([{ kind: 'point', name: 'red', position: [0, H, 0], color: [1, 0.5, 0], intensity: 2, range: Infinity }], 4);
    const i = (SIZE / 2) * SIZE + SIZE / 2;
    expect(acc.radiance[i * 3 + 1]! / acc.radiance[i * 3]!).toBeCloseTo(0.5, 4);
    expect(acc.radiance[i * 3 + 2]).toBe(0);
  });
});

describe('emissive triangles and punctual lights share the light table', () => {
  /** A 0.6 × 0.6 quad at height 0.8 over (−0.5, 0), emitting downward: (v1 − v0) × (v2 − v0) = −y. */
  const quad: Mesh = {
    name: 'panel',
    positions: new Float32Array([-0.8, 0, -0.3, -0.2, 0, -0.3, -0.2, 0, 0.3, -0.8, 0, 0.3]),
    indices: new Uint32Array([0, 1, 2, 0, 2, 3]),
    materialIds: new Uint32Array([1, 1]),
  };
  const panel = (e: number): Material => ({ kind: 'emissive', name: 'panel', emission: grey(e) });
  const point: PunctualLight = { kind: 'point', name: 'point', position: [0.5, 0.7, 0.2], color: [1, 1, 1], intensity: 0.8, range: Infinity };

  function render(panelEmission: number, lights: PunctualLight[], seed: number): Promise<Accumulation> {
    // The panel is there in every variant (black when off), so that it shadows the same.
    const scene = floorScene('panel and point light', [FLOOR, panel(panelEmission)], { lights, camera: CAMERA }, [quad]);
    const withPanel = { ...scene, instances: [...scene.instances, { id: 1, mesh: 1, worldFromObject: translation([0, 0.8, 0]) }] };
    return renderScene(withPanel, { width: SIZE, height: SIZE, spp: 64, maxBounces: 1, seed });
  }

  it('each alone sums to both together, per 4×4 block within noise', async () => {
    const panelOnly = await render(4, [], 21);
    const pointOnly = await render(0, [point], 22);
    const both = await render(4, [point], 23);
    const all = [...Array(SIZE * SIZE).keys()];
    const a = regionStats(panelOnly, all), b = regionStats(pointOnly, all), c = regionStats(both, all);
    console.log(`image means: panel ${a.mean.toFixed(4)} ± ${a.se.toFixed(4)}, point ${b.mean.toFixed(4)} ± ${b.se.toFixed(4)}, both ${c.mean.toFixed(4)} ± ${c.se.toFixed(4)}`);
    // Power: both halves carry a good share, so a light sampled with the wrong probability is seen.
    expect(a.mean / c.mean).toBeGreaterThan(0.25);
    expect(b.mean / c.mean).toBeGreaterThan(0.25);
    expect(Math.abs(a.mean + b.mean - c.mean)).toBeLessThan(4 * Math.hypot(a.se, b.se, c.se) + 1e-4);
    expect(Math.abs(a.mean + b.mean - c.mean) / c.mean).toBeLessThan(0.02);
    // 16 blocks of 4×4 pixels: a 4.5σ bound keeps a false alarm below 1e-4.
    for (let by = 0; by < SIZE; by += 4) {
      for (let bx = 0; bx < SIZE; bx += 4) {
        const px: number[] = [];
        for (let y = by; y < by + 4; y++) for (let x = bx; x < bx + 4; x++) px.push(y * SIZE + x);
        const ra = regionStats(panelOnly, px), rb = regionStats(pointOnly, px), rc = regionStats(both, px);
        const sigma = Math.hypot(ra.se, rb.se, rc.se);
        expect(Math.abs(ra.mean + rb.mean - rc.mean), `block (${bx}, ${by}): ${ra.mean} + ${rb.mean} vs ${rc.mean} ± ${sigma}`).toBeLessThan(4.5 * sigma + 1e-3 * rc.mean + 1e-6);
      }
    }
  });

  it('the point light alone, with the panel in the scene but dark, still follows ρ·I·cos³θ/(π h²) where the panel does not hide the floor', async () => {
    const acc = await render(0, [point], 24);
    const f = (x: number, z: number) => pointRadiance(point.intensity, point.position[1])(x - point.position[0], z - point.position[2]);
    // The panel (above the light, so it casts no shadow from it) hides the floor at x ≤ −0.2 from the
    // camera; the right half of the image sees bare floor.
    let checked = 0;
    for (let py = 0; py < SIZE; py++) {
      for (let px = SIZE / 2; px < SIZE; px++) {
        const i = py * SIZE + px;
        expectPixel(acc, i, squareMean(f, pixelFootprint([0, 0], HALF, SIZE, px, py)), 'point light beside a dark panel');
        checked++;
      }
    }
    expect(checked).toBe(SIZE * SIZE / 2);
  });
});

describe('two-sided emission (MaterialBase.twoSidedEmission)', () => {
  /** The panel of the block above, turned over: its front faces up, away from the floor. */
  const panelUp: Mesh = {
    name: 'panel facing up',
    positions: new Float32Array([-0.8, 0, -0.3, -0.2, 0, -0.3, -0.2, 0, 0.3, -0.8, 0, 0.3]),
    indices: new Uint32Array([0, 2, 1, 0, 3, 2]),
    materialIds: new Uint32Array([1, 1]),
  };
  const panelDown: Mesh = { ...panelUp, name: 'panel facing down', indices: new Uint32Array([0, 1, 2, 0, 2, 3]) };

  function render(mesh: Mesh, twoSided: boolean, lightSampling: 'mis' | 'bsdf', seed: number): Promise<Accumulation> {
    const panel: Material = { kind: 'emissive', name: 'panel', emission: grey(3), twoSidedEmission: twoSided };
    const scene = floorScene('one panel', [FLOOR, panel], { camera: CAMERA }, [mesh]);
    const placed = { ...scene, instances: [...scene.instances, { id: 1, mesh: 1, worldFromObject: translation([0, 0.8, 0]) }] };
    return renderScene(placed, { width: SIZE, height: SIZE, spp: 64, maxBounces: 1, seed, lightSampling });
  }

  it('lights the floor from its back face as a one-sided panel does from its front, by light and by BSDF sampling; a one-sided back face lights nothing', async () => {
    const right = [...Array(SIZE * SIZE).keys()].filter((i) => i % SIZE >= SIZE / 2);
    const reference = regionStats(await render(panelDown, false, 'mis', 31), right);
    const backMis = regionStats(await render(panelUp, true, 'mis', 32), right);
    const backBsdf = regionStats(await render(panelUp, true, 'bsdf', 33), right);
    const oneSidedBack = regionStats(await render(panelUp, false, 'mis', 34), right);
    expect(reference.mean).toBeGreaterThan(0.02);
    expect(Math.abs(backMis.mean - reference.mean)).toBeLessThan(4 * Math.hypot(backMis.se, reference.se) + 1e-4);
    expect(Math.abs(backBsdf.mean - reference.mean)).toBeLessThan(4 * Math.hypot(backBsdf.se, reference.se) + 1e-4);
    expect(oneSidedBack.mean).toBe(0);
  });
});
