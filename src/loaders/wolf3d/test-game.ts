/**
 * In-memory Wolfenstein 3D games for tests: maps drawn as text, wall pages and sprites of plain
 * colours that say which page they are. Not part of the loader.
 *
 * Map characters (plane 0 / plane 1):
 *   '#' wall 1, '1'–'9' walls 1–9, '.' open floor (area 107), ' ' open floor too,
 *   '|' vertical door (90), '-' horizontal door (91), 'G' gold-key vertical door (92), 'E' elevator horizontal door (101),
 *   'P' push wall (wall 3 under object 98),
 *   '^' '>' 'v' '<' the player's start facing north, east, south, west,
 *   'c' chandelier (27), 'l' ceiling light (37), 'L' floor lamp (26), 'b' barrel (58, blocks), 'o' puddle (23),
 *   'g' a guard standing, facing east (108), 'n' one facing north (109), 'h' a guard from skill 3 (144),
 *   'H' one from skill 4 (180), 'd' a dog on patrol (138), 'O' an officer (116: not drawn).
 */
import type { WolfGame, WolfGraphics, WolfImage, WolfMap } from './types.ts';

/** The shareware VSWAP's count: 98 wall pages, then the eight door pages from DOORWALL = 98. */
export const TEST_WALL_PAGES = 106;
export const TEST_SPRITES = 200;

const WALLS: Record<string, number> = { '#': 1, P: 3, '|': 90, '-': 91, G: 92, E: 101 };
const OBJECTS: Record<string, number> = { '^': 19, '>': 20, v: 21, '<': 22, c: 27, l: 37, L: 26, b: 58, o: 23, g: 108, n: 109, h: 144, H: 180, d: 138, O: 116, P: 98 };

export function testMap(rows: readonly string[], index = 0): WolfMap {
  const height = rows.length;
  const width = Math.max(...rows.map((r) => r.length));
  const walls = new Uint16Array(width * height).fill(107);
  const objects = new Uint16Array(width * height);
  rows.forEach((row, y) => {
    [...row].forEach((ch, x) => {
      const i = y * width + x;
      if (/[1-9]/.test(ch)) walls[i] = Number(ch);
      else if (WALLS[ch] !== undefined) walls[i] = WALLS[ch]!;
      if (OBJECTS[ch] !== undefined) objects[i] = OBJECTS[ch]!;
    });
  });
  return { index, id: `E${Math.floor(index / 10) + 1}L${(index % 10) + 1}`, title: 'Test map', width, height, planes: [walls, objects, new Uint16Array(width * height)] };
}

/** A 64 × 64 image of one colour (alpha 255), or for sprites opaque in its lower half only. */
function plain(r: number, g: number, b: number, lowerHalfOnly = false): WolfImage {
  const rgba = new Uint8Array(64 * 64 * 4);
  for (let i = 0; i < 64 * 64; i++) {
    if (lowerHalfOnly && i < 32 * 64) continue;
    rgba.set([r, g, b, 255], i * 4);
  }
  return { width: 64, height: 64, rgba };
}

/** Palette entry i is grey (i, i, i). */
export const TEST_PALETTE = new Uint8Array(768).map((_, k) => Math.floor(k / 3));

export function testGraphics(): WolfGraphics {
  return {
    palette: TEST_PALETTE,
    wallCount: TEST_WALL_PAGES,
    // Page p is red p, green 100: a test can tell pages apart by colour.
    wall: (page) => {
      if (!(page >= 0 && page < TEST_WALL_PAGES)) throw new RangeError(`no wall page ${page}`);
      return plain(page, 100, 0);
    },
    spriteCount: TEST_SPRITES,
    sprite: (index) => {
      if (!(index >= 0 && index < TEST_SPRITES)) throw new RangeError(`no sprite ${index}`);
      return plain(index, 0, 200, true);
    },
  };
}

export function testGame(maps: readonly WolfMap[]): WolfGame {
  return {
    extension: 'WL1',
    maps,
    map: (idOrIndex) => {
      const m = maps.find((x) => x.id === idOrIndex || x.index === idOrIndex);
      if (!m) throw new RangeError(`no map ${idOrIndex}`);
      return m;
    },
    graphics: testGraphics(),
  };
}
