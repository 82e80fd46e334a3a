import { describe, expect, it } from 'vitest';
import { LINEDEF_FLAGS, NO_SIDEDEF, SKY_FLAT, type DoomMap, type Sector, type Sidedef } from './map-types.ts';
import { buildWalls, type TextureSize, type WallQuad } from './walls.ts';

const SIZES: Record<string, TextureSize> = {
  WALL: { width: 64, height: 72 },
  UPPER: { width: 128, height: 72 },
  LOWER: { width: 32, height: 72 },
  MID: { width: 32, height: 72 },
  TALLMID: { width: 64, height: 128 },
};
const sizeOf = (name: string) => SIZES[name];

const LENGTH = 200;

function sector(props: Partial<Sector> = {}): Sector {
  return { floorHeight: 0, ceilingHeight: 210, floorFlat: 'FLOOR4_8', ceilingFlat: 'CEIL3_5', lightLevel: 160, special: 0, tag: 0, ...props };
}
function side(sectorIndex: number, props: Partial<Sidedef> = {}): Sidedef {
  return { xOffset: 0, yOffset: 0, upper: 'UPPER', lower: 'LOWER', middle: '-', sector: sectorIndex, ...props };
}

/**
 * One line from (0, 0) to (LENGTH, 0), running east: its front side faces south into sector 0, its
 * back side (if `back` is given) north into sector 1.
 */
function lineMap(front: { sector?: Partial<Sector>; side?: Partial<Sidedef> }, back?: { sector?: Partial<Sector>; side?: Partial<Sidedef> }, flags = 0): DoomMap {
  const sectors = [sector(front.sector), ...(back ? [sector(back.sector)] : [])];
  const sidedefs = [side(0, back ? front.side : { middle: 'WALL', ...front.side }), ...(back ? [side(1, back.side)] : [])];
  return {
    name: 'TEST',
    vertices: [{ x: 0, y: 0 }, { x: LENGTH, y: 0 }],
    linedefs: [{ v1: 0, v2: 1, flags: flags | (back ? LINEDEF_FLAGS.TWO_SIDED : 0), special: 0, tag: 0, front: 0, back: back ? 1 : NO_SIDEDEF }],
    sidedefs,
    sectors,
    things: [],
  };
}

function walls(map: DoomMap) {
  const warnings: string[] = [];
  const quads = buildWalls(map, sizeOf, (w) => warnings.push(w));
  const find = (side: 'front' | 'back', section: WallQuad['section']) => quads.filter((q) => q.side === side && q.section === section);
  const one = (side: 'front' | 'back', section: WallQuad['section']) => {
    const found = find(side, section);
    expect(found).toHaveLength(1);
    return found[0]!;
  };
  return { quads, warnings, find, one };
}

const mod = (a: number, n: number) => ((a % n) + n) % n;

/** The texel row the quad shows at height h (unwrapped: any whole number of repeats may differ). */
function rowAt(q: WallQuad, h: number, height: number): number {
  return (q.vTop + ((q.vBottom - q.vTop) * (q.top - h)) / (q.top - q.bottom)) * height;
}
/** The quad shows texel row `row` (mod the texture height) at height h, one row per map unit. */
function expectRow(q: WallQuad, size: TextureSize, h: number, row: number): void {
  expect(mod(rowAt(q, h, size.height) - row + 1e-9, size.height)).toBeCloseTo(0, 6);
  expect((q.vBottom - q.vTop) * size.height).toBeCloseTo(q.top - q.bottom, 9);
}
/** The quad shows texel column `column` (mod the width) at distance d from its start vertex. */
function expectColumn(q: WallQuad, size: TextureSize, d: number, column: number): void {
  const u = q.u0 + ((q.u1 - q.u0) * d) / LENGTH;
  expect(mod(u * size.width - column + 1e-9, size.width)).toBeCloseTo(0, 6);
  expect((q.u1 - q.u0) * size.width).toBeCloseTo(LENGTH, 9);
}

