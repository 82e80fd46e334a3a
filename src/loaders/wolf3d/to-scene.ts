/**
 * A Lantern scene from a Wolfenstein 3D map (level.ts reads what the tiles are):
 * - walls: a face wherever a wall tile borders a tile one can see into, the wall's light page on
 *   north and south faces and its dark page on east and west faces, the door frame's page on the
 *   faces beside a door (map-codes.ts), each 64 × 64 page spanning one face, read left to right
 *   from the tile it faces (as the game draws it: never mirrored);
 * - floor and ceiling: a quad per tile one can see into, in the game's plain colours (the floor's
 *   one colour, the map's ceiling colour), the palette's display values decoded to linear;
 * - doors: a thin panel (an eighth of a tile) across the middle of the door tile, an instance of its
 *   own that slides into the wall beside it (world/sliding-doors.ts); the game's door pages, which
 *   read left to right from the west (vertical doors) or south (horizontal ones), as the game draws
 *   them (mirrored from the other side);
 * - push walls: a wall block of four faces, an instance that the use key slides two tiles away
 *   (world/push-walls.ts);
 * - static objects: alpha-tested sprites standing at their tile's centre, facing the view plane
 *   (scene/billboards.ts, one image: Wolfenstein's objects have no rotations); the lamps
 *   (chandelier, ceiling light, floor lamp) each get a small emitter facing down under the lamp's
 *   body (LAMPS), since sprites turn with the viewer and must not emit;
 * - the player's start as the camera, at eye height, and the torch (Doom's) on by default;
 * - the walk map (walk-map.ts) and the tile grid hint (Scene.tileGrid).
 *
 * Scale and axes: a tile is 64 units, the walls 64 units high (the game's own texel units: a wall
 * page's texel is one unit), and one unit is 1/32 m (Doom's scale), so a tile is 2 m square and
 * 2 m high and Doom's torch fits unchanged. The map's x (east) is world +x, its y (south) world +z,
 * and y is up: north is −z, as in the Doom loader. Tile (x, y) covers [64x, 64x + 64] × [64y, 64y + 64].
 *
 * - guards, SS and dogs of the skill (LoadOptions.skill, 1–4, default 3) as billboards standing
 *   still where the level starts them, with their eight rotations (the dead guard with one); they
 *   do not block the walker.
 *
 * Not built: officers, mutants, bosses and ghosts (counted in a warning), the actors' behaviour,
 * the elevator switch's behaviour, keys and locks (every door opens).
 */
import { IDENTITY, translation } from '../../math/mat4.ts';
import { luminance, scale, type Vec3 } from '../../math/vec3.ts';
import { billboardPoses, billboardQuad } from '../../scene/billboards.ts';
import type { Billboard, PushWall, PushWallSet, SlidingDoor, SlidingDoorSet, WalkGrid } from '../../scene/dynamics-types.ts';
import { diffuse, type Camera, type Instance, type Material, type Mesh, type Scene, type Texture } from '../../scene/types.ts';
import { DOOM_TORCH } from '../doom/light-table.ts';
import type { LoadOptions } from '../format.ts';
import { DIRECTIONS, readLevel, SOLID, type Level, type LevelDoor } from './level.ts';
import { doorPage, doorSidePage, LAST_TEXTURED_WALL, SPR_STAT_0, wallPages, type StaticInfo } from './map-codes.ts';
import { ceilingColourIndex, FLOOR_COLOUR_INDEX } from './palette.ts';
import type { WolfGame, WolfImage, WolfMap } from './types.ts';
import { wolfWalkMap } from './walk-map.ts';

