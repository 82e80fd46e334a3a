import { describe, expect, it } from 'vitest';
import { LanternError } from '../../errors.ts';
import { encodeFlat, encodeMap, squareRoom, WadBuilder } from './test-wad.ts';
import { readWad, WadStack } from './wad.ts';

const bytesOf = (...values: number[]) => new Uint8Array(values);
const text = (b: Uint8Array | undefined) => (b ? new TextDecoder().decode(b) : undefined);
const enc = (s: string) => new TextEncoder().encode(s);

describe('readWad', () => {
  it('reads the header and directory, upper-casing names and stopping at NUL', () => {
    const bytes = new WadBuilder().lump('hello', enc('world')).marker('F_START').lump('Two', bytesOf(1, 2)).build('IWAD');
    const wad = readWad(bytes, 'test.wad');
    expect(wad.kind).toBe('IWAD');
    expect(wad.name).toBe('test.wad');
    expect(wad.lumps.map((l) => [l.name, l.size, l.index])).toEqual([['HELLO', 5, 0], ['F_START', 0, 1], ['TWO', 2, 2]]);
    expect(text(wad.data(wad.lumps[0]!))).toBe('world');
    expect([...wad.data(wad.lumps[2]!)]).toEqual([1, 2]);
  });

  it('ignores garbage after the NUL in a name', () => {
    const bytes = new WadBuilder().lump('ABC', bytesOf(9)).build('PWAD');
    const dir = new DataView(bytes.buffer).getInt32(8, true);
    bytes.set([0, 0x58, 0x59], dir + 8 + 3); // "ABC\0XY.."
    expect(readWad(bytes, 'x.wad').lumps[0]!.name).toBe('ABC');
  });

  it('reads a WAD inside a larger buffer (a Node Buffer slice)', () => {
    const inner = new WadBuilder().lump('A', bytesOf(7, 8)).build();
    const outer = new Uint8Array(inner.length + 10);
    outer.set(inner, 5);
    const wad = readWad(outer.subarray(5, 5 + inner.length), 'sliced.wad');
    expect([...wad.data(wad.lumps[0]!)]).toEqual([7, 8]);
  });

  const header = (magic: string, count: number, offset: number, total = 12) => {
    const b = new Uint8Array(total);
    b.set(enc(magic));
    new DataView(b.buffer).setInt32(4, count, true);
    new DataView(b.buffer).setInt32(8, offset, true);
    return b;
  };

  it.each([
    ['too short', new Uint8Array(5), /only 5 bytes/],
    ['bad magic', header('PK\x03\x04', 0, 12), /not a WAD file/],
    ['negative count', header('IWAD', -1, 12), /negative lump count/],
    ['negative directory offset', header('PWAD', 0, -5), /negative directory offset/],
    ['huge count', header('PWAD', 0x7fffffff, 12), /directory .* runs past the end/],
    ['directory past the end', header('PWAD', 1, 8, 20), /runs past the end/],
  ])('refuses a %s with a LanternError naming the file', (_, bytes, message) => {
    const err = (() => {
      try {
        readWad(bytes, 'bad.wad');
      } catch (e) {
        return e;
      }
    })();
    expect(err).toBeInstanceOf(LanternError);
    expect((err as Error).message).toMatch(message);
    expect((err as Error).message).toContain('bad.wad');
  });

  it('refuses lump data past the end, naming the lump', () => {
    const bytes = new WadBuilder().lump('FIRST', bytesOf(1)).lump('SECOND', bytesOf(1, 2, 3)).build();
    const dir = new DataView(bytes.buffer).getInt32(8, true);
    new DataView(bytes.buffer).setInt32(dir + 16 + 4, 1000, true); // SECOND's size
    expect(() => readWad(bytes, 'bad.wad')).toThrow(/lump 1 \(SECOND, 1000 bytes at offset \d+\) lies outside/);
    new DataView(bytes.buffer).setInt32(dir + 16 + 4, -3, true);
    expect(() => readWad(bytes, 'bad.wad')).toThrow(/negative size/);
  });

  it('accepts empty marker lumps whatever their offset', () => {
    const bytes = new WadBuilder().marker('S_START').build();
    new DataView(bytes.buffer).setInt32(12, 999999, true);
    expect(readWad(bytes, 'ok.wad').lumps[0]).toMatchObject({ name: 'S_START', size: 0 });
  });
});

