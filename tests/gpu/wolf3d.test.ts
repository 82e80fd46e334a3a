/**
 * E1L1 of the Wolfenstein 3D shareware (read in place; skipped where absent) on the GPU, tiny: from
 * the player's start the image is neither black nor saturated; at t = 2 s, beside the cell door,
 * the World has slid its panel open (Renderer.applySceneUpdate) and the view through it is lit too.
 */
import { existsSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { readWolfGame } from '../../src/loaders/wolf3d/game.ts';
import { WOLF_TILE, wolfMapToScene } from '../../src/loaders/wolf3d/to-scene.ts';
import { renderProgressive } from '../../src/renderer/progressive.ts';
import { Renderer } from '../../src/renderer/renderer.ts';
import { sceneUpdateAt } from '../../src/world/world.ts';
import { testGpu } from './gpu-context.ts';

const CANDIDATES = ['../shared/assets/wolf3d-shareware', '/work/shared/assets/wolf3d-shareware'];
const DIR = CANDIDATES.find((d) => ['MAPHEAD.WL1', 'GAMEMAPS.WL1', 'VSWAP.WL1'].every((f) => existsSync(join(d, f))));
if (!DIR) console.warn(`Wolfenstein 3D shareware files not found in ${CANDIDATES.join(' or ')}: skipping the E1L1 render`);
const file = (name: string) => ({ name, bytes: new Uint8Array(readFileSync(join(DIR!, name))) });

const W = 48, H = 32;

describe.skipIf(!DIR)('E1L1 on the GPU', () => {
  it('renders the start neither black nor saturated, and the cell door slid open at t = 2 s', async () => {
    const game = readWolfGame({ maphead: file('MAPHEAD.WL1'), gamemaps: file('GAMEMAPS.WL1'), vswap: file('VSWAP.WL1') });
    const scene = wolfMapToScene(game, game.map('E1L1'));
    const renderer = await Renderer.create(await testGpu());
    try {
      await renderer.setScene(scene);
      await renderer.resize(W, H);
      renderer.updateSettings({ maxBounces: 2, seed: 7 });
      await renderProgressive(renderer, { spp: 4 });
      const image = await renderer.readImage();
      let sum = 0, black = 0, white = 0;
      for (let i = 0; i < W * H; i++) {
        const v = (image[4 * i]! + image[4 * i + 1]! + image[4 * i + 2]!) / 3;
        sum += v;
        if (v < 2) black++;
        if (v > 253) white++;
      }
      const mean = sum / (W * H);
      console.log(`E1L1 ${W}×${H}, 4 spp: mean display value ${mean.toFixed(1)}, ${black} black and ${white} white pixels`);
      expect(mean).toBeGreaterThan(15);
      expect(mean).toBeLessThan(200);
      expect(black).toBeLessThan(0.2 * W * H);
      expect(white).toBeLessThan(0.05 * W * H);

      // Walk the camera to the cell door (32, 57): at t = 2 s it is open, the panel has slid south.
      const view = { position: [31.4 * WOLF_TILE, 32, 57.5 * WOLF_TILE] as [number, number, number], forward: [1, 0, 0] as [number, number, number] };
      const update = sceneUpdateAt(scene, 2, view);
      const door = scene.dynamics!.slidingDoors!.doors.find((d) => d.cell[0] === 32 && d.cell[1] === 57)!;
      expect(update.instances.get(door.instance)!.worldFromObject![14]).toBeCloseTo(58 * WOLF_TILE, 3);
      renderer.applySceneUpdate(update);
      renderer.setCamera({ ...scene.camera, position: view.position, forward: view.forward });
      await renderProgressive(renderer, { spp: 4 });
      const open = await renderer.readImage();
      let openSum = 0;
      for (let i = 0; i < W * H; i++) openSum += (open[4 * i]! + open[4 * i + 1]! + open[4 * i + 2]!) / 3;
      console.log(`at the open door: mean display value ${(openSum / (W * H)).toFixed(1)}`);
      expect(openSum / (W * H)).toBeGreaterThan(15);
    } finally {
      renderer.destroy();
    }
  }, 600_000);
});
