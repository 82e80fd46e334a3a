/**
 * A Doom map's floor plan as a WalkMap (scene/walk-map.ts), with the player's dimensions from the
 * Doom source: radius 16, height 56, steps up to 24 units, eye 41 units above the floor. Linedefs
 * with the impassable flag block whatever the heights (vanilla Doom's rule for players).
 */
import { toWorld } from './coordinates.ts';
import { EYE_HEIGHT, LINEDEF_FLAGS, NO_SIDEDEF, type DoomMap } from './map-types.ts';
import { NO_SECTOR, type WalkMap } from '../../scene/walk-map.ts';

export const PLAYER_RADIUS = 16;
export const PLAYER_HEIGHT = 56;
export const MAX_STEP_HEIGHT = 24;

export function doomWalkMap(map: DoomMap): WalkMap {
  const lines: number[] = [];
  const sectors: number[] = [];
  const blocks: number[] = [];
  const sectorOf = (side: number) => (side === NO_SIDEDEF ? NO_SECTOR : (map.sidedefs[side]?.sector ?? NO_SECTOR));
  for (const line of map.linedefs) {
    const a = map.vertices[line.v1], b = map.vertices[line.v2];
    if (!a || !b || (a.x === b.x && a.y === b.y)) continue;
    const [x0, , z0] = toWorld(a.x, a.y, 0);
    const [x1, , z1] = toWorld(b.x, b.y, 0);
    lines.push(x0, z0, x1, z1);
    // The front sidedef is on the right of v1 -> v2 on the map (y north); with z = −y that is the
    // side where the cross product in (x, z) is positive.
    const front = sectorOf(line.front), back = sectorOf(line.back);
    sectors.push(front < map.sectors.length ? front : NO_SECTOR, back < map.sectors.length ? back : NO_SECTOR);
    blocks.push(line.flags & LINEDEF_FLAGS.BLOCKING ? 1 : 0);
  }
  return {
    lines: new Float32Array(lines),
    lineSectors: new Int32Array(sectors),
    lineBlocks: new Uint8Array(blocks),
    floors: new Float32Array(map.sectors.map((s) => s.floorHeight)),
    ceilings: new Float32Array(map.sectors.map((s) => s.ceilingHeight)),
    eyeHeight: EYE_HEIGHT,
    stepHeight: MAX_STEP_HEIGHT,
    bodyHeight: PLAYER_HEIGHT,
    radius: PLAYER_RADIUS,
  };
}
