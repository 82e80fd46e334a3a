/**
 * Damaged input: whatever the bytes, the Doom loaders either return a result or throw a
 * LanternError; never another exception (a RangeError from a bad offset, a huge allocation) and
 * never a hang.
 */
import { describe, expect, it } from 'vitest';
import { LanternError } from '../../errors.ts';
import { readMap } from './map-lumps.ts';
import type { DoomMap } from './map-types.ts';
import {
  encodeFlat, encodeMap, encodePalette, encodePatch, encodePnames, encodeTextureLump, squareRoom, WadBuilder,
} from './test-wad.ts';
import { DoomGraphics } from './textures.ts';
import { readWad, WadStack } from './wad.ts';
import { seededRandom } from '../../math/seeded-random.ts';


/** A small WAD exercising every reader: a map, PNAMES, TEXTURE1, patches (one tall), flats. */
function smallWad(): Uint8Array {
  const room = squareRoom('E1M1');
  const map: DoomMap = {
    ...room,
    vertices: [...room.vertices, { x: 10, y: 10 }, { x: 20, y: 20 }],
    linedefs: [...room.linedefs, { v1: 4, v2: 5, flags: 4, special: 0, tag: 0, front: 0, back: 1 }],
  };
  const tall = Array.from({ length: 300 }, (_, i) => (i % 50 < 5 ? -1 : i & 0xff));
  return new WadBuilder()
    .lump('PLAYPAL', encodePalette().subarray(0, 768))
    .lumps(encodeMap(map))
    .lump('PNAMES', encodePnames(['PA', 'PB', 'TALL']))
    .lump('TEXTURE1', encodeTextureLump([
      { name: 'STARTAN3', width: 8, height: 8, patches: [{ x: 0, y: 0, patch: 0 }, { x: 3, y: 2, patch: 1 }] },
      { name: 'SKY1', width: 4, height: 300, patches: [{ x: 0, y: 0, patch: 2 }, { x: 2, y: -5, patch: 2 }] },
    ]))
    .marker('P_START')
    .lump('PA', encodePatch(4, 4, [1, 2, -1, 3, 4, -1, 5, 6, 7, 8, 9, -1, -1, 10, 11, 12]))
    .lump('PB', encodePatch(3, 3, [20, 21, 22, -1, 23, -1, 24, 25, 26]))
    .lump('TALL', encodePatch(1, 300, tall))
    .marker('P_END')
    .marker('F_START')
    .lump('FLOOR4_8', encodeFlat(3, 64))
    .lump('CEIL3_5', encodeFlat(4, 64))
    .marker('F_END')
    .build('IWAD');
}

/** Everything a scene load does with a WAD. Returns normally or throws. */
function loadEverything(bytes: Uint8Array): void {
  const stack = new WadStack([readWad(bytes, 'fuzz.wad')]);
  for (const m of stack.maps()) readMap(stack, m.name, { onWarning: () => {} });
  const g = new DoomGraphics(stack, { onWarning: () => {} });
  for (const name of g.textureNames()) g.texture(name);
  for (const name of g.flatNames()) g.flat(name);
  g.sky('E1M1');
}

/** Runs the loaders; anything thrown must be a LanternError. Returns what happened, for the tallies. */
function outcome(bytes: Uint8Array): 'ok' | 'refused' {
  try {
    loadEverything(bytes);
    return 'ok';
  } catch (e) {
    if (!(e instanceof LanternError)) throw new Error(`not a LanternError: ${String(e)}`, { cause: e });
    return 'refused';
  }
}