describe('WadStack', () => {
  const iwad = readWad(
    new WadBuilder()
      .lump('PLAYPAL', bytesOf(1))
      .lump('COLORMAP', bytesOf(2))
      .marker('F_START')
      .marker('F1_START')
      .lump('FLOOR1', encodeFlat(1))
      .lump('FLOOR2', encodeFlat(2))
      .marker('F1_END')
      .marker('F_END')
      .marker('P_START')
      .lump('WALL1', bytesOf(3))
      .marker('P_END')
      .marker('S_START')
      .lump('TROOA1', bytesOf(4))
      .marker('S_END')
      .lumps(encodeMap(squareRoom('MAP01')))
      .lumps(encodeMap(squareRoom('MAP02')))
      .build('IWAD'),
    'iwad.wad',
  );
  const pwad = readWad(
    new WadBuilder()
      .lump('COLORMAP', bytesOf(20))
      .marker('FF_START')
      .lump('FLOOR2', encodeFlat(22))
      .lump('FLOOR3', encodeFlat(23))
      .marker('F_END')
      .lump('WALL1', bytesOf(30)) // a vanilla-style patch replacement, no markers
      .lumps(encodeMap(squareRoom('MAP02', 512)))
      .lumps(encodeMap(squareRoom('MYMAP')))
      .build('PWAD'),
    'pwad.wad',
  );
  const stack = new WadStack([iwad, pwad]);

  it('finds lumps with the last file winning', () => {
    expect([...stack.lump('colormap')!]).toEqual([20]);
    expect([...stack.lump('PLAYPAL')!]).toEqual([1]);
    expect(stack.lump('NOPE')).toBeUndefined();
  });

  it('merges namespaces across files, nested and doubled markers included', () => {
    const flats = stack.namespace('flats');
    expect([...flats.keys()]).toEqual(['FLOOR1', 'FLOOR2', 'FLOOR3']);
    expect(flats.get('FLOOR2')!.file.name).toBe('pwad.wad');
    expect(flats.get('FLOOR1')!.file.name).toBe('iwad.wad');
    expect([...stack.namespace('patches').keys()]).toEqual(['WALL1']);
    expect([...stack.namespace('sprites').keys()]).toEqual(['TROOA1']);
  });

  it('finds patches the vanilla way: a later file without markers wins', () => {
    expect(stack.patch('wall1')!.file.name).toBe('pwad.wad');
    expect(new WadStack([iwad]).patch('WALL1')!.file.name).toBe('iwad.wad');
    // A flat is not a patch, even though a global lookup would find it; a sprite can serve as one.
    expect(stack.patch('FLOOR3')).toBeUndefined();
    expect(stack.patch('TROOA1')!.lump.name).toBe('TROOA1');
  });

  it('discovers maps, the PWAD replacing the IWAD map of the same name, PWAD maps first', () => {
    expect(stack.maps()).toEqual([
      { name: 'MAP02', format: 'doom', file: 'pwad.wad' },
      { name: 'MYMAP', format: 'doom', file: 'pwad.wad' },
      { name: 'MAP01', format: 'doom', file: 'iwad.wad' },
    ]);
    const map02 = stack.mapLumps('map02')!;
    expect(map02.info.file).toBe('pwad.wad');
    // The lumps come from the marker's file: the 512-unit room.
    expect(new DataView(map02.lump('VERTEXES')!.slice().buffer).getInt16(6, true)).toBe(512);
    expect(stack.mapLumps('MAP03')).toBeUndefined();
    expect(new WadStack([iwad]).maps().map((m) => m.name)).toEqual(['MAP01', 'MAP02']);
  });

  it('recognises Hexen (BEHAVIOR) and UDMF (TEXTMAP ... ENDMAP) maps', () => {
    const hexenLumps = encodeMap(squareRoom('MAP03'));
    hexenLumps.push(['BEHAVIOR', bytesOf(0x41, 0x43, 0x53, 0)]);
    const wad = readWad(
      new WadBuilder()
        .lumps(hexenLumps)
        .marker('MAP04')
        .lump('TEXTMAP', enc('namespace = "zdoom";'))
        .lump('ZNODES', bytesOf(1))
        .marker('ENDMAP')
        .lumps(encodeMap(squareRoom('E1M1')))
        .marker('GL_E1M1') // GL nodes: a marker followed by GL_VERT, not a map
        .lump('GL_VERT', bytesOf(1))
        .build(),
      'mixed.wad',
    );
    expect(new WadStack([wad]).maps()).toEqual([
      { name: 'MAP03', format: 'hexen', file: 'mixed.wad' },
      { name: 'MAP04', format: 'udmf', file: 'mixed.wad' },
      { name: 'E1M1', format: 'doom', file: 'mixed.wad' },
    ]);
  });

  it('handles an empty stack', () => {
    const empty = new WadStack([]);
    expect(empty.maps()).toEqual([]);
    expect(empty.lump('X')).toBeUndefined();
    expect(empty.describe()).toBe('(no WAD files)');
  });
});
