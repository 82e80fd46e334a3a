import { it } from 'vitest';
import { loadDoomMap } from '../../src/loaders/doom/load.ts';
import { DoomGraphics } from '../../src/loaders/doom/textures.ts';
import { readWad, WadStack } from '../../src/loaders/doom/wad.ts';
import { bigSectorMap, danglingSegmentsMap, gridMap, manyLumpsWad, missingPatchesWad, noPlayerStartMap, randomLinesMap, wadOf } from './crafted.ts';

const cases: Array<[string, () => Uint8Array, 'map' | 'textures']> = (process.env.CASES ?? 'grid,patches,lumps,sector,noplayer,random,dangling').split(',').map((c) => ({
  grid: ['106,260-linedef grid (230² sectors)', () => wadOf([gridMap(230)]), 'map'],
  patches: ['8,000 missing patches behind 20,000 lumps', () => missingPatchesWad(8000, 20_000), 'textures'],
  lumps: ['200,000 lumps', () => manyLumpsWad(200_000), 'map'],
  sector: ['65,000-vertex sector', () => wadOf([bigSectorMap(65_000)]), 'map'],
  noplayer: ['140,000 vertices, no player start', () => wadOf([noPlayerStartMap(140_000)]), 'map'],
  random: ['100,000 random linedefs, 1,000 sectors', () => wadOf([randomLinesMap(100_000, 50_000, 1000)]), 'map'],
  dangling: ['20,000 dangling segments in one sector', () => wadOf([danglingSegmentsMap(20_000)]), 'map'],
} as Record<string, [string, () => Uint8Array, 'map' | 'textures']>)[c]!);

it('timing', () => {
  for (const [label, make, kind] of cases) {
    const bytes = make();
    const rss0 = process.memoryUsage().rss;
    const t0 = performance.now();
    let result = 'ok';
    try {
      const stack = new WadStack([readWad(bytes, 'x.wad')]);
      if (kind === 'map') {
        const l = loadDoomMap(stack, 'MAP01', { onWarning: () => {} });
        result = `ok, ${l.failures.length} sectors failed`;
      } else {
        const g = new DoomGraphics(stack, { onWarning: () => {} });
        for (const n of g.textureNames()) g.texture(n);
      }
    } catch (e) {
      result = `${(e as Error).name}: ${(e as Error).message.slice(0, 80)}`;
    }
    const ms = performance.now() - t0;
    console.log(`TIMING | ${label} | ${(ms / 1000).toFixed(2)} s | rss +${((process.memoryUsage().rss - rss0) / 2 ** 20).toFixed(0)} MB | ${result}`);
  }
}, 900_000);
