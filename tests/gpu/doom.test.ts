/**
 * A Doom map on the GPU: freedoom1 E1M1 from the player start at a small size is textured (many
 * distinct colours), not black, and the same image for the same seed. Skipped where Freedoom is not
 * installed (scripts/setup.sh installs it).
 */
import { existsSync, readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { loadDoomMap } from '../../src/loaders/doom/load.ts';
import { readWad, WadStack } from '../../src/loaders/doom/wad.ts';
import { prepareScene } from '../../src/renderer/prepare.ts';
import { Renderer } from '../../src/renderer/renderer.ts';
import { testGpu } from './gpu-context.ts';

const FREEDOOM1 = '/usr/share/games/doom/freedoom1.wad';

describe.skipIf(!existsSync(FREEDOOM1))('freedoom1 E1M1 on the GPU', () => {
  const load = () => {
    const stack = new WadStack([readWad(readFileSync(FREEDOOM1), 'freedoom1.wad')]);
    return prepareScene(loadDoomMap(stack, 'E1M1').scene);
  };

  async function render(seed: number): Promise<Uint8Array> {
    const renderer = await Renderer.create(await testGpu());
    await renderer.setScene(load());
    await renderer.resize(64, 40);
    renderer.updateSettings({ seed, maxBounces: 3 });
    renderer.accumulate(4);
    const image = await renderer.readImage();
    renderer.destroy();
    return image;
  }

  it('renders textured, lit and deterministic from the player start', async () => {
    const a = await render(3);
    const colours = new Set<number>();
    let sum = 0, tinted = 0;
    for (let i = 0; i < a.length; i += 4) {
      colours.add((a[i]! << 16) | (a[i + 1]! << 8) | a[i + 2]!);
      sum += a[i]! + a[i + 1]! + a[i + 2]!;
      if (Math.max(a[i]!, a[i + 1]!, a[i + 2]!) - Math.min(a[i]!, a[i + 1]!, a[i + 2]!) > 8) tinted++;
    }
    const pixels = a.length / 4;
    const meanLevel = sum / (pixels * 3);
    // Measured at 64×40, 4 spp: ~1050 distinct colours, mean level ~24 of 255.
    expect(colours.size).toBeGreaterThan(500);
    expect(meanLevel).toBeGreaterThan(15);
    // Textures, not grey shading: a good share of pixels have a hue.
    expect(tinted / pixels).toBeGreaterThan(0.1);
    expect(Buffer.compare(Buffer.from(await render(3)), Buffer.from(a))).toBe(0);
    expect(Buffer.compare(Buffer.from(await render(4)), Buffer.from(a))).not.toBe(0);
  });
});