describe('buildWalls', () => {
  describe('one-sided middle', () => {
    const map = (flags = 0, xOffset = 0, yOffset = 0) => lineMap({ sector: { floorHeight: 8, ceilingHeight: 136 }, side: { xOffset, yOffset } }, undefined, flags);

    it('spans floor to ceiling, its top at the ceiling', () => {
      const q = walls(map()).one('front', 'middle');
      expect([q.bottom, q.top]).toEqual([8, 136]);
      expect(q.surface).toEqual({ kind: 'texture', name: 'WALL' });
      expectRow(q, SIZES.WALL!, 136, 0);
      expectRow(q, SIZES.WALL!, 8, 128);
    });

    it('with lower unpegged, has its bottom at the floor', () => {
      const q = walls(map(LINEDEF_FLAGS.LOWER_UNPEGGED)).one('front', 'middle');
      expectRow(q, SIZES.WALL!, 8, 72); // row 71 ends at the floor
      expectRow(q, SIZES.WALL!, 136, 72 - 128);
    });

    it('adds the x offset to u and the y offset to v', () => {
      const q = walls(map(0, 10, 5)).one('front', 'middle');
      expectColumn(q, SIZES.WALL!, 0, 10);
      expectColumn(q, SIZES.WALL!, LENGTH, 10 + LENGTH);
      expectRow(q, SIZES.WALL!, 136, 5);
      const unpegged = walls(map(LINEDEF_FLAGS.LOWER_UNPEGGED, 10, 5)).one('front', 'middle');
      expectRow(unpegged, SIZES.WALL!, 8, 72 + 5);
    });

    it('runs from v1 to v2 with its sector on the right', () => {
      const q = walls(map()).one('front', 'middle');
      expect([q.x0, q.y0, q.x1, q.y1]).toEqual([0, 0, LENGTH, 0]);
      expect(q.sector).toBe(0);
    });
  });

  describe('two-sided', () => {
    // Front sector: floor 0, ceiling 210. Back: floor 40, ceiling 150: upper 150–210 and lower
    // 0–40 on the front side, nothing but a possible masked middle on the back.
    const step = (flags = 0, frontSide: Partial<Sidedef> = {}, backSide: Partial<Sidedef> = {}) =>
      lineMap({ side: frontSide }, { sector: { floorHeight: 40, ceilingHeight: 150 }, side: backSide }, flags);

    it('has sections as high as the sectors differ, on the side facing the step', () => {
      const { quads, one } = walls(step());
      expect([one('front', 'upper').bottom, one('front', 'upper').top]).toEqual([150, 210]);
      expect([one('front', 'lower').bottom, one('front', 'lower').top]).toEqual([0, 40]);
      expect(quads.filter((q) => q.side === 'back')).toEqual([]);
    });

    it('pegs the upper texture to the lower ceiling, or with upper unpegged to its own ceiling', () => {
      const pegged = walls(step(0, { yOffset: 3 })).one('front', 'upper');
      expectRow(pegged, SIZES.UPPER!, 150, 72 + 3); // its last row ends at the other ceiling
      expectRow(pegged, SIZES.UPPER!, 210, 72 - 60 + 3);
      const unpegged = walls(step(LINEDEF_FLAGS.UPPER_UNPEGGED, { yOffset: 3 })).one('front', 'upper');
      expectRow(unpegged, SIZES.UPPER!, 210, 3);
    });

    it('pegs the lower texture to the higher floor, or with lower unpegged to its own ceiling', () => {
      const pegged = walls(step(0, { yOffset: 3 })).one('front', 'lower');
      expectRow(pegged, SIZES.LOWER!, 40, 3);
      expectRow(pegged, SIZES.LOWER!, 0, 43);
      const unpegged = walls(step(LINEDEF_FLAGS.LOWER_UNPEGGED, { yOffset: 3 })).one('front', 'lower');
      expectRow(unpegged, SIZES.LOWER!, 40, 210 - 40 + 3); // as if the texture started at the ceiling
    });

    it('gives every section of a side the same u: distance from the start vertex plus x offset', () => {
      const { one } = walls(step(0, { xOffset: 7 }));
      for (const [q, size] of [[one('front', 'upper'), SIZES.UPPER!], [one('front', 'lower'), SIZES.LOWER!]] as const) {
        expectColumn(q, size, 0, 7);
        expectColumn(q, size, 50, 57);
      }
    });

    it('starts the back side at v2, with its own x offset, facing the back sector', () => {
      // Swap the sectors so the back side has the sections.
      const map = lineMap({ sector: { floorHeight: 40, ceilingHeight: 150 } }, { side: { xOffset: 5 } });
      const { quads, one } = walls(map);
      const upper = one('back', 'upper');
      expect([upper.x0, upper.y0, upper.x1, upper.y1]).toEqual([LENGTH, 0, 0, 0]);
      expect(upper.sector).toBe(1);
      expectColumn(upper, SIZES.UPPER!, 0, 5);
      expect(quads.filter((q) => q.side === 'front')).toEqual([]);
    });

    it('keeps every quad facing its own sector: the sector lies right of start → end', () => {
      const map = lineMap({ side: { middle: 'MID' } }, { sector: { floorHeight: 40, ceilingHeight: 150 }, side: { middle: 'MID' } });
      for (const q of walls(map).quads) {
        const inside = q.sector === 0 ? [LENGTH / 2, -10] : [LENGTH / 2, 10];
        const cross = (q.x1 - q.x0) * (inside[1]! - q.y0) - (q.y1 - q.y0) * (inside[0]! - q.x0);
        expect(cross).toBeLessThan(0);
      }
    });

    it('clips an upper section to the floor of its own sector (a closed door)', () => {
      const map = lineMap({}, { sector: { floorHeight: 0, ceilingHeight: 0 } });
      const { one } = walls(map);
      expect([one('front', 'upper').bottom, one('front', 'upper').top]).toEqual([0, 210]);
    });
  });

  describe('masked middle', () => {
    // Opening between the sectors: 40 (higher floor) to 150 (lower ceiling).
    const masked = (flags: number, middle: string, yOffset = 0) =>
      walls(lineMap({ side: { middle, yOffset } }, { sector: { floorHeight: 40, ceilingHeight: 150 } }, flags)).one('front', 'masked');

    it('hangs once from the lower ceiling, not tiled', () => {
      const q = masked(0, 'MID');
      expect([q.bottom, q.top]).toEqual([150 - 72, 150]);
      expect([q.vTop, q.vBottom]).toEqual([0, 1]);
      expect(q.surface).toEqual({ kind: 'texture', name: 'MID' });
    });

    it('with lower unpegged, stands on the higher floor', () => {
      const q = masked(LINEDEF_FLAGS.LOWER_UNPEGGED, 'MID');
      expect([q.bottom, q.top]).toEqual([40, 40 + 72]);
      expect([q.vTop, q.vBottom]).toEqual([0, 1]);
    });

    it('moves with the y offset and is clipped to the opening', () => {
      const q = masked(0, 'MID', 20); // texture from 170 down to 98: its top 20 rows are above the opening
      expect([q.bottom, q.top]).toEqual([98, 150]);
      expect(q.vTop).toBeCloseTo(20 / 72, 12);
      expect(q.vBottom).toBeCloseTo(1, 12);
      const tall = masked(0, 'TALLMID'); // 128 rows in a 110-unit opening
      expect([tall.bottom, tall.top]).toEqual([40, 150]);
      expect([tall.vTop, tall.vBottom]).toEqual([0, 110 / 128]);
    });

    it('is left out, with a warning, when the WAD lacks its texture', () => {
      const { quads, warnings } = walls(lineMap({ side: { middle: 'NOSUCH' } }, { sector: { floorHeight: 40, ceilingHeight: 150 } }));
      expect(quads.filter((q) => q.section === 'masked')).toEqual([]);
      expect(warnings).toEqual(['texture NOSUCH is not in the WAD (one wall section, linedef 0 (front) masked middle); left out']);
    });
  });

  describe('sky', () => {
    const sky = (ceilingHeight: number) => ({ ceilingHeight, ceilingFlat: SKY_FLAT });

    it('draws no upper texture between two sky ceilings, but closes the gap with sky on the higher side', () => {
      const { quads, one } = walls(lineMap({ sector: sky(210) }, { sector: sky(150) }));
      expect(quads.filter((q) => q.surface.kind === 'texture' && q.section === 'upper')).toEqual([]);
      const gap = one('front', 'upper');
      expect(gap.surface).toEqual({ kind: 'sky' });
      expect([gap.bottom, gap.top]).toEqual([150, 210]);
      expect(quads.filter((q) => q.side === 'back')).toEqual([]);
    });

    it('draws nothing above between two sky ceilings at one height', () => {
      expect(walls(lineMap({ sector: sky(210) }, { sector: sky(210) })).quads).toEqual([]);
    });

    it('aligns a lower-unpegged lower texture to the other ceiling under the sky hack', () => {
      const q = walls(lineMap({ sector: sky(210) }, { sector: { ...sky(150), floorHeight: 40 } }, LINEDEF_FLAGS.LOWER_UNPEGGED)).one('front', 'lower');
      expectRow(q, SIZES.LOWER!, 40, 150 - 40);
    });

    it('draws the upper texture of a sky sector above a lower roof, and sky where it has none', () => {
      const textured = walls(lineMap({ sector: sky(210) }, { sector: { ceilingHeight: 150 } })).one('front', 'upper');
      expect(textured.surface).toEqual({ kind: 'texture', name: 'UPPER' });
      const bare = walls(lineMap({ sector: sky(210), side: { upper: '-' } }, { sector: { ceilingHeight: 150 } }));
      expect(bare.one('front', 'upper').surface).toEqual({ kind: 'sky' });
      expect(bare.warnings).toEqual([]);
    });

    it('shows the sky through an upper section with no texture below a sky ceiling', () => {
      const { one, warnings } = walls(lineMap({ side: { upper: '-' } }, { sector: sky(150) }));
      expect(one('front', 'upper').surface).toEqual({ kind: 'sky' });
      expect(warnings).toEqual([]);
    });
  });

  describe('missing textures', () => {
    it('still emits a section that needs a texture, and warns once per name with a count', () => {
      const map = lineMap({ side: { middle: '-' } });
      const twice: DoomMap = { ...map, linedefs: [map.linedefs[0]!, { ...map.linedefs[0]!, v1: 1, v2: 0 }] };
      const { quads, warnings } = walls(twice);
      expect(quads.map((q) => q.surface)).toEqual([{ kind: 'missing', name: '-' }, { kind: 'missing', name: '-' }]);
      expect(warnings).toEqual(['2 wall sections, the first linedef 0 (front) middle, need a texture but name none; drawn with a plain material']);
    });

    it('names a texture the WAD lacks', () => {
      const { one, warnings } = walls(lineMap({ side: { lower: 'NOSUCH' } }, { sector: { floorHeight: 40, ceilingHeight: 150 } }));
      expect(one('front', 'lower').surface).toEqual({ kind: 'missing', name: 'NOSUCH' });
      expect([one('front', 'lower').bottom, one('front', 'lower').top]).toEqual([0, 40]);
      expect(warnings).toEqual(['texture NOSUCH is not in the WAD (one wall section, linedef 0 (front) lower); drawn with a plain material']);
    });
  });
});
