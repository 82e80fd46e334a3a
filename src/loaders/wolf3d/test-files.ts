/**
 * Writes small Wolfenstein 3D data files in the game's own formats, for tests: MAPHEAD and
 * GAMEMAPS with planes really Carmack- and RLEW-compressed (near and far pointers, escaped tag
 * words, runs), and a VSWAP with wall pages, compiled sprites and sound chunks. The readers
 * (maps.ts, vswap.ts) are tested by writing with these and reading back; the map-to-scene builder
 * and the browser tests use `testGameFiles()`, a ready-made small game. Pure.
 */
import type { NamedBytes } from '../format.ts';
import { FAR_TAG, MAP_HEADER_SIZE, MAX_MAPS, NEAR_TAG, GAMEMAPS_SIGNATURE } from './maps.ts';
import { PAGE_SIZE, WALL_PAGE_BYTES } from './vswap.ts';

/** The RLEW tag of every shipped Wolf3D MAPHEAD. */
export const DEFAULT_RLEW_TAG = 0xabcd;

export interface TestMap {
  readonly title: string;
  readonly width: number;
  readonly height: number;
  /** Row-major, width · height words each (as WolfMap.planes). */
  readonly planes: readonly [Uint16Array, Uint16Array, Uint16Array];
}

/** RLEW compression: runs of 3 or more equal words, and every word equal to the tag, become `tag count value`. */
export function rlewCompress(words: Uint16Array, tag: number): Uint16Array {
  const out: number[] = [words.length * 2];
  for (let i = 0; i < words.length; ) {
    const w = words[i]!;
    let run = 1;
    while (i + run < words.length && words[i + run] === w && run < 0xffff) run++;
    if (run >= 3 || w === tag) out.push(tag, run, w);
    else for (let k = 0; k < run; k++) out.push(w);
    i += run;
  }
  return new Uint16Array(out);
}

/**
 * Carmack compression (greedy, longest match first): a repeat of 2+ words at most 255 words back
 * becomes a near pointer (3 bytes), a longer repeat further back a far pointer (4 bytes); a literal
 * word with 0xA7 or 0xA8 as its high byte is escaped (count 0, tag, low byte). Output starts with
 * the expanded size in bytes. `far: false` / `near: false` turn a kind of pointer off, so that a
 * test can make sure the other kind is exercised.
 */
export function carmackCompress(words: Uint16Array, options: { near?: boolean; far?: boolean } = {}): Uint8Array {
  const useNear = options.near ?? true;
  const useFar = options.far ?? true;
  const out: number[] = [(words.length * 2) & 0xff, (words.length * 2) >> 8];
  for (let i = 0; i < words.length; ) {
    let bestLength = 0;
    let bestFrom = 0;
    let bestNear = false;
    for (let from = 0; from < i; from++) {
      const nearOk = useNear && i - from <= 255;
      if (!nearOk && !(useFar && from <= 0xffff)) continue;
      let n = 0;
      while (n < 255 && i + n < words.length && words[from + n] === words[i + n]) n++;
      // Longest first; between equals, a near pointer (one byte shorter).
      if (n > bestLength || (n === bestLength && nearOk && !bestNear)) {
        bestLength = n;
        bestFrom = from;
        bestNear = nearOk;
      }
    }
    if (bestLength >= 2 && bestNear) {
      out.push(bestLength, NEAR_TAG, i - bestFrom);
      i += bestLength;
    } else if (bestLength >= 3 && !bestNear) {
      out.push(bestLength, FAR_TAG, bestFrom & 0xff, bestFrom >> 8);
      i += bestLength;
    } else {
      const w = words[i]!;
      const hi = w >> 8;
      if (hi === NEAR_TAG || hi === FAR_TAG) out.push(0, hi, w & 0xff);
      else out.push(w & 0xff, hi);
      i++;
    }
  }
  return new Uint8Array(out);
}

