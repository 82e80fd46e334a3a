import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../expect-lantern-error.ts';
import { DUNGEON_MAP, isFloor, parseTileMap } from '../loaders/builtin/dungeon-map.ts';
import { DUNGEON_TILE, dungeonScene, PHANTOM_ID } from '../loaders/builtin/dungeon.ts';
import { flattenTriangles } from './triangles.ts';
import { cullSceneToTile, defaultTileCulling, drawnTriangles, tileAt, tileGridFromWalkMap, tileSquare, triangleSquareDistance, walkableTiles } from './tile-culling.ts';
import { validateScene } from './validate.ts';

/** The distance: 10 units of the seed's 2-unit tiles, five tiles. */
const DISTANCE = 5 * DUNGEON_TILE;
const scene = dungeonScene();
const grid = tileGridFromWalkMap(scene.walkMap!, DUNGEON_TILE);

/** A small deterministic generator (xorshift32) for the random cases. */
function rng(seed: number): () => number {
  let s = seed >>> 0 || 1;
  return () => {
    s ^= s << 13;
    s ^= s >>> 17;
    s ^= s << 5;
    return (s >>> 0) / 4294967296;
  };
}

/**
 * Distance from a triangle to a square in the plan by brute force: a dense sampling of both (the
 * triangle by barycentric grid, the square's boundary and inside). An upper bound on the true
 * distance, within about one sampling step of it.
 */
function sampledDistance(t: readonly number[], [x0, z0, x1, z1]: readonly number[], n = 24): number {
  const tri: [number, number][] = [];
  for (let i = 0; i <= n; i++) {
    for (let j = 0; j <= n - i; j++) {
      const a = i / n, b = j / n, c = 1 - a - b;
      tri.push([a * t[0]! + b * t[2]! + c * t[4]!, a * t[1]! + b * t[3]! + c * t[5]!]);
    }
  }
  let best = Infinity;
  for (const [x, z] of tri) {
    // The nearest point of the square to (x, z), exactly: clamping is the brute force's own oracle-free step.
    const dx = Math.max(0, x0! - x, x - x1!), dz = Math.max(0, z0! - z, z - z1!);
    best = Math.min(best, Math.hypot(dx, dz));
  }
  return best;
}

describe('triangle to square distance', () => {
  it('agrees with dense sampling on random triangles, overlapping ones at 0', () => {
    const r = rng(12);
    let zero = 0;
    for (let k = 0; k < 400; k++) {
      const t = Array.from({ length: 6 }, () => r() * 20 - 10);
      if (k % 5 === 0) {
        // Triangles seen edge-on: all three on a line.
        t[4] = (t[0]! + t[2]!) / 2;
        t[5] = (t[1]! + t[3]!) / 2;
      }
      const square = [-1, -2, 1.5, 0.5];
      const exact = triangleSquareDistance(t, square[0]!, square[1]!, square[2]!, square[3]!);
      const sampled = sampledDistance(t, square, 60);
      const step = Math.max(Math.hypot(t[0]! - t[2]!, t[1]! - t[3]!), Math.hypot(t[2]! - t[4]!, t[3]! - t[5]!), Math.hypot(t[4]! - t[0]!, t[5]! - t[1]!)) / 60;
      expect(exact).toBeLessThanOrEqual(sampled + 1e-9);
      expect(sampled - exact).toBeLessThanOrEqual(step + 1e-9);
      if (exact === 0) zero++;
    }
    expect(zero).toBeGreaterThan(20);
    expect(zero).toBeLessThan(380);
  });
});

