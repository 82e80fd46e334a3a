/**
 * Distance culling per floor tile (the trick of the dungeon's seed, Lantern issue #12 §4): for every
 * walkable tile of a grid laid over a walk map, the scene with only the static triangles within a
 * distance of that tile, precomputed, so a renderer can trace a much smaller BVH and swap to the next
 * one when the viewer steps onto another tile (renderer/tile-culled.ts).
 *
 * "Within d of the tile" is measured in the plan (x, z): the distance from the triangle's projection
 * to the tile's square. The viewer stands anywhere above the square, at any height, so this is the
 * least 3D distance from the tile's column to the triangle, and every triangle that could be within d
 * of the eye is kept. What lies farther is gone for every ray, light included: the approximation the
 * trick makes (the dungeon's walls hide most of it).
 *
 * Instances that move, and meshes with morph targets, are kept whole: they may be anywhere later.
 * Mesh indices and instance ids stay as in the scene (culled meshes are appended), so SceneUpdates
 * apply to a culled scene unchanged. Spheres and capsules are kept when their box's plan is within d
 * (conservative). Pure.
 */
import { LanternError } from '../errors.ts';
import { transformPoint } from '../math/mat4.ts';
import type { Instance, Mesh, Scene } from './types.ts';
import { NO_SECTOR, sectorAt, type WalkMap } from './walk-map.ts';

/** A grid of square tiles over the plan: tile (row, column) covers x ∈ originX + [column, column + 1)·size, z likewise by row. */
export interface TileGrid {
  readonly originX: number;
  readonly originZ: number;
  readonly size: number;
  readonly columns: number;
  readonly rows: number;
  /** Row-major: 1 where the tile's centre stands on the walk map's floor. */
  readonly walkable: Uint8Array;
}

/**
 * The grid of `size`-unit tiles over a walk map's lines, its corner at their smallest x and z (for a
 * tile map, a tile corner); a tile is walkable when its centre lies in a sector.
 */
export function tileGridFromWalkMap(map: WalkMap, size: number): TileGrid {
  if (!(size > 0) || !Number.isFinite(size)) throw new LanternError(`tile culling: the tile size must be a finite number > 0, not ${size}`);
  const L = map.lines;
  if (L.length === 0) throw new LanternError('tile culling needs a walk map with lines');
  let minX = Infinity, minZ = Infinity, maxX = -Infinity, maxZ = -Infinity;
  for (let i = 0; i < L.length; i += 2) {
    minX = Math.min(minX, L[i]!);
    maxX = Math.max(maxX, L[i]!);
    minZ = Math.min(minZ, L[i + 1]!);
    maxZ = Math.max(maxZ, L[i + 1]!);
  }
  const columns = Math.max(1, Math.ceil((maxX - minX) / size)), rows = Math.max(1, Math.ceil((maxZ - minZ) / size));
  const walkable = new Uint8Array(columns * rows);
  for (let r = 0; r < rows; r++) {
    for (let c = 0; c < columns; c++) walkable[r * columns + c] = sectorAt(map, minX + (c + 0.5) * size, minZ + (r + 0.5) * size) === NO_SECTOR ? 0 : 1;
  }
  return { originX: minX, originZ: minZ, size, columns, rows, walkable };
}

/** The walkable tile under (x, z), or undefined (off the grid, or not walkable). */
export function tileAt(grid: TileGrid, x: number, z: number): number | undefined {
  const c = Math.floor((x - grid.originX) / grid.size), r = Math.floor((z - grid.originZ) / grid.size);
  if (c < 0 || r < 0 || c >= grid.columns || r >= grid.rows) return undefined;
  const tile = r * grid.columns + c;
  return grid.walkable[tile] ? tile : undefined;
}

/** Every walkable tile's index. */
export function walkableTiles(grid: TileGrid): number[] {
  const out: number[] = [];
  grid.walkable.forEach((w, i) => {
    if (w) out.push(i);
  });
  return out;
}