/** Scene units per tile, and the walls' height: the game's texel units. */
export const WOLF_TILE = 64;
export const WOLF_WALL_HEIGHT = 64;
/** Doom's scale: a tile is 2 m. */
export const WOLF_METERS_PER_UNIT = 1 / 32;
/** The game's eye is at half the walls' height. */
export const WOLF_EYE_HEIGHT = WOLF_WALL_HEIGHT / 2;
/** The player's body: MINDIST = 0x5800 / 0x10000 of a tile. */
export const WOLF_PLAYER_RADIUS = (0x5800 / 0x10000) * WOLF_TILE;
/** How tall the walker is (it only has to pass under the walls' 64 units). */
export const WOLF_BODY_HEIGHT = 56;
/** A door panel's thickness: an eighth of a tile. */
export const DOOR_THICKNESS = WOLF_TILE / 8;
/** How far a door panel's trailing end sits inside the panel (units): see doorPanel. */
const DOOR_END_RECESS = 0.25;
/** The game's timing at 70 tics a second: a door moves in 64 tics and stays open 300 (OPENTICS); a push wall moves a tile per 128 tics. */
const TICS_PER_SECOND = 70;
export const DOOR_TRAVEL_SECONDS = 64 / TICS_PER_SECOND;
export const DOOR_WAIT_SECONDS = 300 / TICS_PER_SECOND;
export const PUSH_WALL_SECONDS_PER_TILE = 128 / TICS_PER_SECOND;
/** Standing within a tile and a half of a door's panel (across it) opens it, when doors open by proximity. */
export const DOOR_PROXIMITY = 1.5 * WOLF_TILE;

/**
 * The game's view (WL_DRAW.C CalcProjection): the screen's half width is 0x8000 / (FOCALLENGTH +
 * MINDIST) = 32768 / 44800 in tangent, a horizontal field of view of 72.4°; 57.5° vertically
 * across a 4:3 image.
 */
export const WOLF_VFOV_DEGREES = (2 * Math.atan((0.75 * 0x8000) / (0x5700 + 0x5800)) * 180) / Math.PI;
/**
 * The torch is Doom's, and so is the exposure (doom/to-scene.ts DOOM_EXPOSURE_STOPS): the palette's
 * stone blues and greys are 0.03–0.15 in linear terms, where the tone curve's toe sits well below
 * what the game displays.
 */
export const WOLF_EXPOSURE_STOPS = 1.5;

/** The lamps' light: warm white of luminance 1. */
const LAMP_TINT: Vec3 = [1, 0.82, 0.58];
export const LAMP_COLOR: Vec3 = scale(LAMP_TINT, 1 / luminance(LAMP_TINT));

/**
 * Where each lamp's emitter hangs: a square of `size` units facing down, centred over the tile's
 * centre, at `height`, just under the body the sprite draws (its rows: the chandelier's candles end
 * at row 14, the ceiling light's shade at row 9, the floor lamp's shade at row 31; row r is
 * 64 − r units above the floor). Its radiance lights the floor straight beneath to "full light"
 * (irradiance π, the Doom loader's unit: a wall of albedo a there looks a): L = π h² / size², h the
 * emitter's height, so the lamps' pools of light are about 2.5× as bright as a torch-lit wall at
 * three tiles and fall off as 1/d² around them.
 */
export const LAMPS: Readonly<Record<'chandelier' | 'ceiling light' | 'floor lamp', { readonly height: number; readonly size: number }>> = {
  chandelier: { height: 49, size: 16 },
  'ceiling light': { height: 54, size: 16 },
  'floor lamp': { height: 32, size: 12 },
};

export const lampRadiance = (lamp: { readonly height: number; readonly size: number }): number => (Math.PI * lamp.height ** 2) / lamp.size ** 2;

/** Light (north and south faces) and dark (east and west) sides: faces toward +x, −z, −x, +z, as level.ts DIRECTIONS. */
const LIGHT_SIDE: readonly boolean[] = [false, true, false, true];
const lightSide = (d: number): boolean => LIGHT_SIDE[d] === true;

