/**
 * A Wolfenstein 3D level's floor plan as a WalkMap (scene/walk-map.ts): a line along every tile edge
 * between two different sectors (level.ts), collinear edges between the same two sectors joined, so
 * walls and blocking objects stop the walker and the tiles of doors and push walls stop it while
 * their sector is shut (ceiling down at the floor). The walker's dimensions are the game's: a body
 * of radius MINDIST (0x5800 / 0x10000 of a tile: 22 units), the eye at half the wall's height.
 */
import type { WalkMap } from '../../scene/walk-map.ts';
import { SOLID, sectorOfTile, type Level } from './level.ts';

export interface WolfWalkerSize {
  readonly tile: number;
  readonly wallHeight: number;
  readonly eyeHeight: number;
  readonly radius: number;
  readonly bodyHeight: number;
}

export function wolfWalkMap(level: Level, size: WolfWalkerSize): WalkMap {
  const { tile } = size;
  const lines: number[] = [];
  const sides: number[] = [];
  // The side where cross((x1 − x0, z1 − z0), p − p0) > 0 comes first (scene/walk-map.ts): for an edge
  // running +z that is its west (−x) side; for one running +x, its south (+z) side.
  const emit = (x0: number, z0: number, x1: number, z1: number, first: number, second: number) => {
    lines.push(x0, z0, x1, z1);
    sides.push(first, second);
  };
  // Edges along x = const: between tiles (x − 1, y) and (x, y), runs joined along y.
  for (let x = 0; x <= level.width; x++) {
    let run: { y0: number; a: number; b: number } | undefined;
    for (let y = 0; y <= level.height; y++) {
      const a = y < level.height ? sectorOfTile(level, x - 1, y) : SOLID;
      const b = y < level.height ? sectorOfTile(level, x, y) : SOLID;
      const edge = a !== b && y < level.height;
      if (run && (!edge || run.a !== a || run.b !== b)) {
        emit(x * tile, run.y0 * tile, x * tile, y * tile, run.a, run.b);
        run = undefined;
      }
      if (edge && !run) run = { y0: y, a, b };
    }
  }
  // Edges along z = const: between tiles (x, y − 1) (north) and (x, y) (south), runs joined along x.
  for (let y = 0; y <= level.height; y++) {
    let run: { x0: number; north: number; south: number } | undefined;
    for (let x = 0; x <= level.width; x++) {
      const north = x < level.width ? sectorOfTile(level, x, y - 1) : SOLID;
      const south = x < level.width ? sectorOfTile(level, x, y) : SOLID;
      const edge = north !== south && x < level.width;
      if (run && (!edge || run.north !== north || run.south !== south)) {
        emit(run.x0 * tile, y * tile, x * tile, y * tile, run.south, run.north);
        run = undefined;
      }
      if (edge && !run) run = { x0: x, north, south };
    }
  }
  const floors = new Float32Array(level.sectorCount);
  const ceilings = new Float32Array(level.sectorCount).fill(size.wallHeight);
  for (const s of level.shutAtStart) ceilings[s] = 0;
  return {
    lines: new Float32Array(lines),
    lineSectors: new Int32Array(sides),
    lineBlocks: new Uint8Array(lines.length / 4),
    floors,
    ceilings,
    eyeHeight: size.eyeHeight,
    // No steps in Wolfenstein: every floor is at 0.
    stepHeight: 0,
    bodyHeight: size.bodyHeight,
    radius: size.radius,
  };
}