/** The tile's square in the plan: x0, z0, x1, z1. */
export function tileSquare(grid: TileGrid, tile: number): [number, number, number, number] {
  const c = tile % grid.columns, r = Math.floor(tile / grid.columns);
  const x0 = grid.originX + c * grid.size, z0 = grid.originZ + r * grid.size;
  return [x0, z0, x0 + grid.size, z0 + grid.size];
}

/** Squared distance from point p to segment a–b in the plan. */
function pointSegment2(px: number, pz: number, ax: number, az: number, bx: number, bz: number): number {
  const ex = bx - ax, ez = bz - az;
  const len2 = ex * ex + ez * ez;
  const t = len2 > 0 ? Math.max(0, Math.min(1, ((px - ax) * ex + (pz - az) * ez) / len2)) : 0;
  const dx = ax + t * ex - px, dz = az + t * ez - pz;
  return dx * dx + dz * dz;
}

const orient = (ax: number, az: number, bx: number, bz: number, cx: number, cz: number) => (bx - ax) * (cz - az) - (bz - az) * (cx - ax);

/** Whether segments a–b and c–d cross or touch (in the plan). */
function segmentsMeet(ax: number, az: number, bx: number, bz: number, cx: number, cz: number, dx: number, dz: number): boolean {
  const o1 = orient(ax, az, bx, bz, cx, cz), o2 = orient(ax, az, bx, bz, dx, dz), o3 = orient(cx, cz, dx, dz, ax, az), o4 = orient(cx, cz, dx, dz, bx, bz);
  return ((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0));
}

/**
 * Distance in the plan from the triangle (x, z per vertex: 6 numbers) to the square [x0, x1] × [z0, z1]:
 * 0 when they overlap, else the least distance between their edges (convex polygons). A triangle seen
 * edge-on from above (a wall) is the segment it projects to.
 */
export function triangleSquareDistance(t: ArrayLike<number>, x0: number, z0: number, x1: number, z1: number): number {
  for (let k = 0; k < 3; k++) {
    const x = t[k * 2]!, z = t[k * 2 + 1]!;
    if (x >= x0 && x <= x1 && z >= z0 && z <= z1) return 0;
  }
  const area = orient(t[0]!, t[1]!, t[2]!, t[3]!, t[4]!, t[5]!);
  const corners = [x0, z0, x1, z0, x1, z1, x0, z1];
  if (area !== 0) {
    for (let k = 0; k < 4; k++) {
      const cx = corners[k * 2]!, cz = corners[k * 2 + 1]!;
      const s = Math.sign(area);
      if (s * orient(t[0]!, t[1]!, t[2]!, t[3]!, cx, cz) >= 0 && s * orient(t[2]!, t[3]!, t[4]!, t[5]!, cx, cz) >= 0 && s * orient(t[4]!, t[5]!, t[0]!, t[1]!, cx, cz) >= 0) return 0;
    }
  }
  let best = Infinity;
  for (let i = 0; i < 3; i++) {
    const ax = t[i * 2]!, az = t[i * 2 + 1]!, bx = t[((i + 1) % 3) * 2]!, bz = t[((i + 1) % 3) * 2 + 1]!;
    for (let k = 0; k < 4; k++) {
      const cx = corners[k * 2]!, cz = corners[k * 2 + 1]!, dx = corners[((k + 1) % 4) * 2]!, dz = corners[((k + 1) % 4) * 2 + 1]!;
      if (segmentsMeet(ax, az, bx, bz, cx, cz, dx, dz)) return 0;
      best = Math.min(best, pointSegment2(ax, az, cx, cz, dx, dz), pointSegment2(cx, cz, ax, az, bx, bz));
    }
  }
  return Math.sqrt(best);
}

/** Distance in the plan from the box [ax0, ax1] × [az0, az1] to the square (0 when they overlap). */
const boxSquareDistance = (ax0: number, az0: number, ax1: number, az1: number, x0: number, z0: number, x1: number, z1: number) =>
  Math.hypot(Math.max(0, ax0 - x1, x0 - ax1), Math.max(0, az0 - z1, z0 - az1));

