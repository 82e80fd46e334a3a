/**
 * `dungeon`: a torch-lit stone dungeon built from the 16 × 16 tile map in dungeon-map.ts (Lantern
 * issue #12 §4). Doom's scale, so that Doom's walker and torch fit it unchanged: a tile is 64 units
 * (2 m at 1/32 m per unit), the ceiling 96 units (3 m) high. Per floor tile: four flagstones and a
 * ceiling slab; per wall face: a wall above a plinth (whose ends meet at inner and outer corners);
 * on every face of a torch tile ('t') an iron sconce and a flame (an orange teardrop round a
 * yellow-white core, twice, in a V so it shows from along the corridor too). The player's
 * torch (Doom's) is the main light. The phantom (phantom.ts), a faintly glowing robe, walks the ring
 * corridor (scene/paths.ts: a Catmull–Rom loop through tile centres at 1.5 m/s, facing its way,
 * bobbing). The walk map has one sector, the floor, bounded by every wall face. Pure.
 */
import { IDENTITY, type Mat4 } from '../../math/mat4.ts';
import type { Vec3 } from '../../math/vec3.ts';
import type { InstancePath } from '../../scene/dynamics-types.ts';
import { CompiledPath } from '../../scene/paths.ts';
import { diffuse, type Material, type Mesh, type Scene } from '../../scene/types.ts';
import type { WalkMap } from '../../scene/walk-map.ts';
import { DOOM_TORCH } from '../doom/light-table.ts';
import { EYE_HEIGHT } from '../doom/map-types.ts';
import { MAX_STEP_HEIGHT, PLAYER_HEIGHT, PLAYER_RADIUS } from '../doom/walk-map.ts';
import { DUNGEON_MAP, expandRound, isFloor, parseTileMap, PHANTOM_ROUND, type TileMap } from './dungeon-map.ts';
import { ceilingTexture, FLOOR_STONES_PER_SIDE, floorTexture, hash01, wallTexture } from './dungeon-textures.ts';
import { phantomMesh } from './phantom.ts';

/** Scene units per tile (Doom's grid: 2 m). */
export const DUNGEON_TILE = 64;
export const DUNGEON_HEIGHT = 96;
export const DUNGEON_METERS_PER_UNIT = 1 / 32;
const PLINTH_HEIGHT = 8, PLINTH_DEPTH = 4;
/** The phantom floats with its hem this high, and walks at 1.5 m/s. */
const PHANTOM_FLOAT = 10;
export const PHANTOM_SPEED = 1.5 / DUNGEON_METERS_PER_UNIT;
export const PHANTOM_ID = 1;
export const LEVEL_ID = 0;

/** Flame radiance, the outer teardrop and the core: a pool of warm light round each sconce. */
const FLAME_EMISSION: Vec3 = [7, 3, 0.7];
const FLAME_CORE_EMISSION: Vec3 = [14, 10, 4.5];
const PHANTOM_EMISSION: Vec3 = [0.4, 0.56, 0.88];

/** The centre of tile (row, column) on the floor. */
export const tileCentre = (row: number, column: number): Vec3 => [(column + 0.5) * DUNGEON_TILE, 0, (row + 0.5) * DUNGEON_TILE];

class Builder {
  readonly positions: number[] = [];
  readonly uvs: number[] = [];
  readonly indices: number[] = [];
  readonly materialIds: number[] = [];

  /** Quad v0..v3 (emitting side: counter-clockwise seen from it), uvs per corner. */
  quad(material: number, v: readonly Vec3[], uv: readonly (readonly [number, number])[]): void {
    const base = this.positions.length / 3;
    for (let i = 0; i < 4; i++) {
      this.positions.push(...v[i]!);
      this.uvs.push(...uv[i]!);
    }
    this.indices.push(base, base + 1, base + 2, base, base + 2, base + 3);
    this.materialIds.push(material, material);
  }

  /** A triangle without texture (a, b, c counter-clockwise seen from its emitting side). */
  triangle(material: number, a: Vec3, b: Vec3, c: Vec3): void {
    const base = this.positions.length / 3;
    this.positions.push(...a, ...b, ...c);
    this.uvs.push(0, 0, 1, 0, 0, 1);
    this.indices.push(base, base + 1, base + 2);
    this.materialIds.push(material);
  }

  build(name: string): Mesh {
    return { name, positions: new Float32Array(this.positions), uvs: new Float32Array(this.uvs), indices: new Uint32Array(this.indices), materialIds: new Uint32Array(this.materialIds) };
  }
}