export function wolfMapToScene(game: WolfGame, map: WolfMap, options: LoadOptions = {}): Scene {
  const warn = options.onWarning ?? (() => {});
  const level = readLevel(map, warn, Math.min(4, Math.max(1, options.skill ?? 3)));
  const parts = new Parts(game, warn);
  const T = WOLF_TILE, H = WOLF_WALL_HEIGHT;
  const at = (x: number, y: number) => y * level.width + x;
  const inside = (x: number, y: number) => x >= 0 && y >= 0 && x < level.width && y < level.height;
  const pushAt = new Set(level.pushWalls.map((p) => at(p.x, p.y)));
  const doorAt = new Map(level.doors.map((d) => [at(d.x, d.y), d]));
  /** Tiles one sees into: open floor, doors, and push walls (which can move away). */
  const seeThrough = (x: number, y: number) => inside(x, y) && (level.kinds[at(x, y)] !== 'wall' || pushAt.has(at(x, y)));

  // Walls.
  const warned = new Set<number>();
  for (let y = 0; y < level.height; y++) {
    for (let x = 0; x < level.width; x++) {
      const i = at(x, y);
      if (level.kinds[i] !== 'wall' || pushAt.has(i)) continue;
      const code = level.walls[i]!;
      DIRECTIONS.forEach(([dx, dy], d) => {
        if (!seeThrough(x + dx, y + dy)) return;
        const door = doorAt.get(at(x + dx, y + dy));
        // A door's frame: the walls either side of its panel (SpawnDoor marks them), on their faces toward it.
        const frame = door && door.vertical === lightSide(d);
        const material = frame ? parts.page(doorSidePage(lightSide(d), game.graphics.wallCount)) : parts.wall(code, lightSide(d), warned);
        wallFace(parts.mesh(material), material, x * T, y * T, d, H);
      });
    }
  }

  // Floors and ceilings.
  const palette = game.graphics.palette;
  const floor = parts.add(`floor`, diffuse('floor', paletteLinear(palette, FLOOR_COLOUR_INDEX)));
  const ceiling = parts.add(`ceiling`, diffuse('ceiling', paletteLinear(palette, ceilingColourIndex(map.index))));
  for (let y = 0; y < level.height; y++) {
    for (let x = 0; x < level.width; x++) {
      if (!seeThrough(x, y)) continue;
      const [x0, z0, x1, z1] = [x * T, y * T, (x + 1) * T, (y + 1) * T];
      // Counter-clockwise seen from above (floor, facing up), and from below (ceiling, facing down).
      parts.mesh(floor).quad(floor, [[x0, 0, z0], [x0, 0, z1], [x1, 0, z1], [x1, 0, z0]], [[0, 0], [0, 1], [1, 1], [1, 0]]);
      parts.mesh(ceiling).quad(ceiling, [[x0, H, z0], [x1, H, z0], [x1, H, z1], [x0, H, z1]], [[0, 0], [1, 0], [1, 1], [0, 1]]);
    }
  }

  // Lamps' emitters.
  for (const s of level.statics) {
    const lamp = lampOf(s.info);
    if (!lamp) continue;
    const material = parts.add(`lamp:${s.info.name}`, { kind: 'emissive', name: `${s.info.name} light`, emission: scale(LAMP_COLOR, lampRadiance(lamp)) });
    const [cx, cz, h] = [(s.x + 0.5) * T, (s.y + 0.5) * T, lamp.size / 2];
    // Counter-clockwise seen from below: facing down.
    parts.mesh(material).quad(material, [[cx - h, lamp.height, cz - h], [cx + h, lamp.height, cz - h], [cx + h, lamp.height, cz + h], [cx - h, lamp.height, cz + h]], [[0, 0], [1, 0], [1, 1], [0, 1]]);
  }

  const { meshes, instances } = parts.staticMeshes();
  const nextId = () => instances.length;
  const grid: WalkGrid = { originX: 0, originZ: 0, size: T };

  // Doors: one panel mesh per page and orientation, in the object space of tile (0, 0).
  const doorMeshes = new Map<string, number>();
  const doors: SlidingDoor[] = level.doors.map((door) => {
    const page = doorPage(door, game.graphics.wallCount);
    const material = parts.page(page);
    const key = `${page}:${door.vertical}`;
    let mesh = doorMeshes.get(key);
    if (mesh === undefined) doorMeshes.set(key, (mesh = meshes.push(doorPanel(door.vertical, material, parts.name(material))) - 1));
    const closedPose = translation([door.x * T, 0, door.y * T]);
    const id = nextId();
    instances.push({ id, name: doorName(door), mesh, worldFromObject: closedPose, moves: true });
    // The panel slides south (vertical doors) or east (horizontal ones), into the frame's wall (WL_DRAW.C: the open part is at the tile's low y or x).
    return { instance: id, closedPose, slide: door.vertical ? [0, 0, T] : [T, 0, 0], cell: [door.x, door.y], across: door.vertical ? [1, 0] : [0, 1], sector: door.sector, floor: 0, ceiling: H };
  });

  // Push walls: one block mesh per wall code, in the object space of tile (0, 0).
  const blockMeshes = new Map<number, number>();
  const pushWalls: PushWall[] = level.pushWalls.map((p) => {
    let mesh = blockMeshes.get(p.code);
    if (mesh === undefined) {
      const b = new MeshBuilder();
      DIRECTIONS.forEach((_, d) => {
        const material = parts.wall(p.code, lightSide(d), warned);
        wallFace(b, material, 0, 0, d, H);
      });
      blockMeshes.set(p.code, (mesh = meshes.push(b.build(`push wall ${p.code}`)) - 1));
    }
    const restPose = translation([p.x * T, 0, p.y * T]);
    const id = nextId();
    instances.push({ id, name: `push wall (${p.x}, ${p.y})`, mesh, worldFromObject: restPose, moves: true });
    const path = (d: number) => p.paths[d]!.map((c) => ({ cell: [c.x, c.y] as const, sector: c.sector }));
    return { instance: id, restPose, cell: [p.x, p.y], sector: p.sector, paths: [path(0), path(1), path(2), path(3)], floor: 0, ceiling: H };
  });

  // Static objects as sprites.
  const camera = playerCamera(level, map, warn);
  const billboards: Billboard[] = [];
  const names: string[] = [];
  for (const s of level.statics) {
    const material = parts.sprite(s.info);
    if (material === undefined) continue;
    billboards.push({
      instance: -1,
      position: [(s.x + 0.5) * T, 0, (s.y + 0.5) * T],
      facing: 0,
      // A sprite page spans a tile's width and the walls' height, standing on the floor at its middle.
      frames: [{ duration: 1, images: [{ material, width: T, height: H, left: T / 2, top: H, mirrored: false }] }],
    });
    names.push(`${s.info.name} (${s.x}, ${s.y})`);
  }
  // Actors, standing still where the level starts them: eight rotations, chosen by the angle they are seen from.
  for (const a of level.actors) {
    const count = a.info.rotations;
    const materials = Array.from({ length: count }, (_, k) => parts.sprite({ name: count === 1 ? a.info.name : `${a.info.name} ${k + 1}`, stat: a.info.sprite - SPR_STAT_0 + k, blocks: false }));
    if (materials.some((m) => m === undefined)) continue;
    billboards.push({
      instance: -1,
      position: [(a.x + 0.5) * T, 0, (a.y + 0.5) * T],
      // Billboard facing: 0 east, π/2 north (−z), as the game's angles.
      facing: (a.info.facing * Math.PI) / 2,
      frames: [{ duration: 1, images: materials.map((material) => ({ material: material!, width: T, height: H, left: T / 2, top: H, mirrored: false })) }],
    });
    names.push(`${a.info.name} (${a.x}, ${a.y})`);
  }
  let placed: Billboard[] = [];
  if (billboards.length > 0) {
    const quad = meshes.push(billboardQuad(billboards[0]!.frames[0]!.images[0]!.material, 'sprite quad')) - 1;
    placed = billboards.map((b, k) => ({ ...b, instance: instances.length + k }));
    const poses = billboardPoses(placed, { position: camera.position, forward: camera.forward });
    placed.forEach((b, k) => instances.push({ id: b.instance, name: names[k]!, mesh: quad, moves: true, ...poses.get(b.instance)! }));
  }

  if (level.undrawnActors > 0) warn(`${map.id}: ${level.undrawnActors} officers, mutants, bosses and ghosts are not shown (Lantern draws the guards, SS and dogs)`);
  const unknown = [...level.skipped];
  if (unknown.length > 0) warn(`${map.id}: object codes not shown: ${unknown.map(([code, count]) => `${code} (×${count})`).join(', ')}`);

  const slidingDoors: SlidingDoorSet = {
    doors,
    grid,
    trigger: 'proximity',
    proximity: DOOR_PROXIMITY,
    travelSeconds: DOOR_TRAVEL_SECONDS,
    waitSeconds: DOOR_WAIT_SECONDS,
    bodyRadius: WOLF_PLAYER_RADIUS,
  };
  const pushWallSet: PushWallSet = { walls: pushWalls, grid, secondsPerCell: PUSH_WALL_SECONDS_PER_TILE, reach: 2 };
  const dynamics = {
    ...(doors.length > 0 && { slidingDoors }),
    ...(pushWalls.length > 0 && { pushWalls: pushWallSet }),
    ...(placed.length > 0 && { billboards: placed }),
  };
  return {
    name: `${map.id} ${map.title}`,
    meshes,
    instances,
    materials: parts.materials,
    textures: parts.textures,
    camera,
    torch: DOOM_TORCH,
    // Rooms lit by lamps and corridors lit by the torch alone differ by stops: the exposure adapts.
    autoExposure: true,
    metersPerUnit: WOLF_METERS_PER_UNIT,
    walkMap: wolfWalkMap(level, { tile: T, wallHeight: H, eyeHeight: WOLF_EYE_HEIGHT, radius: WOLF_PLAYER_RADIUS, bodyHeight: WOLF_BODY_HEIGHT }),
    tileGrid: { origin: [0, 0, 0], cellSize: [T, H, T], dims: [level.width, 1, level.height] },
    ...(Object.keys(dynamics).length > 0 && { dynamics }),
  };
}

