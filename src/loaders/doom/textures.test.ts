import { describe, expect, it } from 'vitest';
import { LanternError } from '../../errors.ts';
import type { Texture } from '../../scene/types.ts';
import { paletteFromRgb, readPalette } from './palette.ts';
import { decodePicture } from './picture.ts';
import {
  encodeFlat, encodePalette, encodePatch, encodePnames, encodeTextureLump, squareRoomWad, testPaletteColor, WadBuilder,
} from './test-wad.ts';
import { DoomGraphics, flatSize } from './textures.ts';
import { readWad, WadStack } from './wad.ts';

const palette = paletteFromRgb(encodePalette().subarray(0, 768));

/** Palette indices back from RGBA (-1 = transparent), using the test palette's distinct colours. */
function indices(t: Pick<Texture, 'rgba'>): number[] {
  const out: number[] = [];
  let wrong = 0; // pixels whose colour is not the test palette's (one expect, not one per pixel: speed)
  for (let i = 0; i < t.rgba.length; i += 4) {
    if (t.rgba[i + 3] === 0) out.push(-1);
    else {
      const index = t.rgba[i]!;
      const [, g, b] = testPaletteColor(index);
      if (t.rgba[i + 1] !== g || t.rgba[i + 2] !== b || t.rgba[i + 3] !== 255) wrong++;
      out.push(index);
    }
  }
  expect(wrong).toBe(0);
  return out;
}

describe('palette', () => {
  it('reads the first palette of PLAYPAL', () => {
    const colors: Array<[number, number, number]> = [[1, 2, 3], [250, 251, 252]];
    const stack = new WadStack([readWad(new WadBuilder().lump('PLAYPAL', encodePalette(colors)).build(), 'p.wad')]);
    const p = readPalette(stack);
    expect([...p.rgb.subarray(0, 6)]).toEqual([1, 2, 3, 250, 251, 252]);
    expect([...new Uint8Array(p.packed.buffer, 4, 4)]).toEqual([250, 251, 252, 255]);
  });

  it('refuses a missing or short PLAYPAL', () => {
    expect(() => readPalette(new WadStack([readWad(new WadBuilder().build(), 'pwad.wad')]))).toThrow(/no PLAYPAL lump/);
    const short = new WadStack([readWad(new WadBuilder().lump('PLAYPAL', new Uint8Array(700)).build(), 'p.wad')]);
    expect(() => readPalette(short)).toThrow(LanternError);
  });
});

describe('pictures', () => {
  it('decodes a patch with gaps (alpha 0) and offsets', () => {
    const pixels = [
      1, -1, 3,
      -1, -1, 6,
      7, -1, 9,
    ];
    const pic = decodePicture(encodePatch(3, 3, pixels, { leftOffset: -4, topOffset: 12 }), 'GAPPY', palette);
    expect(pic).toMatchObject({ name: 'GAPPY', width: 3, height: 3, leftOffset: -4, topOffset: 12 });
    expect(indices(pic)).toEqual(pixels);
  });

  it('decodes a tall patch (relative topdeltas past row 254)', () => {
    const height = 700;
    const pixels = Array.from({ length: 2 * height }, (_, i) => {
      const y = Math.floor(i / 2);
      return y % 100 < 10 ? -1 : (y + (i % 2)) % 256; // gaps every 100 rows, posts far below 254
    });
    const bytes = encodePatch(2, height, pixels);
    expect(indices(decodePicture(bytes, 'TALL', palette))).toEqual(pixels);
  });

  it('refuses a header it cannot use and reports damaged columns', () => {
    expect(() => decodePicture(new Uint8Array(5), 'TINY', palette)).toThrow(/too short/);
    expect(() => decodePicture(new Uint8Array([0, 0, 1, 0, 0, 0, 0, 0]), 'ZERO', palette)).toThrow(/invalid size 0×1/);
    expect(() => decodePicture(new Uint8Array([100, 0, 1, 0, 0, 0, 0, 0, 0, 0]), 'WIDE', palette)).toThrow(/column offsets run past/);
    expect(() => decodePicture(new Uint8Array([0x89, 0x50, 0x4e, 0x47, 0, 0, 0, 0]), 'PNG', palette)).toThrow(/is a PNG/);
    const bytes = encodePatch(2, 2, [1, 2, 3, 4]);
    new DataView(bytes.buffer).setUint32(12, 5000, true); // column 1 points far away
    const warnings: string[] = [];
    const pic = decodePicture(bytes.subarray(0, bytes.length - 2), 'HURT', palette, (w) => warnings.push(w));
    expect(indices(pic)).toEqual([1, -1, 3, -1]);
    expect(warnings).toEqual(['picture HURT: 1 column(s) point past the end of the lump; drew the rest']);
  });
});

