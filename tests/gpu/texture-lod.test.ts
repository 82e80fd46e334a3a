/**
 * Texture level of detail by ray cones: a fine checker seen from afar. Every pixel covers many
 * texels, so with mip levels each pixel shows their average (linear 0.5) and the image is flat;
 * sampled without mips (nearest texels) every pixel shows one black or white texel and the image
 * sparkles. One sample per pixel, emission only: the pixel is exactly the texture lookup.
 */
import { describe, expect, it } from 'vitest';
import { IDENTITY } from '../../src/math/mat4.ts';
import { Renderer } from '../../src/renderer/renderer.ts';
import { floorSquare } from '../../src/scene/shapes.ts';
import { metallicRoughness, type Scene, type Texture } from '../../src/scene/types.ts';
import { testGpu } from './gpu-context.ts';

function checker(side: number, filter: 'nearest' | 'bilinear'): Texture {
  const rgba = new Uint8Array(side * side * 4);
  for (let y = 0; y < side; y++) for (let x = 0; x < side; x++) rgba.set((x + y) % 2 === 0 ? [255, 255, 255, 255] : [0, 0, 0, 255], (y * side + x) * 4);
  return { name: 'checker', width: side, height: side, rgba, filter };
}

function farCheckerScene(filter: 'nearest' | 'bilinear'): Scene {
  // A 20 × 20 floor with the 256² checker repeated 8 times: 2048 texels across, seen from 40 units.
  return {
    name: 'far checker',
    meshes: [floorSquare('floor', 10, 8)],
    instances: [{ id: 0, mesh: 0, worldFromObject: IDENTITY }],
    materials: [metallicRoughness('glowing checker', { baseColor: [0, 0, 0], metallic: 0, emission: [1, 1, 1], emissionTexture: { texture: 0 } })],
    textures: [checker(256, filter)],
    camera: { position: [0, 40, 0.01], forward: [0, -1, 0], up: [0, 0, -1], vfovDegrees: 20 },
  };
}

async function pixelStats(filter: 'nearest' | 'bilinear'): Promise<{ mean: number; sd: number }> {
  const renderer = await Renderer.create(await testGpu());
  await renderer.setScene(farCheckerScene(filter));
  await renderer.resize(24, 24);
  renderer.updateSettings({ maxBounces: 0, seed: 3 });
  renderer.accumulate(1);
  const acc = await renderer.readAccumulation();
  renderer.destroy();
  const values = Array.from({ length: 24 * 24 }, (_, i) => acc.radiance[i * 3 + 1]!);
  const mean = values.reduce((a, b) => a + b, 0) / values.length;
  const sd = Math.sqrt(values.reduce((a, b) => a + (b - mean) ** 2, 0) / values.length);
  return { mean, sd };
}

describe('texture level of detail (ray cones)', () => {
  it('a distant fine checker shows its mean, not single texels', async () => {
    const mipped = await pixelStats('bilinear');
    const nearest = await pixelStats('nearest');
    // The checker's mean in linear light is 0.5 (black and white texels in equal numbers).
    expect(Math.abs(mipped.mean - 0.5)).toBeLessThan(0.03);
    expect(mipped.sd).toBeLessThan(0.05);
    // Without mips the same pixels are each one texel: black or white.
    expect(nearest.sd).toBeGreaterThan(0.3);
  });
});