function lampOf(info: StaticInfo): { readonly height: number; readonly size: number } | undefined {
  if (!info.light) return undefined;
  return LAMPS[info.name as keyof typeof LAMPS];
}

function doorName(door: LevelDoor): string {
  const lock = door.lock === 'none' ? '' : door.lock === 'elevator' ? 'elevator ' : `${door.lock} key `;
  return `${lock}door (${door.x}, ${door.y})`;
}

/**
 * The face of the wall tile whose north-west corner is (x0, z0) on side `d` (level.ts DIRECTIONS:
 * east, north, west, south), facing out of the tile, counter-clockwise seen from there, its page's
 * left edge on the viewer's left.
 */
function wallFace(mesh: MeshBuilder, material: number, x0: number, z0: number, d: number, height: number): void {
  const T = WOLF_TILE;
  const x1 = x0 + T, z1 = z0 + T;
  // Bottom-left and bottom-right corners as seen from outside the face.
  const [left, right]: [[number, number], [number, number]] =
    d === 0 ? [[x1, z1], [x1, z0]] : d === 1 ? [[x1, z0], [x0, z0]] : d === 2 ? [[x0, z0], [x0, z1]] : [[x0, z1], [x1, z1]];
  mesh.quad(material, [[left[0], 0, left[1]], [right[0], 0, right[1]], [right[0], height, right[1]], [left[0], height, left[1]]], [[0, 1], [1, 1], [1, 0], [0, 0]]);
}

