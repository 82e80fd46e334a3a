/**
 * The real thing: every map, texture and flat of the Freedoom IWADs (Debian/Ubuntu's `freedoom`
 * package installs them). Skipped where they are absent.
 */
import { existsSync, readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { loadDoomMap } from './load.ts';
import { readMap } from './map-lumps.ts';
import { DoomGraphics } from './textures.ts';
import { readWad, WadStack } from './wad.ts';

const DIR = '/usr/share/games/doom';
const IWADS = [
  { file: 'freedoom1.wad', maps: 36, first: 'E1M1', last: 'E4M9' },
  { file: 'freedoom2.wad', maps: 32, first: 'MAP01', last: 'MAP32' },
];

describe.each(IWADS)('$file', ({ file, maps, first, last }) => {
  const path = `${DIR}/${file}`;

  it.skipIf(!existsSync(path))('reads every map and composes every texture and flat', () => {
    const bytes = readFileSync(path);
    const warnings: string[] = [];
    const onWarning = (w: string) => warnings.push(w);
    const t0 = performance.now();
    const stack = new WadStack([readWad(bytes, file)]);
    const infos = stack.maps();
    let lines = 0;
    let sectors = 0;
    for (const info of infos) {
      const map = readMap(stack, info.name, { onWarning });
      lines += map.linedefs.length;
      sectors += map.sectors.length;
    }
    const t1 = performance.now();
    const g = new DoomGraphics(stack, { onWarning });
    let pixels = 0;
    for (const name of g.textureNames()) pixels += g.texture(name)!.rgba.length / 4;
    let flats = 0;
    for (const name of g.flatNames()) if (g.flat(name)) flats++;
    const t2 = performance.now();

    console.log(
      `${file}: ${infos.length} maps (${lines} linedefs, ${sectors} sectors) read in ${(t1 - t0).toFixed(0)} ms; ` +
        `${g.textureNames().length} textures (${(pixels / 1e6).toFixed(1)} Mpixel) and ${flats}/${g.flatNames().length} flats composed in ${(t2 - t1).toFixed(0)} ms` +
        (warnings.length ? `; ${warnings.length} warning(s):\n  ${warnings.join('\n  ')}` : '; no warnings'),
    );
    expect(infos).toHaveLength(maps);
    expect(infos.every((m) => m.format === 'doom' && m.file === file)).toBe(true);
    expect(infos[0]!.name).toBe(first);
    expect(infos.at(-1)!.name).toBe(last);
    expect(flats).toBe(g.flatNames().length);
    expect(g.sky(first)).toBeDefined();
    expect(g.flat('F_SKY1')).toBeDefined();
  });
});

/**
 * Things drawn and light-giving things per map, counted by hand from the THINGS lumps (each thing's
 * flags against the skill bits and the multiplayer bit, player starts left out): Freedoom's E1M1 has
 * 238 things, 31 of them multiplayer-only, and 7 floor lamps (2028) at every skill; MAP01 has 162,
 * 30 multiplayer-only, and 5 floor lamps.
 */
describe.each([
  { file: 'freedoom1.wad', map: 'E1M1', drawn: { 1: 171, 3: 169, 5: 185 }, emitting: 7 },
  { file: 'freedoom2.wad', map: 'MAP01', drawn: { 1: 95, 3: 101, 5: 114 }, emitting: 5 },
])('$file $map things', ({ file, map, drawn, emitting }) => {
  const path = `${DIR}/${file}`;

  it.skipIf(!existsSync(path))('draws every thing of the skill as a sprite, the lamps emitting', () => {
    const stack = new WadStack([readWad(readFileSync(path), file)]);
    const warnings: string[] = [];
    for (const [skill, n] of Object.entries(drawn)) {
      const loaded = loadDoomMap(stack, map, { things: { skill: Number(skill) }, onWarning: (w) => warnings.push(w) });
      expect(loaded.stats.sprites).toBe(n);
      expect(loaded.stats.emittingSprites).toBe(emitting);
      const sprites = new Set(loaded.scene.dynamics!.billboards!.map((b) => b.instance));
      expect(loaded.scene.instances.filter((i) => sprites.has(i.id) && i.moves)).toHaveLength(n);
      // Every floor lamp's material emits on both faces.
      const lamps = loaded.scene.instances.filter((i) => i.name === 'Floor lamp');
      expect(lamps).toHaveLength(emitting);
      for (const lamp of lamps) expect(loaded.scene.materials[lamp.material!]!.twoSidedEmission).toBe(true);
    }
    // Every thing type is known and every sprite frame is complete: nothing is reported.
    expect(warnings.filter((w) => /thing|sprite/.test(w))).toEqual([]);
  });
});