describe('corrupt WADs', () => {
  const wad = smallWad();

  it('loads the undamaged WAD', () => {
    expect(outcome(wad)).toBe('ok');
    expect(new WadStack([readWad(wad, 'ok.wad')]).maps()).toHaveLength(1);
  });

  it('survives truncation at every length', () => {
    const tally = { ok: 0, refused: 0 };
    for (let n = 0; n < wad.length; n++) tally[outcome(wad.slice(0, n))]++;
    // The directory is at the end, so any truncation loses it.
    expect(tally.ok).toBe(0);
  });

  it('survives truncation at every length with the directory first', () => {
    // Move the directory in front of the data, so truncations cut lumps rather than the directory.
    const view = new DataView(wad.buffer);
    const count = view.getInt32(4, true);
    const dir = view.getInt32(8, true);
    const moved = new Uint8Array(wad.length);
    const out = new DataView(moved.buffer);
    moved.set(wad.subarray(0, 12));
    moved.set(wad.subarray(12, dir), 12 + 16 * count);
    moved.set(wad.subarray(dir), 12);
    out.setInt32(8, 12, true);
    for (let i = 0; i < count; i++) {
      const at = 12 + 16 * i;
      if (out.getInt32(at + 4, true) > 0) out.setInt32(at, out.getInt32(at, true) + 16 * count, true);
    }
    expect(outcome(moved)).toBe('ok');
    const tally = { ok: 0, refused: 0 };
    for (let n = 0; n < moved.length; n++) tally[outcome(moved.slice(0, n))]++;
    expect(tally.ok).toBe(0);
  });

  it('stops at garbage columns instead of walking them for ever', { timeout: 5_000 }, () => {
    // 1000 columns all pointing at the same 60 000 bytes of empty posts: 15 million posts to walk.
    const width = 1000;
    const bytes = new Uint8Array(8 + 4 * width + 60_000);
    const view = new DataView(bytes.buffer);
    view.setInt16(0, width, true);
    view.setInt16(2, 1, true);
    for (let c = 0; c < width; c++) view.setUint32(8 + 4 * c, 8 + 4 * width, true);
    const wadBytes = new WadBuilder()
      .lump('PLAYPAL', encodePalette().subarray(0, 768))
      .lump('PNAMES', encodePnames(['JUNK']))
      .lump('TEXTURE1', encodeTextureLump([{ name: 'JUNK', width, height: 1, patches: [{ x: 0, y: 0, patch: 0 }] }]))
      .lump('JUNK', bytes)
      .build();
    const warnings: string[] = [];
    const g = new DoomGraphics(new WadStack([readWad(wadBytes, 'junk.wad')]), { onWarning: (w) => warnings.push(w) });
    expect(g.texture('JUNK')).toBeDefined();
    expect(warnings).toEqual(['texture JUNK: patch JUNK: 1000 column(s) have more posts than rows (garbage)']);
  });

  it('survives lump offsets and sizes pointing anywhere', () => {
    const dir = new DataView(wad.buffer).getInt32(8, true);
    const count = new DataView(wad.buffer).getInt32(4, true);
    const random = seededRandom(7);
    for (let i = 0; i < 300; i++) {
      const bytes = wad.slice();
      const view = new DataView(bytes.buffer);
      const entry = dir + 16 * Math.floor(random() * count);
      const field = random() < 0.5 ? 0 : 4;
      const values = [-1, 0x7fffffff, -0x80000000, bytes.length, bytes.length - 1, Math.floor(random() * bytes.length)];
      view.setInt32(entry + field, values[Math.floor(random() * values.length)]!, true);
      outcome(bytes);
    }
  });

  it('survives counts inside lumps set to extremes', () => {
    const lumps = readWad(wad, 'x.wad').lumps;
    for (const name of ['PNAMES', 'TEXTURE1']) {
      const lump = lumps.find((l) => l.name === name)!;
      for (const count of [-1, 1 << 30, 0x7fffffff, 3, 0]) {
        const bytes = wad.slice();
        new DataView(bytes.buffer).setInt32(lump.offset, count, true);
        outcome(bytes);
      }
    }
  });

  it('survives hundreds of random byte flips', { timeout: 10_000 }, () => {
    const random = seededRandom(1234);
    const tally = { ok: 0, refused: 0 };
    const dir = new DataView(wad.buffer).getInt32(8, true);
    for (let i = 0; i < 600; i++) {
      const bytes = wad.slice();
      const flips = 1 + Math.floor(random() * 4);
      for (let f = 0; f < flips; f++) {
        // Half the flips land in the header and directory, where they do the most damage.
        const at = random() < 0.5 ? (random() < 0.1 ? Math.floor(random() * 12) : dir + Math.floor(random() * (bytes.length - dir))) : Math.floor(random() * bytes.length);
        bytes[at] = Math.floor(random() * 256);
      }
      tally[outcome(bytes)]++;
    }
    // Both outcomes occur: the test exercises the readers, not just the header check.
    expect(tally.ok).toBeGreaterThan(50);
    expect(tally.refused).toBeGreaterThan(50);
  });
});