describe('DoomGraphics', () => {
  // Patch A: 4×4, index 10 + x, with a hole at (1, 1). Patch B: 3×2, index 50 + y.
  const patchA = Array.from({ length: 16 }, (_, i) => (i === 5 ? -1 : 10 + (i % 4)));
  const patchB = Array.from({ length: 6 }, (_, i) => 50 + Math.floor(i / 3));
  const iwad = new WadBuilder()
    .lump('PLAYPAL', encodePalette())
    .lump('PNAMES', encodePnames(['PATA', 'PATB', 'GONE']))
    .lump('TEXTURE1', encodeTextureLump([
      // B overlaps A and hangs over the right edge; a missing patch and a bad PNAMES index are skipped.
      { name: 'COMBO', width: 6, height: 5, patches: [{ x: 0, y: 0, patch: 0 }, { x: 2, y: 3, patch: 2 }, { x: 4, y: 3, patch: 1 }, { x: 0, y: 0, patch: 7 }] },
      { name: 'NEGATIVE', width: 3, height: 3, patches: [{ x: -2, y: -1, patch: 0 }] },
      { name: 'SKY1', width: 4, height: 4, patches: [{ x: 0, y: 0, patch: 0 }] },
      { name: 'SKY3', width: 4, height: 4, patches: [{ x: 0, y: 0, patch: 0 }] },
    ]))
    .lump('TEXTURE2', encodeTextureLump([
      { name: 'COMBO', width: 1, height: 1, patches: [] }, // a duplicate: TEXTURE1's wins
      { name: 'SKY2', width: 2, height: 2, patches: [{ x: 0, y: 0, patch: 1 }] },
    ]))
    .marker('P_START')
    .lump('PATA', encodePatch(4, 4, patchA))
    .lump('PATB', encodePatch(3, 2, patchB))
    .marker('P_END')
    .marker('F_START')
    .lump('FLAT1', encodeFlat(Array.from({ length: 4096 }, (_, i) => i & 0xff)))
    .lump('TALLFLAT', encodeFlat(5, 8192))
    .lump('BIGFLAT', encodeFlat(6, 128 * 128))
    .lump('ODDFLAT', encodeFlat(7, 1000))
    .marker('F_END')
    .build('IWAD');

  const graphics = (...more: Uint8Array[]) => {
    const warnings: string[] = [];
    const wads = [iwad, ...more].map((b, i) => readWad(b, i === 0 ? 'iwad.wad' : `pwad${i}.wad`));
    return { g: new DoomGraphics(new WadStack(wads), { onWarning: (w) => warnings.push(w) }), warnings };
  };

  it('composes overlapping patches, clipped, skipping missing ones with a warning', () => {
    const { g, warnings } = graphics();
    const combo = g.texture('combo')!;
    expect(combo).toMatchObject({ name: 'COMBO', width: 6, height: 5 });
    const _ = -1;
    expect(indices(combo)).toEqual([
      10, 11, 12, 13, _, _,
      10, _, 12, 13, _, _,
      10, 11, 12, 13, _, _,
      10, 11, 12, 13, 50, 50,
      _, _, _, _, 51, 51,
    ]);
    expect(warnings).toEqual([
      'texture COMBO: skipped patch GONE: no such lump in the WADs',
      'texture COMBO: skipped patch #7: PNAMES has no entry 7 (it has 3)',
    ]);
    expect(g.texture('COMBO')).toBe(combo); // memoised
    expect(indices(g.texture('NEGATIVE')!)).toEqual([12, 13, _, 12, 13, _, 12, 13, _]);
  });

  it('lists textures (first definition wins) and flats; absent names are undefined', () => {
    const { g } = graphics();
    expect(g.textureNames()).toEqual(['COMBO', 'NEGATIVE', 'SKY1', 'SKY3', 'SKY2']);
    expect(g.flatNames()).toEqual(['FLAT1', 'TALLFLAT', 'BIGFLAT', 'ODDFLAT']);
    expect(g.texture('NOPE')).toBeUndefined();
    expect(g.flat('NOPE')).toBeUndefined();
    expect(g.texture('-')).toBeUndefined();
  });

  it('decodes flats of every supported size and skips others with a warning', () => {
    const { g, warnings } = graphics();
    const flat = g.flat('flat1')!;
    expect(flat).toMatchObject({ name: 'FLAT1', width: 64, height: 64 });
    expect(indices(flat).slice(0, 3)).toEqual([0, 1, 2]);
    expect(g.flat('TALLFLAT')).toMatchObject({ width: 64, height: 128 });
    expect(g.flat('BIGFLAT')).toMatchObject({ width: 128, height: 128 });
    expect(g.flat('ODDFLAT')).toBeUndefined();
    expect(warnings).toEqual(['flat ODDFLAT in iwad.wad: 1000 bytes is not a flat size (64×64 is 4096 bytes); skipped']);
    expect([4096, 4160, 8192, 16384, 65536].map(flatSize)).toEqual([[64, 64], [64, 64], [64, 128], [128, 128], [256, 256]]);
    expect(flatSize(4097)).toBeUndefined();
  });

  it('picks the sky by map name, falling back to SKY1', () => {
    const { g } = graphics();
    expect(g.sky('E1M1')!.name).toBe('SKY1');
    expect(g.sky('E2M3')!.name).toBe('SKY2');
    expect(g.sky('E4M1')!.name).toBe('SKY1'); // no SKY4 here
    expect(g.sky('MAP11')!.name).toBe('SKY1');
    expect(g.sky('MAP12')!.name).toBe('SKY2');
    expect(g.sky('MAP20')!.name).toBe('SKY2');
    expect(g.sky('MAP21')!.name).toBe('SKY3');
    expect(g.sky('anything')!.name).toBe('SKY1');
  });

  it('lets a PWAD replace a flat, a patch (without markers) and the texture lumps', () => {
    const pwad = new WadBuilder()
      .lump('PATA', encodePatch(4, 4, new Array<number>(16).fill(99)))
      .marker('FF_START')
      .lump('FLAT1', encodeFlat(42))
      .marker('FF_END')
      .build();
    const { g } = graphics(pwad);
    expect(indices(g.flat('FLAT1')!).every((i) => i === 42)).toBe(true);
    expect(indices(g.texture('SKY1')!).every((i) => i === 99)).toBe(true);
    const newTextures = new WadBuilder().lump('TEXTURE1', encodeTextureLump([{ name: 'MINE', width: 4, height: 4, patches: [{ x: 0, y: 0, patch: 0 }] }])).build();
    // TEXTURE1 replaced, TEXTURE2 kept (its COMBO, hidden before by TEXTURE1's, now shows)
    expect(graphics(newTextures).g.textureNames()).toEqual(['MINE', 'COMBO', 'SKY2']);
  });

  it('builds the square-room test WAD', () => {
    const g = new DoomGraphics(new WadStack([readWad(squareRoomWad(), 'room.wad')]));
    const wall = indices(g.texture('STARTAN3')!);
    expect(wall.slice(0, 6)).toEqual([-1, -1, -1, -1, 100, 101]);
    expect(g.sky('MAP01')).toMatchObject({ width: 256, height: 128 });
    expect(g.flat('F_SKY1')).toBeDefined();
  });
});
