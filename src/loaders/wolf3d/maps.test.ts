import { describe, expect, it } from 'vitest';
import { LanternError } from '../../errors.ts';
import { seededRandom } from '../../math/seeded-random.ts';
import { carmackExpand, FAR_TAG, listMaps, mapId, mapIndexOf, NEAR_TAG, readMap, readMapHead, rlewExpand } from './maps.ts';
import { carmackCompress, DEFAULT_RLEW_TAG, rlewCompress, testMap, writeMapFiles, type TestMap } from './test-files.ts';

const named = (name: string, bytes: Uint8Array) => ({ name, bytes });

/** A map whose planes hold what the compressors must handle: runs, repeats near and far, tag words, words with 0xA7/0xA8 high bytes. */
function awkwardMap(seed: number, width = 64, height = 64): TestMap {
  const random = seededRandom(seed);
  const n = width * height;
  const planes = [0, 1, 2].map(() => {
    const p = new Uint16Array(n);
    for (let i = 0; i < n; ) {
      const r = random();
      if (r < 0.3) {
        // A run.
        const len = 1 + Math.floor(random() * 40);
        p.fill(Math.floor(random() * 4), i, i + len);
        i += len;
      } else if (r < 0.5 && i > 300) {
        // A repeat of something far back (a far pointer) or near (a near pointer).
        const back = random() < 0.5 ? 2 + Math.floor(random() * 200) : 260 + Math.floor(random() * (i - 260));
        const len = 2 + Math.floor(random() * 12);
        for (let k = 0; k < len && i < n; k++, i++) p[i] = p[i - back]!;
      } else if (r < 0.6) {
        p[i++] = [NEAR_TAG << 8, (NEAR_TAG << 8) | 0x13, (FAR_TAG << 8) | 0xff, DEFAULT_RLEW_TAG, 0xa7a7][Math.floor(random() * 5)]!;
      } else p[i++] = Math.floor(random() * 0x10000);
    }
    return p;
  }) as unknown as [Uint16Array, Uint16Array, Uint16Array];
  return { title: `Awkward ${seed}`, width, height, planes };
}

describe('map ids', () => {
  it('numbers maps ten to an episode, from E1L1', () => {
    expect([0, 9, 10, 59].map(mapId)).toEqual(['E1L1', 'E1L10', 'E2L1', 'E6L10']);
    expect(['E1L1', 'e2l3', 'E1L10', '1', '13', 'E1L11', 'E0L1', '0', '101', 'MAP01'].map(mapIndexOf)).toEqual([0, 12, 9, 0, 12, undefined, undefined, undefined, undefined, undefined]);
  });
});

