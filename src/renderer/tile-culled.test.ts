import { describe, expect, it } from 'vitest';
import { traceScene } from '../bvh/levels.ts';
import { DUNGEON_TILE, dungeonScene, PHANTOM_ID, tileCentre } from '../loaders/builtin/dungeon.ts';
import { EYE_HEIGHT } from '../loaders/doom/map-types.ts';
import { normalize, type Vec3 } from '../math/vec3.ts';
import { CompiledPath } from '../scene/paths.ts';
import { tileAt, tileGridFromWalkMap, tileSquare } from '../scene/tile-culling.ts';
import { prepareScene, updateGeometry, type PreparedScene } from './prepare.ts';
import { geometryBytes, TileCulledScenes } from './tile-culled.ts';

const DISTANCE = 5 * DUNGEON_TILE;
const scene = dungeonScene();
const grid = tileGridFromWalkMap(scene.walkMap!, DUNGEON_TILE);
const full = prepareScene(scene);
const culled = TileCulledScenes.prepare(full, grid, DISTANCE);
const eye = (row: number, column: number): Vec3 => {
  const [x, , z] = tileCentre(row, column);
  return [x, EYE_HEIGHT, z];
};

/** The closest hit's distance along a unit ray, or Infinity. */
const hitT = (p: PreparedScene, origin: Vec3, direction: Vec3): number => traceScene(p.scene, p.triangles, p.bvh, p.levels, { origin, direction })?.t ?? Infinity;

describe('tile-culled scenes', () => {
  it('prepares one scene per walkable tile, smaller than the full one', () => {
    const s = culled.stats();
    console.log(`tile culling: ${s.tiles} tiles, ${s.fullTriangles} triangles in full, mean ${s.meanTriangles.toFixed(0)}, max ${s.maxTriangles}; geometry ${(s.fullGeometryBytes / 1024).toFixed(0)} KiB full, ${(s.tilesGeometryBytes / 1024).toFixed(0)} KiB for all tiles; precompute ${s.precomputeMs.toFixed(0)} ms (CPU, this machine)`);
    expect(s.tiles).toBe(130);
    expect(s.maxTriangles).toBeLessThan(s.fullTriangles);
    expect(s.meanTriangles).toBeLessThan(0.5 * s.fullTriangles);
    for (const p of culled.tiles.values()) expect(geometryBytes(p)).toBeLessThan(geometryBytes(full));
    // Shared, not packed again per tile.
    for (const p of culled.tiles.values()) expect(p.packed.packedMaterials).toBe(full.packed.packedMaterials);
  });

  it('says when the camera steps onto another tile, and falls back to the full scene off the floor', () => {
    const a = culled.select(eye(1, 1));
    expect(a.changed).toBe(true);
    expect(a.tile).toBe(tileAt(grid, ...([eye(1, 1)[0], eye(1, 1)[2]] as const)));
    expect(a.prepared).toBe(culled.tiles.get(a.tile!));
    const [x, y, z] = eye(1, 1);
    expect(culled.select([x + 20, y + 30, z - 20]).changed).toBe(false); // same tile, elsewhere on it
    const b = culled.select(eye(1, 2));
    expect(b.changed).toBe(true);
    expect(b.tile).not.toBe(a.tile);
    const off = culled.select([-500, 40, -500]);
    expect(off).toMatchObject({ tile: undefined, changed: true });
    expect(off.prepared).toBe(full);
    expect(culled.select([-400, 40, -500]).changed).toBe(false);
  });

  it('sees from its tile exactly what the full scene shows within the distance (CPU traversal oracle)', () => {
    let compared = 0, culledAway = 0;
    for (const [row, column] of [[1, 1], [5, 6], [10, 9], [14, 14]] as const) {
      const origin = eye(row, column);
      const { prepared } = culled.select(origin);
      const [x0, z0, x1, z1] = tileSquare(grid, tileAt(grid, origin[0], origin[2])!);
      for (let k = 0; k < 400; k++) {
        // Directions on a spiral over the sphere.
        const y = 1 - (2 * (k + 0.5)) / 400, r = Math.sqrt(1 - y * y), phi = k * 2.399963;
        const d = normalize([r * Math.cos(phi), y, r * Math.sin(phi)]);
        const tFull = hitT(full, origin, d);
        const px = origin[0] + d[0] * tFull, pz = origin[2] + d[2] * tFull;
        const planDistance = Math.hypot(Math.max(0, x0 - px, px - x1), Math.max(0, z0 - pz, pz - z1));
        const tCulled = hitT(prepared, origin, d);
        if (planDistance <= DISTANCE - 1e-3) {
          expect(tCulled).toBeCloseTo(tFull, 3);
          compared++;
        } else if (tCulled !== tFull) culledAway++;
      }
    }
    console.log(`rays: ${compared} hits within the distance agree; ${culledAway} beyond it differ`);
    expect(compared).toBeGreaterThan(1200);
  });

  it('hands a newly chosen tile the poses of everything that moved since loading', () => {
    const path = new CompiledPath(scene.dynamics!.paths![0]!);
    const pose = path.poseAt(3);
    const update = { instances: new Map([[PHANTOM_ID, { worldFromObject: pose }]]), morphWeights: new Map(), materials: new Map(), walkHeights: new Map() };
    const fresh = new TileCulledScenes(grid, full, culled.tiles);
    fresh.noteUpdate(update);
    const from = eye(1, 1);
    const selection = fresh.select(from);
    expect(selection.catchUp.instances.get(PHANTOM_ID)?.worldFromObject).toEqual(pose);
    const caughtUp = updateGeometry(selection.prepared, selection.catchUp.instances, selection.catchUp.morphWeights).prepared;
    const fullMoved = updateGeometry(full, update.instances, update.morphWeights).prepared;
    // Aim at the phantom's chest where it now is: both scenes hit it at the same distance, and not where it stood.
    const target: Vec3 = [pose[12]!, pose[13]! + 30, pose[14]!];
    const d = normalize([target[0] - from[0], target[1] - from[1], target[2] - from[2]]);
    const dist = Math.hypot(target[0] - from[0], target[1] - from[1], target[2] - from[2]);
    const tMoved = hitT(caughtUp, from, d);
    expect(tMoved).toBeCloseTo(hitT(fullMoved, from, d), 4);
    expect(tMoved).toBeLessThan(dist);
    expect(tMoved).toBeGreaterThan(dist - 20);
    expect(hitT(selection.prepared, from, d)).not.toBeCloseTo(tMoved, 0);
  });
});
