import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../expect-lantern-error.ts';
import { builtinScene } from '../loaders/builtin/index.ts';
import { prepareScene } from '../renderer/prepare.ts';
import { checkSceneFits, sceneNeeds, sceneOverLimit, type SceneLimits } from './scene-limits.ts';

// WebGPU's guaranteed minimums (the spec's defaults): what every adapter offers at least.
const DEFAULTS: SceneLimits = { maxBufferSize: 268_435_456, maxStorageBufferBindingSize: 134_217_728, maxUniformBufferBindingSize: 65_536, maxTextureDimension2D: 8192, maxTextureArrayLayers: 256 };

describe('a scene against the GPU limits', () => {
  const { packed } = prepareScene(builtinScene('cornell'));

  it('fits the guaranteed limits; each need is exactly what is uploaded', () => {
    expect(sceneOverLimit(packed, DEFAULTS)).toBeUndefined();
    const needs = sceneNeeds(packed);
    expect(needs.find((n) => n.what === 'the BVH nodes (bvh_nodes)' && n.limit === 'maxStorageBufferBindingSize')?.need).toBe(packed.bvh_nodes.byteLength);
    expect(needs.find((n) => n.limit === 'maxTextureArrayLayers')?.need).toBe(packed.atlas.pages.length);
  });

  it('is refused at the first limit it exceeds by one, with the need and the limit in the message', () => {
    // Every need, with its own limit set one below it: refused, and that need is the one named (or
    // an earlier one of the same limit that is as large).
    for (const need of sceneNeeds(packed)) {
      const limits = { ...DEFAULTS, [need.limit]: need.need - 1 };
      const over = sceneOverLimit(packed, limits);
      expect(over, `${need.what} / ${need.limit}`).toBeDefined();
      expect(over!.limit).toBe(need.limit);
      expect(over!.need).toBeGreaterThanOrEqual(need.need);
    }
    // The largest storage buffer, with the storage limit one byte short of it.
    const largest = sceneNeeds(packed).filter((n) => n.limit === 'maxStorageBufferBindingSize').reduce((a, b) => (b.need > a.need ? b : a));
    const words = largest.what.replace(/[()]/g, (c) => `\\${c}`);
    expectLanternError(
      () => checkSceneFits(packed, { ...DEFAULTS, maxStorageBufferBindingSize: largest.need - 1 }, 'cornell'),
      new RegExp(`^scene 'cornell' is too large for this GPU: ${words} needs ${largest.need.toLocaleString('en-US')} bytes, the GPU allows ${(largest.need - 1).toLocaleString('en-US')} bytes \\(maxStorageBufferBindingSize\\)$`),
    );
    expectLanternError(() => checkSceneFits(packed, { ...DEFAULTS, maxTextureArrayLayers: 0 }, 'cornell'), /colour texture atlas's pages needs 1 texture layers, the GPU allows 0 texture layers \(maxTextureArrayLayers\)/);
  });
});