describe('RLEW and Carmack', () => {
  it('expand what the compressors wrote, exactly, through near and far pointers and escapes', () => {
    for (const seed of [1, 2, 3]) {
      const plane = awkwardMap(seed).planes[0];
      const rlew = rlewCompress(plane, DEFAULT_RLEW_TAG);
      expect(rlew.length).toBeLessThan(plane.length);
      const carmack = carmackCompress(rlew);
      // The stream must really use every kind of code: near (0xA7) and far (0xA8) pointers and escapes (count 0).
      const codes = { near: 0, far: 0, escape: 0 };
      for (let i = 2; i + 1 < carmack.length; ) {
        const [count, tag] = [carmack[i]!, carmack[i + 1]!];
        if (tag === NEAR_TAG || tag === FAR_TAG) {
          if (count === 0) codes.escape++;
          else if (tag === NEAR_TAG) codes.near++;
          else codes.far++;
          i += count === 0 || tag === NEAR_TAG ? 3 : 4;
        } else i += 2;
      }
      expect(codes.near).toBeGreaterThan(10);
      expect(codes.far).toBeGreaterThan(10);
      expect(codes.escape).toBeGreaterThan(10);
      const expanded = carmackExpand(carmack, 'test');
      expect(expanded).toEqual(rlew);
      expect(rlewExpand(expanded, DEFAULT_RLEW_TAG, plane.length, 'test')).toEqual(plane);
    }
  });

  it('expand far-only and near-only streams too', () => {
    const plane = awkwardMap(7).planes[1];
    const rlew = rlewCompress(plane, DEFAULT_RLEW_TAG);
    for (const options of [{ near: false }, { far: false }, { near: false, far: false }]) {
      expect(carmackExpand(carmackCompress(rlew, options), 'test')).toEqual(rlew);
    }
  });

  it('a copy that overlaps what it writes repeats a run (word by word)', () => {
    // Size 10 bytes, the word 5, a near copy of 4 words from 1 back: five 5s.
    const stream = new Uint8Array([10, 0, 5, 0, 4, NEAR_TAG, 1]);
    expect([...carmackExpand(stream, 'test')]).toEqual([5, 5, 5, 5, 5]);
  });

  it('refuse pointers before the start, copies past the stated size and short data', () => {
    const bad = [
      [new Uint8Array([6, 0, 1, NEAR_TAG, 1]), /near pointer at word 0 reaches 1 words back/],
      [new Uint8Array([6, 0, 5, 0, 1, FAR_TAG, 1, 0]), /far pointer at word 1 refers to word 1, not yet written/],
      [new Uint8Array([4, 0, 5, 0, 3, NEAR_TAG, 1]), /copy of 3 words at word 1 runs past the expanded size of 2 words/],
      [new Uint8Array([8, 0, 5, 0]), /ends after 1 of 4 words/],
      [new Uint8Array([7, 0, 5, 0]), /not a positive whole number of words/],
      [new Uint8Array([4]), /too few for the expanded size/],
    ] as const;
    for (const [stream, message] of bad) expect(() => carmackExpand(stream, 'GAMEMAPS.WL1: map 1')).toThrow(message);
    expect(() => rlewExpand(new Uint16Array([8, DEFAULT_RLEW_TAG, 5, 1]), DEFAULT_RLEW_TAG, 4, 'x')).toThrow(/run of 5 tiles at tile 0 runs past the map's 4 tiles/);
    expect(() => rlewExpand(new Uint16Array([8, 1, 2]), DEFAULT_RLEW_TAG, 4, 'x')).toThrow(/ends after 2 of 4 tiles/);
    expect(() => rlewExpand(new Uint16Array([8, 1, DEFAULT_RLEW_TAG, 2]), DEFAULT_RLEW_TAG, 4, 'x')).toThrow(/ends inside a run/);
    expect(() => rlewExpand(new Uint16Array([6, 1, 2, 3]), DEFAULT_RLEW_TAG, 4, 'x')).toThrow(/expands to 6 bytes, not the map's 4 tiles/);
  });
});

describe('MAPHEAD and GAMEMAPS', () => {
  it('round-trip: the planes read back are the planes written, in their slots, with titles and sizes', () => {
    const maps = [testMap(0), undefined, awkwardMap(4), awkwardMap(5, 32, 48)];
    const { maphead, gamemaps } = writeMapFiles(maps, { rlewTag: 0x1234 });
    const head = readMapHead(named('MAPHEAD.WL6', maphead));
    expect(head.rlewTag).toBe(0x1234);
    expect(head.offsets).toHaveLength(100);
    const file = named('GAMEMAPS.WL6', gamemaps);
    expect(listMaps(head, file)).toEqual([
      { index: 0, id: 'E1L1', title: 'Test Map1', width: 64, height: 64 },
      { index: 2, id: 'E1L3', title: 'Awkward 4', width: 64, height: 64 },
      { index: 3, id: 'E1L4', title: 'Awkward 5', width: 32, height: 48 },
    ]);
    for (const i of [0, 2, 3]) {
      const map = readMap(head, file, i);
      expect(map.planes).toEqual(maps[i]!.planes);
    }
    expect(() => readMap(head, file, 1)).toThrow(/map slot 2 \(E1L2\) is empty/);
    expect(() => readMap(head, file, 100)).toThrow(LanternError);
  });

  it('a MAPHEAD shorter than 100 slots lists the slots it has', () => {
    const { maphead, gamemaps } = writeMapFiles([testMap(0), testMap(1)]);
    const head = readMapHead(named('MAPHEAD.WL1', maphead.subarray(0, 2 + 4 * 2)));
    expect(head.offsets).toHaveLength(2);
    expect(listMaps(head, named('GAMEMAPS.WL1', gamemaps)).map((m) => m.id)).toEqual(['E1L1', 'E1L2']);
    expect(() => readMapHead(named('MAPHEAD.WL1', maphead.subarray(0, 5)))).toThrow(/MAPHEAD.WL1: not a MAPHEAD file \(5 bytes/);
  });

  it('every truncation and every flipped byte gives a map or a LanternError naming the file, never another error', () => {
    const { maphead, gamemaps } = writeMapFiles([testMap(0), awkwardMap(9, 16, 16)]);
    const head = readMapHead(named('MAPHEAD.WL1', maphead));
    const readAll = (bytes: Uint8Array, h = head) => {
      const file = named('GAMEMAPS.WL1', bytes);
      for (const info of listMaps(h, file)) readMap(h, file, info.index);
    };
    const outcomes = { ok: 0, errors: 0 };
    const check = (run: () => void) => {
      try {
        run();
        outcomes.ok++;
      } catch (e) {
        expect(e).toBeInstanceOf(LanternError);
        expect((e as Error).message).toMatch(/^(GAMEMAPS|MAPHEAD)\.WL1/);
        outcomes.errors++;
      }
    };
    // Cut anywhere: every map's data ends somewhere, so every cut but none is an error.
    for (let cut = 0; cut < gamemaps.length; cut += 1) check(() => readAll(gamemaps.subarray(0, cut)));
    expect(outcomes.ok).toBe(0);
    // Flip bytes: lengths, offsets, sizes and codes all lie somewhere.
    const random = seededRandom(11);
    for (let t = 0; t < 2000; t++) {
      const bytes = gamemaps.slice();
      const at = Math.floor(random() * bytes.length);
      bytes[at] = Math.floor(random() * 256);
      check(() => readAll(bytes));
    }
    // MAPHEAD's offsets lie too.
    for (let t = 0; t < 500; t++) {
      const bytes = maphead.slice();
      bytes[Math.floor(random() * 10)] = Math.floor(random() * 256);
      check(() => readAll(gamemaps, readMapHead(named('MAPHEAD.WL1', bytes))));
    }
    expect(outcomes.errors).toBeGreaterThan(gamemaps.length);
  });

  it('names the map and the problem', () => {
    const { maphead, gamemaps } = writeMapFiles([testMap(0)]);
    const head = readMapHead(named('MAPHEAD.WL1', maphead));
    const lying = gamemaps.slice();
    const headerAt = head.offsets[0]!;
    // Width 300 × height 300: more than a plane can hold.
    new DataView(lying.buffer).setUint16(headerAt + 18, 300, true);
    new DataView(lying.buffer).setUint16(headerAt + 20, 300, true);
    expect(() => listMaps(head, named('GAMEMAPS.WL1', lying))).toThrow(/^GAMEMAPS\.WL1: map 1 \(E1L1\): its header says 300 × 300 tiles/);
    // A smaller width than the planes were written for: the RLEW size no longer matches.
    new DataView(lying.buffer).setUint16(headerAt + 18, 32, true);
    new DataView(lying.buffer).setUint16(headerAt + 20, 64, true);
    expect(() => readMap(head, named('GAMEMAPS.WL1', lying), 0)).toThrow(/^GAMEMAPS\.WL1: map 1 \(E1L1\), plane 0: expands to 8192 bytes, not the map's 2048 tiles/);
    const far = maphead.slice();
    new DataView(far.buffer).setUint32(2, 1_000_000, true);
    expect(() => listMaps(readMapHead(named('MAPHEAD.WL1', far)), named('GAMEMAPS.WL1', gamemaps))).toThrow(/map 1 \(E1L1\): its header at offset 1000000 \(from MAPHEAD\.WL1\) runs past the end/);
  });
});
