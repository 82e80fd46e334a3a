import { describe, expect, it } from 'vitest';
import { LanternError } from '../../errors.ts';
import { readWolfGame } from './game.ts';
import { ceilingColourIndex, FLOOR_COLOUR_INDEX, gamePalette, vgaTo8Bit } from './palette.ts';
import { testGameFiles, testMap, testSpritePage, testWallPage } from './test-files.ts';

describe('the palette and the level colours', () => {
  it('holds 256 colours scaled from 6 bits, the EGA colours first', () => {
    const p = gamePalette();
    expect(p).toHaveLength(768);
    expect([vgaTo8Bit(0), vgaTo8Bit(21), vgaTo8Bit(42), vgaTo8Bit(63)]).toEqual([0, 85, 170, 255]);
    // EGA: black, blue, green, cyan, red, magenta, brown, light grey; bright white at 15.
    expect([...p.subarray(0, 24)]).toEqual([0, 0, 0, 0, 0, 170, 0, 170, 0, 0, 170, 170, 170, 0, 0, 170, 0, 170, 170, 85, 0, 170, 170, 170]);
    expect([...p.subarray(45, 48)]).toEqual([255, 255, 255]);
    // The floor's grey (28/63) and the usual ceiling's darker grey (14/63).
    expect([...p.subarray(3 * FLOOR_COLOUR_INDEX, 3 * FLOOR_COLOUR_INDEX + 3)]).toEqual([113, 113, 113]);
    expect([...p.subarray(3 * 0x1d, 3 * 0x1d + 3)]).toEqual([57, 57, 57]);
    // Each call is a fresh copy.
    p[0] = 9;
    expect(gamePalette()[0]).toBe(0);
  });

  it('gives each map its ceiling colour from the game table', () => {
    expect([0, 8, 9, 10, 14, 29, 59].map(ceilingColourIndex)).toEqual([0x1d, 0x1d, 0xbf, 0x4e, 0x8d, 0x98, 0xdd]);
    expect(ceilingColourIndex(60)).toBe(0x1d);
  });
});

describe('readWolfGame', () => {
  it('lists the maps, decodes them by id, number or index, and keeps what it decoded', () => {
    const game = readWolfGame(testGameFiles({ maps: 3 }));
    expect(game.extension).toBe('WL1');
    expect(game.maps.map((m) => [m.id, m.title])).toEqual([['E1L1', 'Test Map1'], ['E1L2', 'Test Map2'], ['E1L3', 'Test Map3']]);
    const map = game.map('e1l2');
    expect(map.planes).toEqual(testMap(1).planes);
    expect(game.map('E1L2')).toBe(map);
    expect(game.map(1)).toBe(map);
    expect(game.map('2')).toBe(map);
    expect(() => game.map('E1L4')).toThrow(/GAMEMAPS\.WL1 has no map 'E1L4'.*/);
    expect(() => game.map(7)).toThrow(/has no map number 8/);
    expect(game.graphics.wallCount).toBe(16);
    expect(game.graphics.spriteCount).toBe(50);
    const wall = game.graphics.wall(3);
    expect(game.graphics.wall(3)).toBe(wall);
    const palette = game.graphics.palette;
    const c = testWallPage(3)[10 * 64 + 20]!;
    expect([...wall.rgba.subarray(4 * (10 * 64 + 20), 4 * (10 * 64 + 20) + 4)]).toEqual([palette[3 * c], palette[3 * c + 1], palette[3 * c + 2], 255]);
    const sprite = game.graphics.sprite(4);
    const drawn = testSpritePage(4).reduce((n, v) => n + (v >= 0 ? 1 : 0), 0);
    expect(sprite.rgba.filter((_, i) => i % 4 === 3 && sprite.rgba[i] === 255)).toHaveLength(drawn);
  });

  it('refuses files of two games', () => {
    const files = testGameFiles();
    const registered = testGameFiles({ extension: 'WL6' });
    expect(() => readWolfGame({ ...files, vswap: registered.vswap })).toThrow(/MAPHEAD\.WL1 and VSWAP\.WL6 are not of one game/);
  });

  it('refuses a MAPHEAD with no maps', () => {
    const files = testGameFiles();
    const empty = new Uint8Array(402);
    empty.set(files.maphead.bytes.subarray(0, 2));
    expect(() => readWolfGame({ ...files, maphead: { name: 'MAPHEAD.WL1', bytes: empty } })).toThrow(LanternError);
  });
});
