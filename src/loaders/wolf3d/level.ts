/**
 * A Wolfenstein 3D map read as a level: what each tile is (map-codes.ts), its doors, push walls,
 * static objects and player start, and its floor plan as walk-map sectors. Pure; to-scene.ts builds
 * the geometry from it, walk-map.ts the WalkMap.
 *
 * Sectors. Every tile one can stand in belongs to one sector: each door tile, push-wall tile and
 * tile a push wall may slide into (their heights change as they open, close or fill) has a sector
 * of its own; the other open tiles form one sector per connected area. Walls, blocking objects
 * (the game's `block` statics fill their tile for walking) and the outside have none.
 */
import { LanternError } from '../../errors.ts';
import { actorInfo, doorCode, FIRST_ACTOR, isInvisibleMark, PUSHABLETILE, staticInfo, startFacing, tileKind, type ActorInfo, type DoorCode, type StaticInfo, type TileKind } from './map-codes.ts';
import type { WolfMap } from './types.ts';

/** No sector: a wall, a blocking object, outside the map. */
export const SOLID = -1;

export interface LevelDoor extends DoorCode {
  readonly x: number;
  readonly y: number;
  readonly sector: number;
}

export interface LevelPushWall {
  readonly x: number;
  readonly y: number;
  /** Its plane-0 wall code. */
  readonly code: number;
  readonly sector: number;
  /** Free tiles in each direction (east, north, west, south), nearest first, at most PUSH_REACH. */
  readonly paths: readonly [LevelCell[], LevelCell[], LevelCell[], LevelCell[]];
}

export interface LevelCell {
  readonly x: number;
  readonly y: number;
  readonly sector: number;
}

export interface LevelStatic {
  readonly x: number;
  readonly y: number;
  readonly code: number;
  readonly info: StaticInfo;
}

export interface LevelActor {
  readonly x: number;
  readonly y: number;
  readonly code: number;
  readonly info: ActorInfo;
}

export interface Level {
  readonly width: number;
  readonly height: number;
  /** Plane 0, per tile (y · width + x). */
  readonly walls: Uint16Array;
  readonly kinds: readonly TileKind[];
  /** Per tile: its sector, or SOLID. */
  readonly sectors: Int32Array;
  readonly sectorCount: number;
  /** Sectors whose heights change (doors, push walls and their paths): [floor, ceiling] at the start. */
  readonly shutAtStart: ReadonlySet<number>;
  readonly doors: readonly LevelDoor[];
  readonly pushWalls: readonly LevelPushWall[];
  readonly statics: readonly LevelStatic[];
  /** The actors drawn (map-codes.ts actorInfo), at the level's skill. */
  readonly actors: readonly LevelActor[];
  /** Actors of the skill that are not drawn (officers, mutants, bosses, ghosts). */
  readonly undrawnActors: number;
  /** The player's start tile and facing (a unit step on the map), or undefined when the map has none. */
  readonly start?: { readonly x: number; readonly y: number; readonly facing: readonly [number, number] };
  /** Plane-1 codes the builder does not know, with how many of each. */
  readonly skipped: ReadonlyMap<number, number>;
}

/** How far a push wall moves (WL_ACT1.C MovePWalls: "the block has been pushed two tiles"). */
export const PUSH_REACH = 2;
/** East, north, west, south as map steps (y south). */
export const DIRECTIONS: readonly (readonly [number, number])[] = [[1, 0], [0, -1], [-1, 0], [0, 1]];