/**
 * A door panel in the object space of tile (0, 0): a box an eighth of a tile thick across the
 * tile's middle, its two broad faces and its trailing end, the one that shows as the panel slides
 * away (its top and bottom touch the floor and ceiling; its leading end is always in the wall). The
 * page's u runs with the map's y (vertical doors) or x (horizontal doors) on both faces, as the game
 * draws it. The trailing end is set DOOR_END_RECESS into the panel so that, fully open, it hides
 * behind the frame's face instead of lying in its plane.
 */
function doorPanel(vertical: boolean, material: number, name: string): Mesh {
  const b = new MeshBuilder();
  const T = WOLF_TILE, H = WOLF_WALL_HEIGHT, c = T / 2, h = DOOR_THICKNESS / 2, r = DOOR_END_RECESS;
  // Each face: bottom-left and bottom-right (x, z) seen from outside, with their u.
  const face = (l: [number, number], r: [number, number], ul: number, ur: number) =>
    b.quad(material, [[l[0], 0, l[1]], [r[0], 0, r[1]], [r[0], H, r[1]], [l[0], H, l[1]]], [[ul, 1], [ur, 1], [ur, 0], [ul, 0]]);
  const end = DOOR_THICKNESS / T;
  if (vertical) {
    face([c - h, 0], [c - h, T], 0, 1); // west face, u = z / T
    face([c + h, T], [c + h, 0], 1, 0); // east face
    face([c + h, r], [c - h, r], 0, end); // north (trailing) end
  } else {
    face([0, c + h], [T, c + h], 0, 1); // south face, u = x / T
    face([T, c - h], [0, c - h], 1, 0); // north face
    face([r, c - h], [r, c + h], 0, end); // west (trailing) end
  }
  return b.build(`door panel ${name}${vertical ? ' (vertical)' : ''}`);
}

