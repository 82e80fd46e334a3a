import { describe, expect, it } from 'vitest';
import { LanternError } from '../../errors.ts';
import { seededRandom } from '../../math/seeded-random.ts';
import { gamePalette } from './palette.ts';
import { compileSprite, testSpritePage, testWallPage, writeVswap, type TestSprite } from './test-files.ts';
import { decodeSprite, decodeWall, readVswap } from './vswap.ts';

const palette = gamePalette();
const named = (bytes: Uint8Array) => ({ name: 'VSWAP.WL1', bytes });

/** The RGBA the decoder must give for palette indices (−1: transparent). */
function expectedRgba(indices: ArrayLike<number>): Uint8Array {
  const out = new Uint8Array(indices.length * 4);
  for (let i = 0; i < indices.length; i++) {
    const c = indices[i]!;
    if (c < 0) continue;
    out.set([palette[3 * c]!, palette[3 * c + 1]!, palette[3 * c + 2]!, 255], 4 * i);
  }
  return out;
}

/** Sprites the compiler must get right: one texel, one column, posts at the top and bottom rows, a full square, random holes. */
function awkwardSprites(): TestSprite[] {
  const at = (x: number, y: number, c: number, s = new Int16Array(4096).fill(-1)) => ((s[y * 64 + x] = c), s);
  const random = seededRandom(5);
  const holes = new Int16Array(4096).map(() => (random() < 0.4 ? -1 : Math.floor(random() * 256)));
  const column = new Int16Array(4096).fill(-1);
  for (let y = 0; y < 64; y += 3) column[y * 64 + 17] = y;
  return [at(63, 63, 7), at(0, 0, 200), at(40, 50, 3, at(40, 0, 4)), new Int16Array(4096).fill(9), holes, column, new Int16Array(4096).fill(-1)];
}

describe('VSWAP', () => {
  it('round-trip: wall pages come back as written (column-major on disk) and sprites with alpha 0 where nothing is drawn', () => {
    const walls = [testWallPage(0), testWallPage(1), testWallPage(9)];
    const sprites = [...awkwardSprites(), testSpritePage(3)];
    const file = readVswap(named(writeVswap(walls, sprites, [new Uint8Array(3)])));
    expect([file.chunks.length, file.spriteStart, file.soundStart]).toEqual([walls.length + sprites.length + 1, 3, 3 + sprites.length]);
    walls.forEach((w, i) => {
      const image = decodeWall(file, i, palette);
      expect([image.width, image.height]).toEqual([64, 64]);
      expect(image.rgba).toEqual(expectedRgba(w));
    });
    sprites.forEach((s, i) => expect(decodeSprite(file, i, palette).rgba, `sprite ${i}`).toEqual(expectedRgba(s)));
    // On disk, byte x · 64 + y of a wall page is texel (x, y).
    const raw = writeVswap([testWallPage(2)], []);
    const page = raw.subarray(raw.length - 4096);
    expect(page[5 * 64 + 40]).toBe(testWallPage(2)[40 * 64 + 5]);
    expect(() => decodeWall(file, 3, palette)).toThrow(/has 3 wall pages; there is no wall page 3/);
    expect(() => decodeSprite(file, sprites.length, palette)).toThrow(/there is no sprite/);
  });

  it('reads sprite texels at source offset + row in 16 bits, as the game adds them', () => {
    // One texel at row 60 of column 0: the texels start right after the 6-byte header, so the
    // stored offset (6 − 60) wraps below zero.
    const sprite = new Int16Array(4096).fill(-1);
    sprite[60 * 64] = 42;
    const chunk = compileSprite(sprite);
    const view = new DataView(chunk.buffer);
    const post = view.getUint16(4, true);
    expect(view.getUint16(post + 2, true)).toBe((6 - 60) & 0xffff);
    const file = readVswap(named(writeVswap([], [sprite])));
    expect(decodeSprite(file, 0, palette).rgba).toEqual(expectedRgba(sprite));
  });

  it('a truncated or lying file gives a LanternError naming it, never another error or a hang', () => {
    const bytes = writeVswap([testWallPage(0), testWallPage(1)], awkwardSprites(), [new Uint8Array(5)]);
    const decodeAll = (b: Uint8Array) => {
      const file = readVswap(named(b));
      for (let i = 0; i < file.spriteStart; i++) decodeWall(file, i, palette);
      for (let i = 0; i < file.soundStart - file.spriteStart; i++) decodeSprite(file, i, palette);
    };
    let errors = 0;
    const check = (b: Uint8Array) => {
      try {
        decodeAll(b);
      } catch (e) {
        expect(e).toBeInstanceOf(LanternError);
        expect((e as Error).message).toMatch(/^VSWAP\.WL1/);
        errors++;
      }
    };
    // Cut through the header, the table and the pages (sound chunks are never read, so a cut in the last, a sound, is fine).
    const soundAt = bytes.length - 5;
    for (let cut = 0; cut < soundAt; cut += 7) check(bytes.subarray(0, cut));
    expect(errors).toBe(Math.ceil(soundAt / 7));
    const random = seededRandom(3);
    for (let t = 0; t < 3000; t++) {
      const b = bytes.slice();
      // Mostly the header, the table and the sprites' words, where lies matter.
      const at = random() < 0.5 ? Math.floor(random() * 120) : 6 + 6 * 10 + 2 * 4096 + Math.floor(random() * (soundAt - 6 - 60 - 8192));
      b[at] = Math.floor(random() * 256);
      check(b);
    }
    expect(() => readVswap(named(new Uint8Array([10, 0, 20, 0, 5, 0])))).toThrow(/VSWAP\.WL1: the header's chunk counts do not fit together/);
    expect(() => readVswap(named(new Uint8Array([200, 0, 0, 0, 0, 0])))).toThrow(/VSWAP\.WL1: the table of 200 chunks runs past the end of the 6-byte file/);
  });

  it('a column of posts that never ends is refused, not followed', () => {
    // Column 0 of 0..0: 70 one-row posts and no 0 word after them.
    const posts = 70;
    const chunk = new Uint8Array(6 + 6 * posts + 16);
    const view = new DataView(chunk.buffer);
    view.setUint16(4, 6, true);
    for (let k = 0; k < posts; k++) view.setUint16(6 + 6 * k, 2, true);
    const bytes = writeVswap([], [], [chunk]);
    // Count the one chunk as a sprite: sounds start after it.
    new DataView(bytes.buffer).setUint16(4, 1, true);
    expect(() => decodeSprite(readVswap(named(bytes)), 0, palette)).toThrow(/VSWAP\.WL1: sprite 0 \(chunk 0\): column 0 does not end its list of posts/);
  });
});
