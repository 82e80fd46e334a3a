/**
 * A Wolfenstein 3D map as a Scene — the readers' minimal version, so that the format, the CLI and
 * the page work end to end while the full builder (textured walls, doors, sprites, lights) is
 * written beside it; that builder replaces this file, keeping `wolfMapToScene`'s signature.
 *
 * What this one draws: every wall tile's faces that border a non-wall tile, in its wall page's
 * average colour (the light page on north and south faces, the dark page on east and west faces,
 * as the game shades them); one floor and one ceiling quad over the map in the level's palette
 * colours; the camera at the player start (plane 1 codes 19–22 face north, east, south, west)
 * with Doom's torch. Doors, push walls and objects are not drawn (door tiles are open floor).
 *
 * Doom's scale, as the dungeon built-in: a tile is 64 units (2 m at 1/32 m per unit) and the
 * walls as high as a tile is wide, as in the game. World x = tile column, z = tile row (south).
 * Pure.
 */
import { IDENTITY } from '../../math/mat4.ts';
import type { Vec3 } from '../../math/vec3.ts';
import { MeshBuilder } from '../../scene/builder.ts';
import { diffuse, type Scene } from '../../scene/types.ts';
import { DOOM_TORCH } from '../doom/light-table.ts';
import type { LoadOptions } from '../format.ts';
import { ceilingColourIndex, FLOOR_COLOUR_INDEX } from './palette.ts';
import type { WolfGame, WolfImage, WolfMap } from './types.ts';

/** Scene units per tile, and the wall height. */
export const WOLF_TILE = 64;
export const WOLF_METERS_PER_UNIT = 1 / 32;
/** The game's eye is at half the wall height. */
const EYE = WOLF_TILE / 2;
/** Plane 0 codes 1–63 are solid walls (wall k uses pages 2k − 2 and 2k − 1). */
const isWall = (code: number) => code >= 1 && code <= 63;
/** Plane 1 player start codes, north, east, south, west. */
const START_FORWARD: Record<number, Vec3> = { 19: [0, 0, -1], 20: [1, 0, 0], 21: [0, 0, 1], 22: [-1, 0, 0] };

const srgbToLinear = (c: number) => {
  const v = c / 255;
  return v <= 0.04045 ? v / 12.92 : ((v + 0.055) / 1.055) ** 2.4;
};

function averageColour(image: WolfImage): Vec3 {
  const sum = [0, 0, 0];
  const n = image.width * image.height;
  for (let i = 0; i < n; i++) for (let c = 0; c < 3; c++) sum[c]! += srgbToLinear(image.rgba[4 * i + c]!);
  return [sum[0]! / n, sum[1]! / n, sum[2]! / n];
}

function paletteColour(palette: Uint8Array, index: number): Vec3 {
  return [srgbToLinear(palette[3 * index]!), srgbToLinear(palette[3 * index + 1]!), srgbToLinear(palette[3 * index + 2]!)];
}

export function wolfMapToScene(game: WolfGame, map: WolfMap, options: LoadOptions = {}): Scene {
  const { width, height } = map;
  const [walls, objects] = map.planes;
  const builder = new MeshBuilder(map.id);
  const warnings: string[] = [];
  const pageMaterial = new Map<number, number>();
  const materialOfPage = (page: number): number => {
    let m = pageMaterial.get(page);
    if (m === undefined) {
      const colour: Vec3 = page < game.graphics.wallCount ? averageColour(game.graphics.wall(page)) : [0.5, 0.5, 0.5];
      m = builder.material(diffuse(`wall page ${page}`, colour));
      pageMaterial.set(page, m);
    }
    return m;
  };
  const S = WOLF_TILE;
  const wallAt = (x: number, y: number) => x >= 0 && y >= 0 && x < width && y < height && isWall(walls[y * width + x]!);
  let missing = 0;
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const code = walls[y * width + x]!;
      if (!isWall(code)) continue;
      const light = 2 * code - 2;
      if (light + 1 >= game.graphics.wallCount) missing++;
      const x0 = x * S, x1 = (x + 1) * S, z0 = y * S, z1 = (y + 1) * S;
      // Each face wound counter-clockwise seen from outside the tile.
      if (!wallAt(x, y - 1)) builder.quad(materialOfPage(light), [x1, 0, z0], [x0, 0, z0], [x0, S, z0], [x1, S, z0]);
      if (!wallAt(x, y + 1)) builder.quad(materialOfPage(light), [x0, 0, z1], [x1, 0, z1], [x1, S, z1], [x0, S, z1]);
      if (!wallAt(x + 1, y)) builder.quad(materialOfPage(light + 1), [x1, 0, z1], [x1, 0, z0], [x1, S, z0], [x1, S, z1]);
      if (!wallAt(x - 1, y)) builder.quad(materialOfPage(light + 1), [x0, 0, z0], [x0, 0, z1], [x0, S, z1], [x0, S, z0]);
    }
  }
  if (missing > 0) warnings.push(`${map.id}: ${missing} wall tile(s) name wall pages VSWAP does not have; drawn grey`);
  const palette = game.graphics.palette;
  const floor = builder.material(diffuse('floor', paletteColour(palette, FLOOR_COLOUR_INDEX)));
  const ceiling = builder.material(diffuse('ceiling', paletteColour(palette, ceilingColourIndex(map.index))));
  const W = width * S, H = height * S;
  builder.quad(floor, [0, 0, 0], [0, 0, H], [W, 0, H], [W, 0, 0]);
  builder.quad(ceiling, [0, S, 0], [W, S, 0], [W, S, H], [0, S, H]);

  let camera: Scene['camera'] = { position: [W / 2, EYE, H / 2], forward: [0, 0, -1], up: [0, 1, 0], vfovDegrees: 70 };
  const start = objects.findIndex((code) => START_FORWARD[code] !== undefined);
  if (start >= 0) {
    const x = start % width, y = Math.floor(start / width);
    camera = { position: [(x + 0.5) * S, EYE, (y + 0.5) * S], forward: START_FORWARD[objects[start]!]!, up: [0, 1, 0], vfovDegrees: 70 };
  } else warnings.push(`${map.id} has no player start; the camera is at the map's centre`);
  for (const w of warnings) options.onWarning?.(w);

  return {
    name: `${map.id} ${map.title}`,
    meshes: [builder.build()],
    instances: [{ id: 0, name: map.id, mesh: 0, worldFromObject: IDENTITY }],
    materials: builder.materials,
    camera,
    torch: DOOM_TORCH,
    metersPerUnit: WOLF_METERS_PER_UNIT,
    ...(warnings.length > 0 ? { warnings } : {}),
  };
}
