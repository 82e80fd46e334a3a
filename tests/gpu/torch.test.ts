/**
 * The torch's near field (shaders/scene/torch.wgsl): a sphere of radius r and uniform radiance
 * I/(π r²), sampled uniformly in the cone it subtends. A sphere wholly on one side of a plane lights
 * it exactly as a point of intensity I at its centre does (the irradiance of a uniform sphere is
 * π L sin²α cos θ = I cos θ/ρ²), so on a Lambertian floor at height h below the torch the image is
 * ρ·I·cos³θ/(π h²) for a torch of any radius below h: finite as the wall comes to the sphere (at
 * most ρ·I/(π r²)), and the inverse-square law far away. Cone sampling with the wrong pdf, or a
 * sample that missed the sphere, would break it for the large sphere first.
 */
import { describe, expect, it } from 'vitest';
import { diffuse } from '../../src/scene/types.ts';
import { floorScene, grey, lum, pixelFootprint, renderScene, se, squareMean, topDownCamera } from './scene-render.ts';

const RHO = 0.5;
const SIZE = 16;
const I = 3;

async function torchOverFloor(height: number, radius: number) {
  const scene = floorScene('floor under the torch', [diffuse('floor', grey(RHO))], { camera: topDownCamera([0, 0], height, height) });
  return renderScene(scene, { width: SIZE, height: SIZE, spp: 16, maxBounces: 1, seed: 3 }, (r) =>
    // A range far beyond the image, so the window is 1 to float precision.
    r.updateSettings({ torch: { enabled: true, intensity: I, color: [1, 1, 1], range: 1e6, radius } }),
  );
}

describe('the torch, a sphere light at the camera', () => {
  it.each([
    ['nearly touching the wall (r = 0.9 h)', 0.9],
    ['point-like (r = h / 100)', 0.01],
  ])('%s: the floor shows ρ·I·cos³θ/(π h²)', async (_, radiusOverHeight) => {
    const h = 2;
    const acc = await torchOverFloor(h, radiusOverHeight * h);
    const f = (x: number, z: number) => {
      const cos = h / Math.sqrt(x * x + z * z + h * h);
      return (RHO * I * cos ** 3) / (Math.PI * h * h);
    };
    for (let py = 0; py < SIZE; py++) {
      for (let px = 0; px < SIZE; px++) {
        const i = py * SIZE + px;
        const expected = squareMean(f, pixelFootprint([0, 0], h, SIZE, px, py));
        expect(Math.abs(lum(acc, i) - expected), `pixel ${i}: ${lum(acc, i)} against ${expected}`).toBeLessThanOrEqual(5 * se(acc, i) + 0.005 * expected + 1e-7);
      }
    }
    // Finite at the wall: never above what the sphere's surface itself could give, ρ·I/(π r²).
    const brightest = Math.max(...Array.from({ length: SIZE * SIZE }, (_, i) => lum(acc, i)));
    expect(brightest).toBeLessThan((RHO * I) / (Math.PI * (radiusOverHeight * h) ** 2));
  });
});
