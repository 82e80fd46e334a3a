/**
 * The dungeon's floor plan (the built-in scene `dungeon`, loaders/builtin/dungeon.ts), as a 16 × 16
 * grid read top-down: row 0 at the top is the northern edge (world z = 0), column 0 the western
 * edge (world x = 0); each tile is TILE_SIZE scene units square.
 *
 *   #  stone wall          .  floor          S  floor, where the player starts (facing east)
 *   t  stone wall with a torch on every face that borders a floor tile
 *
 * A ring corridor runs round the outside (the phantom's beat); rooms and a pillared hall fill the
 * middle. Pure.
 */
import { LanternError } from '../../errors.ts';

export const DUNGEON_MAP = `
##t#####t####t##
#S.............#
#.##.######.##.#
t.#...#...#..#.t
#.#...#...#..#.#
#.#.......t..#.#
#.#...#...#..#.#
#.####.####.##.#
t.#.........#..t
#.#.#.###.#.#..#
#.#.........#..#
#.###.#.###.#..#
#.#...t........#
#.##.####.####.#
#..............#
##t#####t####t##
`;

/**
 * The phantom's round, as the tiles (row, column) where it turns: it walks in straight lines of
 * tiles between them and back from the last to the first. It starts at the first, heading for the
 * second: four tiles ahead of the player, coming toward them.
 */
export const PHANTOM_ROUND: readonly (readonly [number, number])[] = [
  [1, 5],
  [1, 1],
  [14, 1],
  [14, 14],
  [1, 14],
];

export type Cell = 'wall' | 'torch' | 'floor';

export interface TileMap {
  readonly rows: number;
  readonly columns: number;
  /** Row-major. */
  readonly cells: readonly Cell[];
  readonly start: readonly [number, number];
}

export const isFloor = (map: TileMap, row: number, column: number): boolean =>
  row >= 0 && row < map.rows && column >= 0 && column < map.columns && map.cells[row * map.columns + column] === 'floor';

/** Reads a map drawn with the characters above; every row the same width, exactly one S. */
export function parseTileMap(text: string): TileMap {
  const lines = text.split('\n').map((l) => l.trimEnd()).filter((l) => l.length > 0);
  const columns = lines[0]?.length ?? 0;
  if (lines.length === 0 || columns === 0) throw new LanternError('the tile map is empty');
  const cells: Cell[] = [];
  let start: [number, number] | undefined;
  lines.forEach((line, row) => {
    if (line.length !== columns) throw new LanternError(`tile map row ${row} has ${line.length} tiles, not ${columns} like row 0`);
    [...line].forEach((ch, column) => {
      switch (ch) {
        case '#':
          cells.push('wall');
          break;
        case 't':
          cells.push('torch');
          break;
        case 'S':
          if (start) throw new LanternError(`the tile map has two starts (S), at row ${start[0]} column ${start[1]} and at row ${row} column ${column}`);
          start = [row, column];
          cells.push('floor');
          break;
        case '.':
          cells.push('floor');
          break;
        default:
          throw new LanternError(`tile map row ${row} column ${column}: unknown tile '${ch}'`, "Tiles are '#' wall, 't' wall with torches, '.' floor, 'S' the start");
      }
    });
  });
  if (!start) throw new LanternError('the tile map has no start (S)');
  const map: TileMap = { rows: lines.length, columns, cells, start };
  // Floor must not reach the edge: the walls close the level.
  for (let r = 0; r < map.rows; r++) {
    for (let c = 0; c < map.columns; c++) {
      if (isFloor(map, r, c) && (r === 0 || c === 0 || r === map.rows - 1 || c === map.columns - 1)) throw new LanternError(`tile map row ${r} column ${c}: floor on the edge of the map leaves the level open`);
    }
  }
  return map;
}

/** Every tile (row, column) on a round through `corners`, walking straight between them; checks they are floor. */
export function expandRound(map: TileMap, corners: readonly (readonly [number, number])[]): [number, number][] {
  const tiles: [number, number][] = [];
  corners.forEach(([r0, c0], i) => {
    const [r1, c1] = corners[(i + 1) % corners.length]!;
    if (r0 !== r1 && c0 !== c1) throw new LanternError(`the round goes from (${r0}, ${c0}) to (${r1}, ${c1}), not along a row or column`);
    const steps = Math.abs(r1 - r0) + Math.abs(c1 - c0);
    for (let k = 0; k < steps; k++) {
      const r = r0 + Math.sign(r1 - r0) * k, c = c0 + Math.sign(c1 - c0) * k;
      if (!isFloor(map, r, c)) throw new LanternError(`the round crosses row ${r} column ${c}, which is not floor`);
      tiles.push([r, c]);
    }
  });
  return tiles;
}
