import { describe, expect, it } from 'vitest';
import { LINEDEF_FLAGS, type DoomMap, type Sector } from '../loaders/doom/map-types.ts';
import { MapBuilder } from '../loaders/doom/test-wad.ts';
import { doomWalkMap, PLAYER_RADIUS } from '../loaders/doom/walk-map.ts';
import { eyeLevel, moveWalker, NO_SECTOR, sectorAt, type WalkPosition } from './walk-map.ts';

/**
 * Two 256-unit rooms side by side on the map: A (x 0..256) and B (x 256..512), y 0..256, joined by
 * a two-sided line at x = 256. Room A has floor 0 and ceiling 128; room B's sector is `b`.
 * World coordinates are (x, height, −y), so both rooms lie at z in [−256, 0].
 */
function twoRooms(b: Partial<Sector>, sharedFlags = 0): DoomMap {
  const m = new MapBuilder();
  const a = m.sector(), bb = m.sector(b);
  // Clockwise, so front (right) sides face into each room; the shared line's front faces room A.
  m.line([0, 0], [0, 256], a);
  m.line([0, 256], [256, 256], a);
  m.line([256, 0], [0, 0], a);
  m.line([256, 256], [256, 0], a, bb, {}, sharedFlags);
  m.line([256, 256], [512, 256], bb);
  m.line([512, 256], [512, 0], bb);
  m.line([512, 0], [256, 0], bb);
  return m.build();
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