/** Wolfenstein's skill levels 1–4 ("can I play, daddy?" … "I am death incarnate"); Doom's 5 counts as 4. Default 3. */
export function readLevel(map: WolfMap, warn: (message: string) => void = () => {}, skill = 3): Level {
  const { width, height } = map;
  const n = width * height;
  if (!(width > 0 && height > 0) || map.planes.some((p) => p.length < n)) {
    throw new LanternError(`${map.id}: its planes hold fewer than ${width} × ${height} tiles`, 'the map file is damaged');
  }
  const [walls, objects] = map.planes;
  const at = (x: number, y: number) => y * width + x;
  const inside = (x: number, y: number) => x >= 0 && y >= 0 && x < width && y < height;
  const kinds: TileKind[] = Array.from(walls.subarray(0, n), tileKind);

  const statics: LevelStatic[] = [];
  const actors: LevelActor[] = [];
  let undrawnActors = 0;
  const pushTiles: { x: number; y: number }[] = [];
  const skipped = new Map<number, number>();
  let start: Level['start'];
  const blocking = new Uint8Array(n);
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const code = objects[at(x, y)]!;
      if (code === 0 || isInvisibleMark(code)) continue;
      const facing = startFacing(code);
      const info = staticInfo(code);
      if (facing) {
        if (start) warn(`${map.id}: a second player start at (${x}, ${y}); the first, at (${start.x}, ${start.y}), is used`);
        else start = { x, y, facing };
      } else if (code === PUSHABLETILE) {
        if (kinds[at(x, y)] === 'wall') pushTiles.push({ x, y });
        else warn(`${map.id}: a push-wall mark at (${x}, ${y}) is not on a wall; ignored`);
      } else if (info && kinds[at(x, y)] === 'open') {
        statics.push({ x, y, code, info });
        if (info.blocks) blocking[at(x, y)] = 1;
      } else if (code >= FIRST_ACTOR) {
        const actor = actorInfo(code, skill);
        if ('skipped' in actor) {
          if (actor.skipped === 'kind') undrawnActors++;
        } else if (kinds[at(x, y)] !== 'wall') actors.push({ x, y, code, info: actor });
      } else skipped.set(code, (skipped.get(code) ?? 0) + 1);
    }
  }

  // The tiles whose heights change get sectors of their own.
  const own = new Uint8Array(n);
  const doorTiles: { x: number; y: number }[] = [];
  for (let i = 0; i < n; i++) if (kinds[i] === 'door') (own[i] = 1), doorTiles.push({ x: i % width, y: Math.floor(i / width) });
  for (const p of pushTiles) own[at(p.x, p.y)] = 1;
  // A push wall enters open tiles that nothing blocks (PushWall: actorat is clear), up to PUSH_REACH.
  const free = (x: number, y: number) => inside(x, y) && kinds[at(x, y)] === 'open' && !blocking[at(x, y)];
  const pathTiles = pushTiles.map(({ x, y }) =>
    DIRECTIONS.map(([dx, dy]) => {
      const cells: { x: number; y: number }[] = [];
      for (let k = 1; k <= PUSH_REACH && free(x + k * dx, y + k * dy); k++) cells.push({ x: x + k * dx, y: y + k * dy });
      for (const c of cells) own[at(c.x, c.y)] = 1;
      return cells;
    }),
  );

  const sectors = new Int32Array(n).fill(SOLID);
  let sectorCount = 0;
  // Connected areas of plain open tiles (4-neighbours), by flood fill.
  const stack: number[] = [];
  for (let i = 0; i < n; i++) {
    if (kinds[i] !== 'open' || blocking[i] || own[i] || sectors[i] !== SOLID) continue;
    const s = sectorCount++;
    sectors[i] = s;
    stack.push(i);
    while (stack.length > 0) {
      const j = stack.pop()!;
      const x = j % width, y = Math.floor(j / width);
      for (const [dx, dy] of DIRECTIONS) {
        const nx = x + dx, ny = y + dy;
        if (!inside(nx, ny)) continue;
        const k = at(nx, ny);
        if (kinds[k] === 'open' && !blocking[k] && !own[k] && sectors[k] === SOLID) {
          sectors[k] = s;
          stack.push(k);
        }
      }
    }
  }
  for (let i = 0; i < n; i++) if (own[i]) sectors[i] = sectorCount++;

  const shutAtStart = new Set<number>();
  const doors = doorTiles.map(({ x, y }) => {
    const sector = sectors[at(x, y)]!;
    shutAtStart.add(sector);
    return { x, y, ...doorCode(walls[at(x, y)]!), sector };
  });
  const pushWalls = pushTiles.map(({ x, y }, k) => {
    const sector = sectors[at(x, y)]!;
    shutAtStart.add(sector);
    const path = (d: number) => pathTiles[k]![d]!.map((c) => ({ ...c, sector: sectors[at(c.x, c.y)]! }));
    const paths: LevelPushWall['paths'] = [path(0), path(1), path(2), path(3)];
    return { x, y, code: walls[at(x, y)]!, sector, paths };
  });
  return { width, height, walls, kinds, sectors, sectorCount, shutAtStart, doors, pushWalls, statics, actors, undrawnActors, ...(start && { start }), skipped };
}

/** The sector of tile (x, y), SOLID outside the map. */
export function sectorOfTile(level: Level, x: number, y: number): number {
  return x >= 0 && y >= 0 && x < level.width && y < level.height ? level.sectors[y * level.width + x]! : SOLID;
}