/** The camera at the player's start, at eye height, facing the start's way; the first open tile when the map has none. */
function playerCamera(level: Level, map: WolfMap, warn: (m: string) => void): Camera {
  let start = level.start;
  if (!start) {
    const i = level.sectors.findIndex((s) => s !== SOLID);
    start = { x: i % level.width, y: Math.floor(i / level.width), facing: [1, 0] };
    warn(`${map.id} has no player start; the camera stands in the first open tile (${start.x}, ${start.y}), facing east`);
  }
  return {
    position: [(start.x + 0.5) * WOLF_TILE, WOLF_EYE_HEIGHT, (start.y + 0.5) * WOLF_TILE],
    forward: [start.facing[0], 0, start.facing[1]],
    up: [0, 1, 0],
    vfovDegrees: WOLF_VFOV_DEGREES,
    exposureStops: WOLF_EXPOSURE_STOPS,
  };
}

/** Palette entry `index` (display values) decoded from sRGB to linear reflectance. */
export function paletteLinear(palette: Uint8Array, index: number): Vec3 {
  const lin = (c: number) => {
    const v = c / 255;
    return v <= 0.04045 ? v / 12.92 : ((v + 0.055) / 1.055) ** 2.4;
  };
  return [lin(palette[3 * index]!), lin(palette[3 * index + 1]!), lin(palette[3 * index + 2]!)];
}

/** Triangles with uvs and a material each. */
class MeshBuilder {
  private readonly positions: number[] = [];
  private readonly uvs: number[] = [];
  private readonly indices: number[] = [];
  private readonly materialIds: number[] = [];

  /** Corners counter-clockwise seen from the side the quad faces. */
  quad(material: number, corners: readonly Vec3[], uvs: readonly (readonly [number, number])[]): void {
    const base = this.positions.length / 3;
    for (let k = 0; k < 4; k++) {
      this.positions.push(...corners[k]!);
      this.uvs.push(...uvs[k]!);
    }
    this.indices.push(base, base + 1, base + 2, base, base + 2, base + 3);
    this.materialIds.push(material, material);
  }

  get empty(): boolean {
    return this.indices.length === 0;
  }

  build(name: string): Mesh {
    return { name, positions: new Float32Array(this.positions), uvs: new Float32Array(this.uvs), indices: new Uint32Array(this.indices), materialIds: new Uint32Array(this.materialIds) };
  }
}