/** A static instance's mesh, culled: what of it lies within `distance` of the square, vertices compacted; undefined when nothing does. */
function cullMesh(mesh: Mesh, inst: Instance, square: readonly number[], distance: number): Mesh | undefined {
  const [x0, z0, x1, z1] = square as [number, number, number, number];
  const m = inst.worldFromObject;
  const P = mesh.positions;
  const vertexCount = P.length / 3;
  const plan = new Float64Array(vertexCount * 2);
  for (let v = 0; v < vertexCount; v++) {
    const w = transformPoint(m, [P[v * 3]!, P[v * 3 + 1]!, P[v * 3 + 2]!]);
    plan[v * 2] = w[0];
    plan[v * 2 + 1] = w[2];
  }
  const keep: number[] = [];
  const tri = new Float64Array(6);
  for (let t = 0; t < mesh.indices.length / 3; t++) {
    for (let k = 0; k < 3; k++) {
      const v = mesh.indices[t * 3 + k]!;
      tri[k * 2] = plan[v * 2]!;
      tri[k * 2 + 1] = plan[v * 2 + 1]!;
    }
    if (triangleSquareDistance(tri, x0, z0, x1, z1) <= distance) keep.push(t);
  }
  const near = (box: [number, number, number, number]) => boxSquareDistance(box[0], box[1], box[2], box[3], x0, z0, x1, z1) <= distance;
  const spheres = mesh.spheres ? pickAnalytic(mesh.spheres.radii.length, (i) => near(planBox(m, [mesh.spheres!.centers.subarray(i * 3, i * 3 + 3)], mesh.spheres!.radii[i]!))) : [];
  const capsules = mesh.capsules ? pickAnalytic(mesh.capsules.radii.length, (i) => near(planBox(m, [mesh.capsules!.endpoints.subarray(i * 6, i * 6 + 3), mesh.capsules!.endpoints.subarray(i * 6 + 3, i * 6 + 6)], mesh.capsules!.radii[i]!))) : [];
  if (keep.length === 0 && spheres.length === 0 && capsules.length === 0) return undefined;

  // Compact the vertices the kept triangles use.
  const remap = new Int32Array(vertexCount).fill(-1);
  const used: number[] = [];
  const indices = new Uint32Array(keep.length * 3);
  keep.forEach((t, i) => {
    for (let k = 0; k < 3; k++) {
      const v = mesh.indices[t * 3 + k]!;
      if (remap[v] === -1) {
        remap[v] = used.length;
        used.push(v);
      }
      indices[i * 3 + k] = remap[v]!;
    }
  });
  const gather = (a: Float32Array | undefined, n: number) => {
    if (!a) return undefined;
    const out = new Float32Array(used.length * n);
    used.forEach((v, i) => out.set(a.subarray(v * n, v * n + n), i * n));
    return out;
  };
  const optional = <K extends string>(key: K, value: Float32Array | undefined) => (value ? ({ [key]: value } as Record<K, Float32Array>) : {});
  return {
    name: `${mesh.name} (culled)`,
    positions: gather(mesh.positions, 3)!,
    indices,
    materialIds: new Uint32Array(keep.map((t) => mesh.materialIds[t]!)),
    ...optional('normals', gather(mesh.normals, 3)),
    ...optional('uvs', gather(mesh.uvs, 2)),
    ...optional('uvs1', gather(mesh.uvs1, 2)),
    ...optional('tangents', gather(mesh.tangents, 4)),
    ...(mesh.spheres && spheres.length > 0
      ? { spheres: { centers: new Float32Array(spheres.flatMap((i) => [...mesh.spheres!.centers.subarray(i * 3, i * 3 + 3)])), radii: new Float32Array(spheres.map((i) => mesh.spheres!.radii[i]!)), materialIds: new Uint32Array(spheres.map((i) => mesh.spheres!.materialIds[i]!)) } }
      : {}),
    ...(mesh.capsules && capsules.length > 0
      ? { capsules: { endpoints: new Float32Array(capsules.flatMap((i) => [...mesh.capsules!.endpoints.subarray(i * 6, i * 6 + 6)])), radii: new Float32Array(capsules.map((i) => mesh.capsules!.radii[i]!)), materialIds: new Uint32Array(capsules.map((i) => mesh.capsules!.materialIds[i]!)) } }
      : {}),
  };
}