interface LevelMaterials {
  readonly wall: number;
  readonly plinth: number;
  readonly floor: number;
  readonly ceiling: number;
  readonly iron: number;
  readonly flame: number;
  readonly flameCore: number;
}

/** The four directions in the plan: (dx, dz) = (column step, row step). */
const DIRECTIONS: readonly (readonly [number, number])[] = [[1, 0], [-1, 0], [0, 1], [0, -1]];

/** Point on the plan (x, z) at height y. */
const at = (x: number, y: number, z: number): Vec3 => [x, y, z];

/**
 * The level's static mesh, and its walk-map lines (x0, z0, x1, z1 with the floor on the positive side
 * of the cross product: lineSectors [0, −1]).
 */
function buildLevel(map: TileMap, m: LevelMaterials): { mesh: Mesh; lines: number[] } {
  const b = new Builder();
  const lines: number[] = [];
  const T = DUNGEON_TILE, H = DUNGEON_HEIGHT;
  for (let r = 0; r < map.rows; r++) {
    for (let c = 0; c < map.columns; c++) {
      if (!isFloor(map, r, c)) continue;
      const x0 = c * T, z0 = r * T;
      // Four flagstones, each a stone of the floor texture chosen by hash and turned by a quarter turn or not.
      const half = T / 2, n = FLOOR_STONES_PER_SIDE;
      for (let q = 0; q < 4; q++) {
        const sx = x0 + (q % 2) * half, sz = z0 + Math.floor(q / 2) * half;
        const stone = Math.floor(hash01(r, c, q) * n * n);
        const u0 = (stone % n) / n, v0 = Math.floor(stone / n) / n, u1 = u0 + 1 / n, v1 = v0 + 1 / n;
        const corners: [number, number][] = [[u0, v0], [u0, v1], [u1, v1], [u1, v0]];
        const turn = hash01(r, c, q, 1) < 0.5 ? 0 : 1;
        const uv = [0, 1, 2, 3].map((k) => corners[(k + turn) % 4]!);
        b.quad(m.floor, [at(sx, 0, sz), at(sx, 0, sz + half), at(sx + half, 0, sz + half), at(sx + half, 0, sz)], uv);
      }
      b.quad(m.ceiling, [at(x0, H, z0), at(x0 + T, H, z0), at(x0 + T, H, z0 + T), at(x0, H, z0 + T)], [[x0 / T, z0 / T], [x0 / T + 1, z0 / T], [x0 / T + 1, z0 / T + 1], [x0 / T, z0 / T + 1]]);

      for (const [dx, dz] of DIRECTIONS) {
        const wr = r + dz, wc = c + dx;
        if (isFloor(map, wr, wc)) continue;
        wallFace(b, map, m, r, c, dx, dz, lines);
        if (map.cells[wr * map.columns + wc] === 'torch') torch(b, m, r, c, dx, dz);
      }
    }
  }
  return { mesh: b.build('dungeon'), lines };
}

/**
 * The face of the wall on side (dx, dz) of floor tile (r, c): wall, plinth front and top, and the
 * walk-map line. n = −(dx, dz) faces into the tile; t = up × n runs along the face, so quads
 * (A, B, B + up, A + up) face n.
 */
