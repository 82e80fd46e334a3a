/**
 * A glTF model end to end: load Duck.glb with the glTF loader (which frames a camera and, the model
 * having no light, adds the default sky and says so as information), prepare, render 32×32 at 4 spp.
 */
import { existsSync, readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { loadGltf } from '../../src/loaders/gltf/index.ts';
import { renderScene } from './scene-render.ts';

const DUCK = '/work/shared/assets/gltf/Duck/glTF-Binary/Duck.glb';
const present = existsSync(DUCK);
if (!present) console.warn(`glTF end-to-end test skipped: ${DUCK} is absent`);

describe.skipIf(!present)('glTF end to end', () => {
  it('Duck.glb: finite, not black, the duck yellow against the sky, and the default-sky note', async () => {
    const scene = await loadGltf({ name: 'Duck.glb', bytes: readFileSync(DUCK) }, async () => undefined);
    expect(scene.environment?.kind).toBe('sky');
    expect(scene.lightingNote).toMatch(/default sky/);
    const acc = await renderScene(scene, { width: 32, height: 32, spp: 4, maxBounces: 2, seed: 1 });
    const n = acc.width * acc.height;
    let sum = 0, yellow = 0;
    for (let i = 0; i < n; i++) {
      const [r, g, b] = [acc.radiance[i * 3]!, acc.radiance[i * 3 + 1]!, acc.radiance[i * 3 + 2]!];
      expect(Number.isFinite(r) && Number.isFinite(g) && Number.isFinite(b), `pixel ${i}`).toBe(true);
      expect(Math.min(r, g, b)).toBeGreaterThanOrEqual(0);
      sum += r + g + b;
      // The duck's base colour texture is yellow (R, G ≫ B); the clear sky is bluish (B > R).
      if (r > 2 * b && g > 1.5 * b) yellow++;
    }
    console.log(`Duck: mean radiance ${(sum / (3 * n)).toFixed(3)}, yellow pixels ${yellow} of ${n}`);
    expect(sum / (3 * n)).toBeGreaterThan(0);
    // The framed duck covers a good part of the image.
    expect(yellow).toBeGreaterThan(n / 20);
  });
});