function pickAnalytic(count: number, near: (i: number) => boolean): number[] {
  const out: number[] = [];
  for (let i = 0; i < count; i++) if (near(i)) out.push(i);
  return out;
}

/** The plan box of spheres of object radius r around object points, in the world (radius scaled by the transform's largest axis). */
function planBox(m: readonly number[], points: readonly ArrayLike<number>[], r: number): [number, number, number, number] {
  const scale = Math.max(Math.hypot(m[0]!, m[1]!, m[2]!), Math.hypot(m[4]!, m[5]!, m[6]!), Math.hypot(m[8]!, m[9]!, m[10]!));
  const rr = r * scale;
  let x0 = Infinity, z0 = Infinity, x1 = -Infinity, z1 = -Infinity;
  for (const p of points) {
    const w = transformPoint(m, [p[0]!, p[1]!, p[2]!]);
    x0 = Math.min(x0, w[0] - rr);
    x1 = Math.max(x1, w[0] + rr);
    z0 = Math.min(z0, w[2] - rr);
    z1 = Math.max(z1, w[2] + rr);
  }
  return [x0, z0, x1, z1];
}

/**
 * `scene` as seen from `tile`: static instances keep only what lies within `distance` of the tile
 * (each as a culled mesh of its own, appended after the scene's meshes); moving and morphing
 * instances are kept whole; instances left with nothing are dropped.
 */
export function cullSceneToTile(scene: Scene, grid: TileGrid, tile: number, distance: number): Scene {
  if (!(distance >= 0) || !Number.isFinite(distance)) throw new LanternError(`tile culling: the distance must be a finite number ≥ 0, not ${distance}`);
  if (!grid.walkable[tile]) throw new LanternError(`tile culling: tile ${tile} is not a walkable tile of the grid`);
  const square = tileSquare(grid, tile);
  const meshes: Mesh[] = [...scene.meshes];
  const instances: Instance[] = [];
  for (const inst of scene.instances) {
    const mesh = scene.meshes[inst.mesh]!;
    if (inst.moves || mesh.morphTargets?.length) {
      instances.push(inst);
      continue;
    }
    const culled = cullMesh(mesh, inst, square, distance);
    if (!culled) continue;
    meshes.push(culled);
    instances.push({ ...inst, mesh: meshes.length - 1 });
  }
  return { ...scene, name: `${scene.name} (tile ${tile})`, meshes, instances };
}

/** The culled scene of every walkable tile, by tile index. */
export function tileCulledScenes(scene: Scene, grid: TileGrid, distance: number): Map<number, Scene> {
  return new Map(walkableTiles(grid).map((tile) => [tile, cullSceneToTile(scene, grid, tile, distance)]));
}

/** Triangles an instance draws in `scene` (meshes no instance names are not drawn). */
export function drawnTriangles(scene: Scene): number {
  return scene.instances.reduce((n, inst) => n + scene.meshes[inst.mesh]!.indices.length / 3, 0);
}

/** The seed's tile (2 m) and culling distance (10 units of its 2-unit tiles: five tiles, 10 m). */
export const TILE_CULLING_TILE_METERS = 2;
export const TILE_CULLING_DISTANCE_METERS = 10;

/**
 * The grid and distance a renderer uses for `scene` when per-tile culling is on: tiles of 2 m over
 * its walk map, everything within 10 m kept (the dungeon: 64-unit tiles, 320 units). Undefined for a
 * scene without a walk map or a known unit size, which the trick does not apply to.
 */
export function defaultTileCulling(scene: Scene): { readonly grid: TileGrid; readonly distance: number } | undefined {
  if (!scene.walkMap || !scene.metersPerUnit) return undefined;
  return { grid: tileGridFromWalkMap(scene.walkMap, TILE_CULLING_TILE_METERS / scene.metersPerUnit), distance: TILE_CULLING_DISTANCE_METERS / scene.metersPerUnit };
}