function wallFace(b: Builder, map: TileMap, m: LevelMaterials, r: number, c: number, dx: number, dz: number, lines: number[]): void {
  const T = DUNGEON_TILE, H = DUNGEON_HEIGHT, P = PLINTH_HEIGHT, D = PLINTH_DEPTH;
  const [cx, , cz] = tileCentre(r, c);
  const nx = -dx, nz = -dz;
  const tx = nz, tz = -nx;
  // The face's middle on the floor, and a point s along it, e out from it.
  const mx = cx + dx * (T / 2), mz = cz + dz * (T / 2);
  const p = (s: number, y: number, e = 0): Vec3 => at(mx + tx * s + nx * e, y, mz + tz * s + nz * e);
  // u continues along the wall in world units, so the bond runs on from face to face.
  const u = (s: number) => (tx * (mx + tx * s) + tz * (mz + tz * s)) / T;
  const v = (y: number) => (H - y) / T;

  b.quad(m.wall, [p(-T / 2, P), p(T / 2, P), p(T / 2, H), p(-T / 2, H)], [[u(-T / 2), v(P)], [u(T / 2), v(P)], [u(T / 2), v(H)], [u(-T / 2), v(H)]]);
  const [x0, , z0] = p(-T / 2, 0), [x1, , z1] = p(T / 2, 0);
  // The floor lies on side n, and cross(t, n) = nx² + nz² = 1 > 0 in the plan: A to B has the floor on
  // its positive side (lineSectors [0, −1]).
  lines.push(x0, z0, x1, z1);

  // The plinth runs the face's length. Faces along x (n along ±x) adjust at corners so neighbours meet:
  // at an inner corner (the next tile along is wall) it stops short by the other plinth's depth; at an
  // outer corner (the wall ends: the next tile along and the one beyond the wall from it are floor) it
  // runs on by the depth, wrapping round the corner, and closes with an end cap.
  let s0 = -T / 2, s1 = T / 2;
  const caps: number[] = [];
  if (nx !== 0) {
    for (const side of [-1, 1]) {
      const ar = r + side * tz, ac = c + side * tx;
      let end = T / 2;
      if (!isFloor(map, ar, ac)) end -= D;
      else if (isFloor(map, ar + dz, ac + dx)) {
        end += D;
        caps.push(side);
      }
      if (side < 0) s0 = -end;
      else s1 = end;
    }
  }
  b.quad(m.plinth, [p(s0, 0, D), p(s1, 0, D), p(s1, P, D), p(s0, P, D)], [[u(s0), v(0)], [u(s1), v(0)], [u(s1), v(P)], [u(s0), v(P)]]);
  b.quad(m.plinth, [p(s0, P, D), p(s1, P, D), p(s1, P, 0), p(s0, P, 0)], [[u(s0), 0], [u(s1), 0], [u(s1), D / T], [u(s0), D / T]]);
  for (const side of caps) {
    const s = side < 0 ? s0 : s1;
    // Facing along side·t: seen from there, counter-clockwise.
    const quad = side > 0 ? [p(s, 0, D), p(s, 0, 0), p(s, P, 0), p(s, P, D)] : [p(s, 0, 0), p(s, 0, D), p(s, P, D), p(s, P, 0)];
    b.quad(m.plinth, quad, [[0, v(0)], [D / T, v(0)], [D / T, v(P)], [0, v(P)]]);
  }
}

/** A torch on the wall face on side (dx, dz) of floor tile (r, c): an iron sconce and a flame. */
function torch(b: Builder, m: LevelMaterials, r: number, c: number, dx: number, dz: number): void {
  const T = DUNGEON_TILE;
  const [cx, , cz] = tileCentre(r, c);
  const nx = -dx, nz = -dz, tx = nz, tz = -nx;
  const mx = cx + dx * (T / 2), mz = cz + dz * (T / 2);
  const p = (s: number, y: number, e: number): Vec3 => at(mx + tx * s + nx * e, y, mz + tz * s + nz * e);
  const box = (s0: number, s1: number, y0: number, y1: number, e0: number, e1: number) => {
    const flat: [number, number][] = [[0, 0], [1, 0], [1, 1], [0, 1]];
    b.quad(m.iron, [p(s0, y0, e1), p(s1, y0, e1), p(s1, y1, e1), p(s0, y1, e1)], flat); // front
    b.quad(m.iron, [p(s0, y1, e1), p(s1, y1, e1), p(s1, y1, e0), p(s0, y1, e0)], flat); // top
    b.quad(m.iron, [p(s0, y0, e0), p(s1, y0, e0), p(s1, y0, e1), p(s0, y0, e1)], flat); // bottom
    b.quad(m.iron, [p(s1, y0, e1), p(s1, y0, e0), p(s1, y1, e0), p(s1, y1, e1)], flat); // side +t
    b.quad(m.iron, [p(s0, y0, e0), p(s0, y0, e1), p(s0, y1, e1), p(s0, y1, e0)], flat); // side −t
  };
  box(-3, 3, 54, 60, 0, 9);
  // The flame, above the sconce: a teardrop (fan of six triangles) with a diamond core in front of
  // it, in two planes turned 35° either way from the wall's normal (a V), so that it shows from
  // along the corridor too; counter-clockwise in (across, up), so each emits toward the room.
  const turn = (35 * Math.PI) / 180, y0 = 60, e = 5.5;
  const OUTER: readonly (readonly [number, number])[] = [[0, 0], [2.6, 3.5], [2.2, 9], [0, 15], [-2.2, 9], [-2.6, 3.5]];
  const CORE: readonly (readonly [number, number])[] = [[0, 1.5], [1.3, 5], [0, 10.5], [-1.3, 5]];
  for (const side of [-1, 1]) {
    const q = (across: number, y: number, forward = 0): Vec3 => p(Math.cos(turn) * across, y0 + y, e + forward + Math.sin(turn) * across * side);
    const centre = q(0, 6);
    OUTER.forEach(([s0, h0], k) => {
      const [s1, h1] = OUTER[(k + 1) % OUTER.length]!;
      b.triangle(m.flame, centre, q(s0, h0), q(s1, h1));
    });
    const [c0, c1, c2, c3] = CORE.map(([s0, h0]) => q(s0, h0, 0.3)) as [Vec3, Vec3, Vec3, Vec3];
    b.triangle(m.flameCore, c0, c1, c2);
    b.triangle(m.flameCore, c0, c2, c3);
  }
}