/** Materials and textures made as needed (one per wall page, sprite, colour), and a static mesh per material. */
class Parts {
  readonly materials: Material[] = [];
  readonly textures: Texture[] = [];
  private readonly byKey = new Map<string, number>();
  private readonly meshes = new Map<number, MeshBuilder>();

  constructor(
    private readonly game: WolfGame,
    private readonly warn: (m: string) => void,
  ) {}

  add(key: string, material: Material): number {
    let index = this.byKey.get(key);
    if (index === undefined) this.byKey.set(key, (index = this.materials.push(material) - 1));
    return index;
  }

  name(material: number): string {
    return this.materials[material]!.name;
  }

  /** Wall page `page`, nearest-filtered, opaque; a plain grey material when the page cannot be read. */
  page(page: number): number {
    const key = `page:${page}`;
    const known = this.byKey.get(key);
    if (known !== undefined) return known;
    let image: WolfImage;
    try {
      image = this.game.graphics.wall(page);
    } catch (e) {
      this.warn(`wall page ${page} cannot be read (${e instanceof Error ? e.message : String(e)}); drawn plain grey`);
      return this.add(key, diffuse(`missing wall page ${page}`, [0.5, 0.5, 0.5]));
    }
    const texture = this.texture(`wall page ${page}`, image);
    return this.add(key, diffuse(`wall page ${page}`, [1, 1, 1], [0, 0, 0], { albedoTexture: { texture } }));
  }

  /** Wall code `code`'s light or dark page; codes without pages of their own are drawn plain (warned once each). */
  wall(code: number, light: boolean, warned: Set<number>): number {
    if (code >= 1 && code <= LAST_TEXTURED_WALL) {
      const pages = wallPages(code);
      const page = light ? pages.light : pages.dark;
      if (page < this.game.graphics.wallCount - 8) return this.page(page);
    }
    if (!warned.has(code)) {
      warned.add(code);
      this.warn(`wall code ${code} has no wall page of its own; drawn plain grey`);
    }
    return this.add('missing wall', diffuse('wall without a page', [0.5, 0.5, 0.5]));
  }

  /** The sprite of a static object, alpha-tested; undefined (warned) when it cannot be read. */
  sprite(info: StaticInfo): number | undefined {
    const key = `sprite:${info.stat}`;
    const known = this.byKey.get(key);
    if (known !== undefined) return known < 0 ? undefined : known;
    let image: WolfImage;
    try {
      image = this.game.graphics.sprite(SPR_STAT_0 + info.stat);
    } catch (e) {
      this.warn(`the sprite of the ${info.name} cannot be read (${e instanceof Error ? e.message : String(e)}); not shown`);
      this.byKey.set(key, -1);
      return undefined;
    }
    const texture = this.texture(`sprite ${info.name}`, image);
    return this.add(key, diffuse(info.name, [1, 1, 1], [0, 0, 0], { albedoTexture: { texture }, alphaMode: 'mask' }));
  }

  mesh(material: number): MeshBuilder {
    let m = this.meshes.get(material);
    if (!m) this.meshes.set(material, (m = new MeshBuilder()));
    return m;
  }

  /** The static meshes, one per material, each placed once. */
  staticMeshes(): { meshes: Mesh[]; instances: Instance[] } {
    const meshes: Mesh[] = [];
    for (const [material, b] of this.meshes) if (!b.empty) meshes.push(b.build(this.materials[material]!.name));
    return { meshes, instances: meshes.map((mesh, i) => ({ id: i, name: mesh.name, mesh: i, worldFromObject: IDENTITY })) };
  }

  private texture(name: string, image: WolfImage): number {
    // Wolfenstein's texels are seen as pixels, never blurred.
    return this.textures.push({ name, width: image.width, height: image.height, rgba: image.rgba, filter: 'nearest' }) - 1;
  }
}
