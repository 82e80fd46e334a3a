import { describe, expect, it } from 'vitest';
import { LINEDEF_FLAGS, NO_SIDEDEF, type DoomMap, type Linedef, type Sector, type Sidedef } from '../loaders/doom/map-types.ts';
import { doomWalkMap, PLAYER_RADIUS } from '../loaders/doom/walk-map.ts';
import { eyeLevel, moveWalker, NO_SECTOR, sectorAt, type WalkPosition } from './walk-map.ts';

/**
 * Two 256-unit rooms side by side on the map: A (x 0..256) and B (x 256..512), y 0..256, joined by
 * a two-sided line at x = 256. Room A has floor 0 and ceiling 128; room B's sector is `b`.
 * World coordinates are (x, height, −y), so both rooms lie at z in [−256, 0].
 */
function twoRooms(b: Partial<Sector>, sharedFlags = 0): DoomMap {
  const vertices = [
    { x: 0, y: 0 }, { x: 0, y: 256 }, { x: 256, y: 256 }, { x: 256, y: 0 }, { x: 512, y: 256 }, { x: 512, y: 0 },
  ];
  const sector = (s: Partial<Sector>): Sector => ({ floorHeight: 0, ceilingHeight: 128, floorFlat: 'F', ceilingFlat: 'C', lightLevel: 160, special: 0, tag: 0, ...s });
  const side = (s: number): Sidedef => ({ xOffset: 0, yOffset: 0, upper: '-', lower: '-', middle: '-', sector: s });
  const line = (v1: number, v2: number, front: number, back: number = NO_SIDEDEF, flags: number = LINEDEF_FLAGS.BLOCKING): Linedef => ({ v1, v2, flags, special: 0, tag: 0, front, back });
  // Clockwise loops, so front (right) sides face into each room.
  const linedefs = [
    line(0, 1, 0), line(1, 2, 1), line(3, 0, 2),
    line(2, 3, 3, 4, LINEDEF_FLAGS.TWO_SIDED | sharedFlags),
    line(2, 4, 5), line(4, 5, 6), line(5, 3, 7),
  ];
  const sidedefs = [side(0), side(0), side(0), side(0), side(1), side(1), side(1), side(1)];
  return { name: 'TEST', vertices, linedefs, sidedefs, sectors: [sector({}), sector(b)], things: [] };
}

const start = (map: ReturnType<typeof doomWalkMap>, x: number, z: number): WalkPosition => ({ x, z, sector: sectorAt(map, x, z) });

describe('walk map', () => {
  it('finds the sector under a point, and none outside the map', () => {
    const map = doomWalkMap(twoRooms({}));
    expect(sectorAt(map, 100, -100)).toBe(0);
    expect(sectorAt(map, 400, -200)).toBe(1);
    expect(sectorAt(map, -10, -100)).toBe(NO_SECTOR);
    expect(sectorAt(map, 600, -100)).toBe(NO_SECTOR);
    expect(sectorAt(map, 100, 10)).toBe(NO_SECTOR);
  });

  it('climbs a 16-unit step and puts the eye 41 units above the new floor', () => {
    const map = doomWalkMap(twoRooms({ floorHeight: 16 }));
    let at = start(map, 200, -128);
    for (let i = 0; i < 10; i++) at = moveWalker(map, at, 20, 0);
    expect(at.x).toBeCloseTo(400, 3);
    expect(at.sector).toBe(1);
    expect(eyeLevel(map, at.sector)).toBe(57);
  });

  it('is stopped by a 32-unit step, a low opening and an impassable line, one radius short of the line', () => {
    for (const map of [doomWalkMap(twoRooms({ floorHeight: 32 })), doomWalkMap(twoRooms({ ceilingHeight: 40 })), doomWalkMap(twoRooms({}, LINEDEF_FLAGS.BLOCKING))]) {
      let at = start(map, 200, -128);
      for (let i = 0; i < 10; i++) at = moveWalker(map, at, 20, 0);
      expect(at.sector).toBe(0);
      expect(at.x).toBeCloseTo(256 - PLAYER_RADIUS, 2);
      expect(at.z).toBeCloseTo(-128, 5);
    }
  });

  it('slides along a wall it walks into at an angle', () => {
    const map = doomWalkMap(twoRooms({}));
    // Toward the wall at map y = 0 (world z = 0) and east at once.
    let at = start(map, 100, -40);
    for (let i = 0; i < 10; i++) at = moveWalker(map, at, 10, 10);
    expect(at.z).toBeCloseTo(-PLAYER_RADIUS, 2);
    expect(at.x).toBeCloseTo(200, 3);
  });

  it('never passes through a wall, however large one move is', () => {
    const map = doomWalkMap(twoRooms({}));
    const at = moveWalker(map, start(map, 100, -128), -1000, 0);
    expect(at.sector).toBe(0);
    expect(at.x).toBeCloseTo(PLAYER_RADIUS, 2);
  });

  it('keeps the eye under a low ceiling', () => {
    const map = doomWalkMap(twoRooms({ ceilingHeight: 40 }));
    expect(eyeLevel(map, 1)).toBe(36);
    expect(eyeLevel(map, NO_SECTOR)).toBeUndefined();
  });
});