/**
 * MAPHEAD and GAMEMAPS holding `maps` in slots 0, 1, … (undefined: an empty slot). Each map's
 * planes come first, then its 38-byte header, as in the game's files.
 */
export function writeMapFiles(maps: readonly (TestMap | undefined)[], options: { rlewTag?: number; carmack?: { near?: boolean; far?: boolean } } = {}): { maphead: Uint8Array; gamemaps: Uint8Array } {
  const tag = options.rlewTag ?? DEFAULT_RLEW_TAG;
  if (maps.length > MAX_MAPS) throw new Error(`at most ${MAX_MAPS} maps`);
  const chunks: Uint8Array[] = [new TextEncoder().encode(GAMEMAPS_SIGNATURE)];
  let size = chunks[0]!.length;
  const headerOffsets: number[] = [];
  for (const map of maps) {
    if (!map) {
      headerOffsets.push(0);
      continue;
    }
    const planeOffsets: number[] = [];
    const planeLengths: number[] = [];
    for (const plane of map.planes) {
      if (plane.length !== map.width * map.height) throw new Error(`plane of ${plane.length} words for a ${map.width} × ${map.height} map`);
      const rlew = rlewCompress(plane, tag);
      const carmack = carmackCompress(rlew, options.carmack);
      planeOffsets.push(size);
      planeLengths.push(carmack.length);
      chunks.push(carmack);
      size += carmack.length;
    }
    const header = new Uint8Array(MAP_HEADER_SIZE);
    const view = new DataView(header.buffer);
    planeOffsets.forEach((o, p) => view.setUint32(4 * p, o, true));
    planeLengths.forEach((l, p) => view.setUint16(12 + 2 * p, l, true));
    view.setUint16(18, map.width, true);
    view.setUint16(20, map.height, true);
    header.set(new TextEncoder().encode(map.title.slice(0, 15)), 22);
    headerOffsets.push(size);
    chunks.push(header);
    size += header.length;
  }
  const gamemaps = concat(chunks);
  const maphead = new Uint8Array(2 + 4 * MAX_MAPS);
  const view = new DataView(maphead.buffer);
  view.setUint16(0, tag, true);
  headerOffsets.forEach((o, i) => view.setUint32(2 + 4 * i, o, true));
  return { maphead, gamemaps };
}

/** A sprite to write: 64 × 64 palette indices, row-major, -1 where nothing is drawn. */
export type TestSprite = Int16Array;

/**
 * A VSWAP with these wall pages (64 × 64 palette indices each, row-major: the writer stores them
 * column-major as the game does), sprites (compiled into posts) and sound chunks (any bytes).
 */
export function writeVswap(walls: readonly Uint8Array[], sprites: readonly TestSprite[], sounds: readonly Uint8Array[] = []): Uint8Array {
  const pages: Uint8Array[] = [];
  for (const wall of walls) {
    if (wall.length !== WALL_PAGE_BYTES) throw new Error(`a wall page is ${WALL_PAGE_BYTES} indices`);
    const page = new Uint8Array(WALL_PAGE_BYTES);
    for (let y = 0; y < PAGE_SIZE; y++) for (let x = 0; x < PAGE_SIZE; x++) page[x * PAGE_SIZE + y] = wall[y * PAGE_SIZE + x]!;
    pages.push(page);
  }
  for (const sprite of sprites) pages.push(compileSprite(sprite));
  pages.push(...sounds);
  const count = pages.length;
  const tableEnd = 6 + 6 * count;
  const out = new Uint8Array(tableEnd + pages.reduce((s, p) => s + p.length, 0));
  const view = new DataView(out.buffer);
  view.setUint16(0, count, true);
  view.setUint16(2, walls.length, true);
  view.setUint16(4, walls.length + sprites.length, true);
  let at = tableEnd;
  pages.forEach((page, i) => {
    view.setUint32(6 + 4 * i, at, true);
    view.setUint16(6 + 4 * count + 2 * i, page.length, true);
    out.set(page, at);
    at += page.length;
  });
  return out;
}