describe('tile culling on the dungeon', () => {
  const map = parseTileMap(DUNGEON_MAP);

  it('lays a 16 × 16 grid over the walk map whose walkable tiles are the floor tiles', () => {
    // The walk map's lines bound the floor, which starts one tile in from the map's edge.
    expect([grid.columns, grid.rows, grid.originX, grid.originZ]).toEqual([14, 14, DUNGEON_TILE, DUNGEON_TILE]);
    const walkable = walkableTiles(grid);
    expect(walkable.length).toBe(130);
    for (const tile of walkable) {
      const r = Math.floor(tile / grid.columns) + 1, c = (tile % grid.columns) + 1;
      expect(isFloor(map, r, c)).toBe(true);
      const [x0, z0] = tileSquare(grid, tile);
      expect(tileAt(grid, x0 + 1, z0 + 63)).toBe(tile);
    }
    expect(tileAt(grid, -5, 100)).toBeUndefined();
    // Map row 2, column 2 is wall.
    expect(isFloor(map, 2, 2)).toBe(false);
    expect(tileAt(grid, 2.5 * DUNGEON_TILE, 2.5 * DUNGEON_TILE)).toBeUndefined();
  });

  it('keeps every static triangle within the distance of the tile and none far beyond, and the phantom whole', () => {
    const world = flattenTriangles(scene);
    const staticTriangles = scene.meshes[0]!.indices.length / 3;
    const tiles = walkableTiles(grid);
    const r = rng(3);
    const picked = [tiles[0]!, tiles[tiles.length - 1]!, ...Array.from({ length: 3 }, () => tiles[Math.floor(r() * tiles.length)]!)];
    for (const tile of picked) {
      const square = tileSquare(grid, tile);
      const culled = cullSceneToTile(scene, grid, tile, DISTANCE);
      expect(() => validateScene(culled)).not.toThrow();
      // The phantom (moves) is there whole, under its own id and mesh.
      const phantom = culled.instances.find((i) => i.id === PHANTOM_ID)!;
      expect(phantom.mesh).toBe(1);
      const level = culled.instances.find((i) => i.id === 0)!;
      const mesh = culled.meshes[level.mesh]!;
      // Brute force: which of the level's triangles lie within the distance, by sampling.
      const kept = new Set<string>();
      const key = (xs: ArrayLike<number>) => Array.from(xs, (v) => v.toFixed(3)).join(',');
      for (let t = 0; t < mesh.indices.length / 3; t++) kept.add(key([0, 1, 2].flatMap((k) => [...mesh.positions.subarray(mesh.indices[t * 3 + k]! * 3, mesh.indices[t * 3 + k]! * 3 + 3)])));
      let within = 0;
      for (let t = 0; t < staticTriangles; t++) {
        const p = world.positions.subarray(t * 9, t * 9 + 9);
        const d = sampledDistance([p[0]!, p[2]!, p[3]!, p[5]!, p[6]!, p[8]!], square);
        const isKept = kept.has(key(p));
        // Sampling over-estimates by at most a step of the triangle's 24-division (≤ 64·√2/24 ≈ 3.8 units).
        if (d <= DISTANCE) {
          within++;
          expect(isKept).toBe(true);
        }
        if (isKept) expect(d).toBeLessThanOrEqual(DISTANCE + 4);
      }
      expect(mesh.indices.length / 3).toBeGreaterThanOrEqual(within);
      expect(drawnTriangles(culled)).toBe(mesh.indices.length / 3 + scene.meshes[1]!.indices.length / 3);
    }
  });

  it('cuts the dungeon to well under half of itself per tile', () => {
    const full = drawnTriangles(scene);
    const counts = walkableTiles(grid).map((tile) => drawnTriangles(cullSceneToTile(scene, grid, tile, DISTANCE)));
    const mean = counts.reduce((a, b) => a + b, 0) / counts.length;
    console.log(`tile culling at ${DISTANCE} units: ${full} triangles in full, per tile mean ${mean.toFixed(0)}, max ${Math.max(...counts)}, min ${Math.min(...counts)}`);
    expect(Math.max(...counts)).toBeLessThan(full);
    expect(mean).toBeLessThan(0.5 * full);
    // A larger distance keeps more; one covering the whole map keeps everything.
    const tile = walkableTiles(grid)[40]!;
    expect(drawnTriangles(cullSceneToTile(scene, grid, tile, 2 * DISTANCE))).toBeGreaterThan(drawnTriangles(cullSceneToTile(scene, grid, tile, DISTANCE)));
    expect(drawnTriangles(cullSceneToTile(scene, grid, tile, 100 * DUNGEON_TILE))).toBe(full);
  });

  it('defaults to 2 m tiles and 10 m for a scene with a walk map and a unit size, and to nothing otherwise', () => {
    const d = defaultTileCulling(scene)!;
    expect(d.distance).toBe(DISTANCE);
    expect(d.grid).toEqual(grid);
    expect(defaultTileCulling({ ...scene, walkMap: undefined })).toBeUndefined();
    expect(defaultTileCulling({ ...scene, metersPerUnit: undefined })).toBeUndefined();
  });

  it('refuses a tile that is not walkable, a bad distance or a bad tile size', () => {
    const wall = grid.walkable.indexOf(0);
    expectLanternError(() => cullSceneToTile(scene, grid, wall, DISTANCE), new RegExp(`tile ${wall} is not a walkable tile`));
    expectLanternError(() => cullSceneToTile(scene, grid, walkableTiles(grid)[0]!, -1), /distance must be a finite number ≥ 0/);
    expectLanternError(() => tileGridFromWalkMap(scene.walkMap!, 0), /tile size/);
  });
});
