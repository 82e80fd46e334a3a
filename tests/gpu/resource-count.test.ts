/**
 * The renderer gives back every GPU buffer and texture it creates: switching scenes and image sizes
 * keeps the live count steady, and destroy() returns it to where it was before the renderer existed.
 */
import { describe, expect, it } from 'vitest';
import { builtinScene } from '../../src/loaders/builtin/index.ts';
import { Renderer } from '../../src/renderer/renderer.ts';
import { testGpu } from './gpu-context.ts';

describe('GPU resource counting', () => {
  it('counts creation and destruction, once per resource', async () => {
    const { device, resources } = await testGpu();
    const before = resources.count;
    const buffer = device.createBuffer({ label: 'counted', size: 256, usage: GPUBufferUsage.STORAGE });
    const texture = device.createTexture({ label: 'counted', size: [4, 4], format: 'rgba8unorm', usage: GPUTextureUsage.TEXTURE_BINDING });
    expect(resources.count).toEqual({ buffers: before.buffers + 1, textures: before.textures + 1, bytes: before.bytes + 256 + 64 });
    buffer.destroy();
    buffer.destroy();
    texture.destroy();
    expect(resources.count).toEqual(before);
  });

  it('sees the renderer give back everything across scene switches, resizes and destroy', async () => {
    const gpu = await testGpu();
    const before = gpu.resources.count;
    const renderer = await Renderer.create(gpu);
    await renderer.resize(16, 16);
    await renderer.setScene(builtinScene('cornell'));
    renderer.accumulate(1);
    await renderer.readImage();
    await renderer.finish();
    const steady = gpu.resources.count;
    for (let i = 0; i < 4; i++) {
      await renderer.setScene(builtinScene(i % 2 ? 'cornell' : 'furnace'));
      await renderer.resize(16 + (i % 2) * 8, 16);
      renderer.accumulate(1);
      await renderer.readAccumulation();
    }
    await renderer.setScene(builtinScene('cornell'));
    await renderer.resize(16, 16);
    await renderer.finish();
    expect(gpu.resources.count).toEqual(steady);
    renderer.destroy();
    expect(gpu.resources.count).toEqual(before);
  });
});