/**
 * The game's compiled sprite: leftpix, rightpix, one offset per column, then the texels of every
 * post, then each column's posts (end · 2, texel offset − start row, start · 2) ending in 0. The
 * stored offset is taken modulo 2¹⁶, as the game adds it in 16 bits.
 */
export function compileSprite(sprite: TestSprite): Uint8Array {
  if (sprite.length !== WALL_PAGE_BYTES) throw new Error(`a sprite is ${WALL_PAGE_BYTES} indices`);
  const drawn = (x: number, y: number) => sprite[y * PAGE_SIZE + x]! >= 0;
  const columns: number[] = [];
  for (let x = 0; x < PAGE_SIZE; x++) for (let y = 0; y < PAGE_SIZE; y++) if (drawn(x, y)) { columns.push(x); break; }
  const left = columns[0] ?? 0;
  const right = columns.at(-1) ?? 0;
  const n = right - left + 1;
  const texels: number[] = [];
  const texelsAt = 4 + 2 * n;
  const posts: number[][] = [];
  for (let x = left; x <= right; x++) {
    const column: number[] = [];
    for (let y = 0; y < PAGE_SIZE; ) {
      if (!drawn(x, y)) {
        y++;
        continue;
      }
      let end = y;
      while (end < PAGE_SIZE && drawn(x, end)) end++;
      const source = texelsAt + texels.length;
      for (let k = y; k < end; k++) texels.push(sprite[k * PAGE_SIZE + x]!);
      column.push(end * 2, (source - y) & 0xffff, y * 2);
      y = end;
    }
    column.push(0);
    posts.push(column);
  }
  const words: number[] = [left, right];
  let postAt = texelsAt + texels.length;
  for (const column of posts) {
    words.push(postAt);
    postAt += 2 * column.length;
  }
  const out = new Uint8Array(postAt);
  const view = new DataView(out.buffer);
  words.forEach((w, i) => view.setUint16(2 * i, w, true));
  out.set(texels, texelsAt);
  let at = texelsAt + texels.length;
  for (const column of posts) for (const w of column) {
    view.setUint16(at, w, true);
    at += 2;
  }
  return out;
}

function concat(chunks: readonly Uint8Array[]): Uint8Array {
  const out = new Uint8Array(chunks.reduce((s, c) => s + c.length, 0));
  let at = 0;
  for (const c of chunks) {
    out.set(c, at);
    at += c.length;
  }
  return out;
}

/** Tile codes of plane 0 and object codes of plane 1 the test game uses (the game's own numbering). */
export const TEST_CODES = {
  /** Wall tiles 1–4 (pages 0–7); the door pages are the last 8 wall pages, as in the game (DOORWALL). */
  walls: [1, 2, 3, 4],
  /** A door in a wall running north–south (passed east–west; the game's vertical door) and one in a wall running east–west. */
  doorVertical: 90,
  doorHorizontal: 91,
  /** The first floor (area) code. */
  floor: 108,
  /** Player start facing north, east, south, west. */
  playerStart: { north: 19, east: 20, south: 21, west: 22 },
  /** Statics: floor lamp, chandelier, ceiling light, green barrel, potted plant. */
  statics: { floorLamp: 26, chandelier: 27, ceilingLight: 37, barrel: 24, plant: 34 },
} as const;

/**
 * A small game: `maps` maps (default 2) of 64 × 64, each a walled room split by a wall with a
 * door, the player in the south half facing north, a few statics; 4 walls (8 pages) and the 8 door
 * pages; 50 sprites (the game's static objects start at sprite 2); two sound chunks. Each map
 * differs (map k's room is k tiles narrower) so that tests can tell them apart.
 */
