/**
 * The real thing: Wolfenstein 3D v1.4 shareware (episode 1), read in place from
 * ../shared/assets/wolf3d-shareware (never copied into the repository). Skipped where absent.
 */
import { createHash } from 'node:crypto';
import { existsSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { WOLF3D_FORMAT } from './format.ts';
import { readWolfGame } from './game.ts';
import { readMapHead } from './maps.ts';
import { readVswap } from './vswap.ts';

// Beside the project (../shared from the main checkout), or where the shared assets live on this machine.
const CANDIDATES = ['../shared/assets/wolf3d-shareware', '/work/shared/assets/wolf3d-shareware'];
const DIR = CANDIDATES.find((d) => ['MAPHEAD.WL1', 'GAMEMAPS.WL1', 'VSWAP.WL1'].every((f) => existsSync(join(d, f))));
const present = DIR !== undefined;
if (!present) console.warn(`Wolfenstein 3D shareware files not found in ${CANDIDATES.join(' or ')}: skipping the tests on the real files`);

const file = (name: string) => ({ name, bytes: new Uint8Array(readFileSync(join(DIR!, name))) });

describe.skipIf(!present)('Wolfenstein 3D v1.4 shareware', () => {
  const files = present ? { maphead: file('MAPHEAD.WL1'), gamemaps: file('GAMEMAPS.WL1'), vswap: file('VSWAP.WL1') } : undefined!;

  it('are the files the published v1.4 tables describe', () => {
    const md5 = (b: Uint8Array) => createHash('md5').update(b).digest('hex');
    expect([files.maphead.bytes.length, files.gamemaps.bytes.length, files.vswap.bytes.length]).toEqual([402, 27425, 742912]);
    expect(md5(files.maphead.bytes)).toBe('7b6dd4e55c33c33a41d1600be5df3228');
    expect(md5(files.gamemaps.bytes)).toBe('30fecd7cce6bc70402651ec922d2da3d');
    expect(md5(files.vswap.bytes)).toBe('6efa079414b817c97db779cecfb081c9');
  });

  it('list ten 64 × 64 maps, E1L1 to E1L10, with their titles, and decode every one', () => {
    const head = readMapHead(files.maphead);
    expect(head.rlewTag).toBe(0xabcd);
    expect(head.offsets.filter((o) => o !== undefined)).toHaveLength(10);
    const game = readWolfGame(files);
    expect(game.extension).toBe('WL1');
    const titles = ['Wolf1 Map1', 'Wolf1 Map2', 'Wolf1 Map3', 'Wolf1 Map4', 'Wolf1 Map5', 'Wolf1 Map6', 'Wolf1 Map7', 'Wolf1 Map8', 'Wolf1 Boss', 'Wolf1 Secret'];
    expect(game.maps).toEqual(titles.map((title, index) => ({ index, id: `E1L${index + 1}`, title, width: 64, height: 64 })));
    for (const info of game.maps) {
      const map = game.map(info.id);
      // Every map: exactly one player start; plane 0 only walls (1–63), doors (90–101) and areas
      // (106–143); plane 2 unused.
      const starts = [...map.planes[1]].filter((c) => c >= 19 && c <= 22);
      expect(starts, info.id).toHaveLength(1);
      expect(map.planes[0].every((c) => (c >= 1 && c <= 63) || (c >= 90 && c <= 101) || (c >= 106 && c <= 143)), info.id).toBe(true);
      expect(map.planes[2].every((c) => c === 0)).toBe(true);
    }
  });

  it("E1L1: the player starts in the cell at (29, 57) facing east, the cell door beside it", () => {
    const map = readWolfGame(files).map('E1L1');
    const at = (plane: 0 | 1, x: number, y: number) => map.planes[plane][y * 64 + x];
    const start = map.planes[1].findIndex((c) => c >= 19 && c <= 22);
    expect([start % 64, Math.floor(start / 64), map.planes[1][start]]).toEqual([29, 57, 20]);
    // The floor of the cell (area 109), its door east of it (90: a door in a wall running north–south), blue stone (wall 9) round it.
    expect([at(0, 28, 57), at(0, 29, 57), at(0, 31, 57), at(0, 32, 57), at(0, 0, 0), at(0, 27, 57), at(0, 29, 55)]).toEqual([109, 109, 109, 90, 1, 9, 9]);
    expect(at(1, 32, 57)).toBe(0);
  });

  it('VSWAP: 663 chunks, walls up to 106, sprites up to 542; every wall opaque, sprites with holes', () => {
    const vswap = readVswap(files.vswap);
    expect([vswap.chunks.length, vswap.spriteStart, vswap.soundStart]).toEqual([663, 106, 542]);
    const { graphics } = readWolfGame(files);
    expect([graphics.wallCount, graphics.spriteCount]).toEqual([106, 436]);
    const opaque = (rgba: Uint8Array) => rgba.every((v, i) => i % 4 !== 3 || v === 255);
    for (let page = 0; page < graphics.wallCount; page++) expect(opaque(graphics.wall(page).rgba), `wall page ${page}`).toBe(true);
    // The shareware leaves out the registered episodes' sprites (chunk offset 0): transparent throughout.
    let drawnSprites = 0;
    for (let index = 0; index < graphics.spriteCount; index++) {
      const { rgba } = graphics.sprite(index);
      let drawn = 0;
      let other = 0;
      for (let i = 3; i < rgba.length; i += 4) {
        if (rgba[i] === 255) drawn++;
        else if (rgba[i] !== 0) other++;
      }
      expect([other, drawn < 64 * 64], `sprite ${index}`).toEqual([0, true]);
      if (drawn > 0) drawnSprites++;
    }
    expect(drawnSprites).toBe(436 - 210);
    // Wall page 0 (grey stone) is grey: equal channels.
    const stone = graphics.wall(0).rgba;
    expect(stone.every((v, i) => i % 4 === 3 || v === stone[i - (i % 4)])).toBe(true);
  });

  it('open as a set from any one of them and list the maps with their counts', async () => {
    const all = [files.maphead, files.gamemaps, files.vswap];
    const opened = await WOLF3D_FORMAT.open({ files: [files.vswap], resolve: (path) => Promise.resolve(all.find((f) => f.name === path)?.bytes) });
    const inventory = opened.inventory!();
    expect(inventory.lines[0]).toBe('Wolfenstein 3D (.WL1): 10 maps, 106 wall pages, 436 sprites');
    const maps = (inventory.json as { maps: unknown[] }).maps;
    expect(maps).toHaveLength(10);
    expect(maps[0]).toMatchObject({ id: 'E1L1', title: 'Wolf1 Map1', doors: 22, walls: 3057, statics: 121 });
  });
});