/** The phantom's round: a Catmull–Rom loop through the centres of the round's tiles. */
export function phantomPath(map: TileMap): InstancePath {
  const tiles = expandRound(map, PHANTOM_ROUND);
  const points = tiles.map(([r, c]): Vec3 => {
    const [x, , z] = tileCentre(r, c);
    return [x, PHANTOM_FLOAT, z];
  });
  // 28 bobs per lap of 52 tiles: one every 2.5 s or so.
  return { instance: PHANTOM_ID, points, speed: PHANTOM_SPEED, bob: { amplitude: 2.5, perLap: 28 } };
}

function walkMap(lines: number[]): WalkMap {
  const count = lines.length / 4;
  return {
    lines: new Float32Array(lines),
    lineSectors: new Int32Array(count * 2).map((_, i) => (i % 2 === 0 ? 0 : -1)),
    lineBlocks: new Uint8Array(count),
    floors: new Float32Array([0]),
    ceilings: new Float32Array([DUNGEON_HEIGHT]),
    eyeHeight: EYE_HEIGHT,
    stepHeight: MAX_STEP_HEIGHT,
    bodyHeight: PLAYER_HEIGHT,
    radius: PLAYER_RADIUS,
  };
}

export function dungeonScene(): Scene {
  const map = parseTileMap(DUNGEON_MAP);
  const textures = [wallTexture(), floorTexture(), ceilingTexture()];
  const materials: Material[] = [];
  const add = (material: Material) => materials.push(material) - 1;
  const level: LevelMaterials = {
    wall: add(diffuse('wall', [1, 1, 1], [0, 0, 0], { albedoTexture: { texture: 0 } })),
    plinth: add(diffuse('plinth', [0.7, 0.68, 0.66], [0, 0, 0], { albedoTexture: { texture: 0 } })),
    floor: add(diffuse('floor', [1, 1, 1], [0, 0, 0], { albedoTexture: { texture: 1 } })),
    ceiling: add(diffuse('ceiling', [1, 1, 1], [0, 0, 0], { albedoTexture: { texture: 2 } })),
    iron: add(diffuse('iron', [0.05, 0.045, 0.04])),
    flame: add({ kind: 'emissive', name: 'flame', emission: FLAME_EMISSION }),
    flameCore: add({ kind: 'emissive', name: 'flame core', emission: FLAME_CORE_EMISSION }),
  };
  const phantom = {
    robe: add(diffuse('phantom robe', [0.26, 0.3, 0.38], PHANTOM_EMISSION)),
    shadow: add(diffuse('phantom shadow', [0.01, 0.01, 0.012])),
    eyes: add({ kind: 'emissive', name: 'phantom eyes', emission: [2.2, 2.8, 3.4] }),
  };
  const { mesh, lines } = buildLevel(map, level);
  const path = phantomPath(map);
  const start: Mat4 = new CompiledPath(path).poseAt(0);
  const [sx, , sz] = tileCentre(...map.start);
  return {
    name: 'dungeon',
    meshes: [mesh, phantomMesh(phantom)],
    instances: [
      { id: LEVEL_ID, name: 'dungeon', mesh: 0, worldFromObject: IDENTITY },
      { id: PHANTOM_ID, name: 'phantom', mesh: 1, worldFromObject: start, moves: true },
    ],
    materials,
    textures,
    camera: { position: [sx, EYE_HEIGHT, sz], forward: [1, 0, 0], up: [0, 1, 0], vfovDegrees: 70 },
    torch: DOOM_TORCH,
    metersPerUnit: DUNGEON_METERS_PER_UNIT,
    walkMap: walkMap(lines),
    // The tile map as the grid traversal's cells (x along columns, z along rows; one cell of wall height).
    tileGrid: { origin: [0, 0, 0], cellSize: [DUNGEON_TILE, DUNGEON_HEIGHT, DUNGEON_TILE], dims: [map.columns, 1, map.rows] },
    dynamics: { paths: [path] },
  };
}
