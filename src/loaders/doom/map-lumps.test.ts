import { describe, expect, it } from 'vitest';
import { LanternError } from '../../errors.ts';
import { readMap } from './map-lumps.ts';
import { NO_SIDEDEF, type DoomMap } from './map-types.ts';
import { encodeMap, squareRoom, WadBuilder } from './test-wad.ts';
import { readWad, WadStack } from './wad.ts';

const stackOf = (...wads: Array<[string, Uint8Array]>) => new WadStack(wads.map(([name, bytes]) => readWad(bytes, name)));
const wadWith = (...maps: DoomMap[]) => new WadBuilder().lumps(maps.flatMap(encodeMap)).build('IWAD');

/** A room with a two-sided line across it, negative coordinates, and odd field values. */
function twoRooms(): DoomMap {
  const room = squareRoom('E1M1');
  return {
    ...room,
    vertices: [...room.vertices, { x: -32768, y: 32767 }, { x: 128, y: -5 }],
    linedefs: [
      ...room.linedefs,
      { v1: 4, v2: 5, flags: 0x0004 | 0x0008 | 0x8000, special: 0x7fff, tag: 65535, front: 4, back: 5 },
    ],
    sidedefs: [
      ...room.sidedefs,
      { xOffset: -8, yOffset: 16, upper: 'BIGDOOR2', lower: 'STEP6', middle: '-', sector: 0 },
      { xOffset: 0, yOffset: 0, upper: 'A', lower: '', middle: 'MIDGRATE', sector: 1 },
    ],
    sectors: [...room.sectors, { floorHeight: -24, ceilingHeight: 72, floorFlat: 'NUKAGE1', ceilingFlat: 'F_SKY1', lightLevel: 255, special: 0x1234, tag: 7 }],
    things: [...room.things, { x: -100, y: 100, angle: 270, type: 3004, flags: 0x0f }],
  };
}

describe('readMap', () => {
  it('round-trips every field through the lumps', () => {
    const map = twoRooms();
    expect(readMap(stackOf(['doom.wad', wadWith(map)]), 'e1m1')).toEqual(map);
  });

  it('reads the map from the PWAD that replaces it', () => {
    const stack = stackOf(['iwad.wad', wadWith(squareRoom('MAP01', 256))], ['pwad.wad', new WadBuilder().lumps(encodeMap(squareRoom('MAP01', 1024))).build()]);
    expect(readMap(stack, 'MAP01').vertices[2]).toEqual({ x: 1024, y: 1024 });
  });

  it('refuses a missing map, listing the maps there are', () => {
    const stack = stackOf(['doom.wad', wadWith(squareRoom('E1M1'), squareRoom('E1M2'))]);
    try {
      readMap(stack, 'E2M1');
      expect.unreachable();
    } catch (e) {
      expect(e).toBeInstanceOf(LanternError);
      expect((e as LanternError).userMessage).toBe('there is no map E2M1 in doom.wad. Its maps are E1M1, E1M2');
    }
    expect(() => readMap(stackOf(['empty.wad', new WadBuilder().lump('X', new Uint8Array(1)).build()]), 'MAP01')).toThrow(/contains no maps/);
  });

  it('refuses Hexen and UDMF maps with a clear message', () => {
    const bytes = new WadBuilder()
      .lumps(encodeMap(squareRoom('MAP01')))
      .lump('BEHAVIOR', new Uint8Array(16))
      .marker('MAP02')
      .lump('TEXTMAP', new TextEncoder().encode('namespace = "doom";'))
      .marker('ENDMAP')
      .build();
    const stack = stackOf(['foo.wad', bytes]);
    expect(() => readMap(stack, 'MAP01')).toThrow(new LanternError('MAP01 in foo.wad is a Hexen-format map; Lantern reads Doom-format maps only'));
    expect(() => readMap(stack, 'MAP02')).toThrow(/MAP02 in foo.wad is a UDMF \(text\) map; Lantern reads Doom-format maps only/);
  });

  it('refuses a lump that is not a whole number of records, naming it', () => {
    const lumps = encodeMap(squareRoom('MAP01'));
    lumps[2] = ['LINEDEFS', new Uint8Array(15)];
    expect(() => readMap(stackOf(['bad.wad', new WadBuilder().lumps(lumps).build()]), 'MAP01')).toThrow(
      /MAP01 in bad.wad: the LINEDEFS lump is 15 bytes, not a whole number of 14-byte records/,
    );
  });

  it('refuses a map without SECTORS', () => {
    const lumps = encodeMap(squareRoom('MAP01')).filter(([n]) => n !== 'SECTORS');
    expect(() => readMap(stackOf(['bad.wad', new WadBuilder().lumps(lumps).build()]), 'MAP01')).toThrow(/has no SECTORS lump/);
  });

  it('drops linedefs with broken references, warning, and renumbers sidedefs', () => {
    const room = squareRoom('MAP01');
    const map: DoomMap = {
      ...room,
      sidedefs: [{ ...room.sidedefs[0]!, sector: 9 }, ...room.sidedefs.slice(1), { ...room.sidedefs[1]!, middle: 'LAST' }],
      linedefs: [
        ...room.linedefs, // line 0 uses sidedef 0, whose sector is bad
        { ...room.linedefs[1]!, v2: 99 },
        { ...room.linedefs[1]!, back: 77 },
        { ...room.linedefs[1]!, front: 4 },
      ],
    };
    const warnings: string[] = [];
    const read = readMap(stackOf(['pwad.wad', wadWith(map)]), 'MAP01', { onWarning: (w) => warnings.push(w) });
    expect(warnings).toEqual([
      'MAP01 in pwad.wad: removed 1 sidedef(s) whose sector index is out of range (the map has 1 sectors)',
      'MAP01 in pwad.wad: dropped linedef 0: its front sidedef 0 has a bad sector',
      'MAP01 in pwad.wad: dropped linedef 4: vertex 99 does not exist (the map has 4)',
      'MAP01 in pwad.wad: dropped linedef 5: its back sidedef 77 does not exist (the map has 5)',
    ]);
    expect(read.sidedefs).toHaveLength(4);
    // Lines 1..3 and 6 survive, their sidedefs renumbered down by one.
    expect(read.linedefs.map((l) => [l.front, l.back])).toEqual([[0, NO_SIDEDEF], [1, NO_SIDEDEF], [2, NO_SIDEDEF], [3, NO_SIDEDEF]]);
    expect(read.sidedefs[3]!.middle).toBe('LAST');
  });

  it('clamps light levels like the game and refuses a map left with no lines', () => {
    const room = squareRoom('MAP01');
    const lit = (lightLevel: number) => ({ ...room, sectors: [{ ...room.sectors[0]!, lightLevel }] });
    expect(readMap(stackOf(['x.wad', wadWith(lit(256))]), 'MAP01').sectors[0]!.lightLevel).toBe(255);
    expect(readMap(stackOf(['x.wad', wadWith(lit(-16))]), 'MAP01').sectors[0]!.lightLevel).toBe(0);
    const broken = { ...room, vertices: [] };
    expect(() => readMap(stackOf(['x.wad', wadWith(broken)]), 'MAP01')).toThrow(/MAP01 in x.wad has no usable linedefs/);
  });
});
