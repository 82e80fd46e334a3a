import { describe, expect, it } from 'vitest';
import { ccw, cw, MapBuilder } from './test-wad.ts';
import { buildSectorShapes, GAP_TOLERANCE, ringArea, sectorAt, type SectorShape } from './sectors.ts';

function build(m: MapBuilder) {
  const warnings: string[] = [];
  const shapes = buildSectorShapes(m.build(), (w) => warnings.push(w));
  return { shapes, warnings, shape: (i: number) => shapes.shapes[i]! };
}

/** Every triangle counter-clockwise seen from above, and their areas summing to `shape.area`. */
function checkTriangles(shape: SectorShape): void {
  let sum = 0;
  for (let t = 0; t < shape.indices.length; t += 3) {
    const [a, b, c] = [0, 1, 2].map((k) => 2 * shape.indices[t + k]!) as [number, number, number];
    const v = shape.vertices;
    const twice = (v[b]! - v[a]!) * (v[c + 1]! - v[a + 1]!) - (v[b + 1]! - v[a + 1]!) * (v[c]! - v[a]!);
    expect(twice).toBeGreaterThan(0);
    sum += twice / 2;
  }
  expect(sum).toBeCloseTo(shape.area, 6);
}

describe('buildSectorShapes', () => {
  it('cuts a pillar out of a room', () => {
    const m = new MapBuilder();
    const room = m.sector();
    m.loop(cw(0, 0, 256), room);
    m.loop(ccw(96, 96, 64), room); // one-sided pillar faces, facing the room
    const { shapes, warnings, shape } = build(m);
    expect(warnings).toEqual([]);
    expect(shapes.failures).toEqual([]);
    expect(shape(room).area).toBe(256 * 256 - 64 * 64);
    expect(shape(room).polygons).toHaveLength(1);
    expect(shape(room).polygons[0]!.holes).toHaveLength(1);
    expect(ringArea(shape(room).polygons[0]!.outer)).toBe(256 * 256);
    expect(ringArea(shape(room).polygons[0]!.holes[0]!)).toBe(-64 * 64);
    checkTriangles(shape(room));
    expect(sectorAt(shapes, 10, 10)).toBe(room);
    expect(sectorAt(shapes, 128, 128)).toBeUndefined();
  });

  it('builds a platform inside a room as its own sector and removes it from the room', () => {
    const m = new MapBuilder();
    const room = m.sector();
    const platform = m.sector({ floorHeight: 32 });
    m.loop(cw(0, 0, 256), room);
    m.loop(cw(64, 64, 128), platform, room); // front (inside) the platform, back the room
    const { shapes, warnings, shape } = build(m);
    expect(warnings).toEqual([]);
    expect(shapes.failures).toEqual([]);
    expect(shape(room).area).toBe(256 * 256 - 128 * 128);
    expect(shape(platform).area).toBe(128 * 128);
    checkTriangles(shape(room));
    checkTriangles(shape(platform));
    expect(sectorAt(shapes, 128, 128)).toBe(platform);
    expect(sectorAt(shapes, 32, 128)).toBe(room);
  });

  it('assigns each hole to the smallest boundary around it, with the same sector again inside a pillar', () => {
    const m = new MapBuilder();
    const room = m.sector();
    m.loop(cw(0, 0, 512), room);
    m.loop(ccw(128, 128, 256), room); // a hollow pillar ...
    m.loop(cw(192, 192, 128), room); // ... whose inside is the room's sector again
    m.loop(ccw(240, 240, 32), room); // with a pillar of its own
    const { shapes, warnings, shape } = build(m);
    expect(warnings).toEqual([]);
    expect(shapes.failures).toEqual([]);
    const polygons = shape(room).polygons;
    expect(polygons).toHaveLength(2);
    expect(polygons.map((p) => [ringArea(p.outer), p.holes.map(ringArea)])).toEqual(
      expect.arrayContaining([[512 * 512, [-256 * 256]], [128 * 128, [-32 * 32]]]),
    );
    expect(shape(room).area).toBe(512 * 512 - 256 * 256 + 128 * 128 - 32 * 32);
    checkTriangles(shape(room));
  });

  it('builds a sector of two disjoint pieces, also where they touch at a corner', () => {
    const m = new MapBuilder();
    const a = m.sector();
    const b = m.sector();
    m.loop(cw(0, 0, 128), a);
    m.loop(cw(512, 0, 64), a);
    m.loop(cw(0, 512, 64), b);
    m.loop(cw(64, 576, 64), b); // touches the first square of b at (64, 576)
    const { shapes, warnings, shape } = build(m);
    expect(warnings).toEqual([]);
    expect(shapes.failures).toEqual([]);
    expect(shape(a).polygons).toHaveLength(2);
    expect(shape(a).area).toBe(128 * 128 + 64 * 64);
    expect(shape(b).polygons).toHaveLength(2);
    expect(shape(b).polygons.every((p) => ringArea(p.outer) === 64 * 64)).toBe(true);
    expect(shape(b).area).toBe(2 * 64 * 64);
    checkTriangles(shape(a));
    checkTriangles(shape(b));
  });

  it('ignores self-referencing lines, which separate nothing', () => {
    const m = new MapBuilder();
    const room = m.sector();
    m.loop(cw(0, 0, 256), room);
    m.line([64, 64], [192, 192], room, room);
    m.loop(cw(32, 160, 32), room, room); // a self-referencing "sector" drawn inside the room
    const { shapes, warnings, shape } = build(m);
    expect(warnings).toEqual([]);
    expect(shapes.failures).toEqual([]);
    expect(shape(room).area).toBe(256 * 256);
  });

  it('leaves a sector no sidedef names empty, without failure', () => {
    const m = new MapBuilder();
    const room = m.sector();
    const unused = m.sector();
    m.loop(cw(0, 0, 256), room);
    const { shapes, shape } = build(m);
    expect(shapes.failures).toEqual([]);
    expect(shape(unused).area).toBe(0);
    expect(shape(unused).indices).toHaveLength(0);
  });

  describe('mapping errors', () => {
    it('closes a small gap between vertices that should have been one, with a warning', () => {
      const m = new MapBuilder();
      const room = m.sector();
      // Clockwise, but the last line ends 2 units short of the first vertex.
      m.line([0, 0], [0, 256], room);
      m.line([0, 256], [256, 256], room);
      m.line([256, 256], [256, 0], room);
      m.line([256, 0], [2, 0], room);
      const { shapes, warnings, shape } = build(m);
      expect(warnings).toEqual(['sector 0: unclosed boundary: joined (0, 0) to (2, 0) (a gap of 2 units)']);
      expect(shapes.failures).toEqual([]);
      expect(shape(room).area).toBe(256 * 256);
      checkTriangles(shape(room));
    });

    it('closes a boundary missing a whole line (a sidedef naming the wrong sector)', () => {
      const m = new MapBuilder();
      const room = m.sector();
      const other = m.sector();
      const [p0, p1, p2, p3] = cw(0, 0, 128);
      m.line(p0!, p1!, room);
      m.line(p1!, p2!, room);
      m.line(p2!, p3!, room);
      m.line(p3!, p0!, other); // should have been `room`
      const { shapes, warnings, shape } = build(m);
      expect(warnings).toContain('sector 0: unclosed boundary: joined (0, 0) to (128, 0) (a gap of 128 units)');
      expect(shapes.failures.map((f) => f.sector)).toEqual([other]); // one stray line encloses nothing
      expect(shape(room).area).toBe(128 * 128);
      checkTriangles(shape(room));
    });

    it('drops a dangling chain too far from anything to close, with a warning', () => {
      const m = new MapBuilder();
      const room = m.sector();
      m.loop(cw(0, 0, 256), room);
      m.line([1000, 0], [1000, 400], room);
      m.line([1000, 400], [1400, 400], room);
      const { shapes, warnings, shape } = build(m);
      expect(1400 - 1000).toBeGreaterThan(GAP_TOLERANCE);
      expect(warnings).toEqual(['sector 0: unclosed boundary: dropped dangling linedefs 4, 5']);
      expect(shapes.failures).toEqual([]);
      expect(shape(room).area).toBe(256 * 256);
    });

    it('uses a repeated line once and skips zero-length lines', () => {
      const m = new MapBuilder();
      const room = m.sector();
      m.loop(cw(0, 0, 256), room);
      m.line([0, 0], [0, 256], room); // the first line again
      m.line([50, 50], [50, 50], room);
      const { shapes, warnings, shape } = build(m);
      expect(warnings).toEqual(['sector 0: linedef 4 repeats linedef 0; using it once', 'linedef 5 has zero length; ignored']);
      expect(shapes.failures).toEqual([]);
      expect(shape(room).area).toBe(256 * 256);
    });

    it('merges vertices at the same spot', () => {
      // TestMap gives every line its own two vertices: merging by position is what closes the loops.
      const m = new MapBuilder();
      const room = m.sector();
      m.loop(cw(0, 0, 64), room);
      expect(m.vertices).toHaveLength(8);
      expect(build(m).shape(room).area).toBe(64 * 64);
    });

    it('flips a boundary drawn with its sidedefs on the wrong side', () => {
      const m = new MapBuilder();
      const room = m.sector();
      m.loop(ccw(0, 0, 128), room); // front sidedefs face out of the room
      const { shapes, warnings, shape } = build(m);
      expect(warnings).toEqual([expect.stringContaining('runs clockwise with nothing around it')]);
      expect(shapes.failures).toEqual([]);
      expect(shape(room).area).toBe(128 * 128);
      checkTriangles(shape(room));
    });
  });
});
