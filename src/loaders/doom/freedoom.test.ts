/**
 * The real thing: every map, texture and flat of the Freedoom IWADs (Debian/Ubuntu's `freedoom`
 * package installs them). Skipped where they are absent.
 */
import { existsSync, readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
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