export function testGameFiles(options: { extension?: string; maps?: number; folder?: string } = {}): { maphead: NamedBytes; gamemaps: NamedBytes; vswap: NamedBytes } {
  const ext = options.extension ?? 'WL1';
  const prefix = options.folder ? `${options.folder}/` : '';
  const maps = Array.from({ length: options.maps ?? 2 }, (_, k) => testMap(k));
  const { maphead, gamemaps } = writeMapFiles(maps);
  const walls = Array.from({ length: 16 }, (_, page) => testWallPage(page));
  const sprites = Array.from({ length: 50 }, (_, i) => testSpritePage(i));
  const vswap = writeVswap(walls, sprites, [new Uint8Array([1, 2, 3, 4]), new Uint8Array(7)]);
  return { maphead: { name: `${prefix}MAPHEAD.${ext}`, bytes: maphead }, gamemaps: { name: `${prefix}GAMEMAPS.${ext}`, bytes: gamemaps }, vswap: { name: `${prefix}VSWAP.${ext}`, bytes: vswap } };
}

/**
 * Map k of testGameFiles: a room from (2, 2) to (61 − k, 40) (x east, y south), split by a wall
 * along y = 20 with a door (91) at x = 10, its south half split again by a wall along x = 30 with a
 * door (90) at y = 33; the player at (10, 30) facing north; statics west of x = 30.
 */
export function testMap(k: number): TestMap {
  const width = 64;
  const height = 64;
  const walls = new Uint16Array(width * height).fill(1);
  const objects = new Uint16Array(width * height);
  const right = 61 - k;
  for (let y = 2; y <= 40; y++) for (let x = 2; x <= right; x++) walls[y * width + x] = TEST_CODES.floor + (y < 20 ? 0 : 1);
  for (let x = 2; x <= right; x++) walls[20 * width + x] = 2 + (x % 3);
  walls[20 * width + 10] = TEST_CODES.doorHorizontal;
  for (let y = 21; y <= 40; y++) walls[y * width + 30] = 3;
  walls[33 * width + 30] = TEST_CODES.doorVertical;
  objects[30 * width + 10] = TEST_CODES.playerStart.north;
  objects[10 * width + 10] = TEST_CODES.statics.chandelier;
  objects[25 * width + 5] = TEST_CODES.statics.floorLamp;
  objects[35 * width + 15] = TEST_CODES.statics.ceilingLight;
  objects[12 * width + 20] = TEST_CODES.statics.barrel;
  objects[38 * width + 3] = TEST_CODES.statics.plant;
  // Plane 2 is unused by the game; a pattern here checks that it round-trips too.
  const unused = new Uint16Array(width * height).map((_, i) => (i * 7919) & 0xffff);
  return { title: `Test Map${k + 1}`, width, height, planes: [walls, objects, unused] };
}

/** Wall page p: stripes in a colour per wall, darker on odd (east–west) pages; door pages a grid. */
export function testWallPage(page: number): Uint8Array {
  const out = new Uint8Array(WALL_PAGE_BYTES);
  for (let y = 0; y < PAGE_SIZE; y++) {
    for (let x = 0; x < PAGE_SIZE; x++) {
      const stripe = ((x >> 3) + (y >> 4)) & 1;
      out[y * PAGE_SIZE + x] = page >= 8 ? (x % 16 === 0 || y % 16 === 0 ? 0x1d : 0x0e) : 0x20 + 16 * ((page >> 1) % 8) + stripe + 4 * (page & 1);
    }
  }
  return out;
}

/** Sprite i: a disc of radius 8 + i % 20 texels, centred, in colour 0x40 + i, with a hole in the middle. */
export function testSpritePage(i: number): TestSprite {
  const out = new Int16Array(WALL_PAGE_BYTES).fill(-1);
  const r = 8 + (i % 20);
  for (let y = 0; y < PAGE_SIZE; y++) {
    for (let x = 0; x < PAGE_SIZE; x++) {
      const d2 = (x - 31.5) ** 2 + (y - 40.5) ** 2;
      if (d2 <= r * r && d2 >= 9) out[y * PAGE_SIZE + x] = (0x40 + i + (x & 3)) & 0xff;
    }
  }
  return out;
}
