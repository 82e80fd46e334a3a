import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../../expect-lantern-error.ts';
import { transformDirection, transformPoint } from '../../math/mat4.ts';
import { cross, normalize, sub, type Vec3 } from '../../math/vec3.ts';
import { CompiledPath } from '../../scene/paths.ts';
import { flattenTriangles } from '../../scene/triangles.ts';
import { validateScene } from '../../scene/validate.ts';
import { moveWalker, NO_SECTOR, sectorAt } from '../../scene/walk-map.ts';
import { sceneUpdateAt } from '../../world/world.ts';
import { DUNGEON_MAP, isFloor, parseTileMap } from './dungeon-map.ts';
import { DUNGEON_HEIGHT, DUNGEON_TILE, dungeonScene, PHANTOM_ID, PHANTOM_SPEED, tileCentre } from './dungeon.ts';
import { PHANTOM_HEIGHT, PHANTOM_RADIUS } from './phantom.ts';

const scene = dungeonScene();
const map = parseTileMap(DUNGEON_MAP);
const walk = scene.walkMap!;
const tileOf = (x: number, z: number): [number, number] => [Math.floor(z / DUNGEON_TILE), Math.floor(x / DUNGEON_TILE)];
const DIRS: [number, number][] = [[1, 0], [-1, 0], [0, 1], [0, -1]];
const VIEW = { position: [0, 0, 0] as Vec3, forward: [1, 0, 0] as Vec3 };

/** Least distance in the plan from (x, z) to any wall face (the walk map's lines). */
function wallDistance(x: number, z: number): number {
  const L = walk.lines;
  let best = Infinity;
  for (let i = 0; i < L.length; i += 4) {
    const ax = L[i]!, az = L[i + 1]!, ex = L[i + 2]! - ax, ez = L[i + 3]! - az;
    const t = Math.max(0, Math.min(1, ((x - ax) * ex + (z - az) * ez) / (ex * ex + ez * ez)));
    best = Math.min(best, Math.hypot(ax + t * ex - x, az + t * ez - z));
  }
  return best;
}

describe('dungeon map', () => {
  it('has about 130 floor tiles, every one reachable from the start, and about 3,000 triangles', () => {
    const floor: [number, number][] = [];
    for (let r = 0; r < map.rows; r++) for (let c = 0; c < map.columns; c++) if (isFloor(map, r, c)) floor.push([r, c]);
    expect([map.rows, map.columns]).toEqual([16, 16]);
    expect(floor.length).toBe(130);
    const seen = new Set([`${map.start[0]},${map.start[1]}`]);
    const queue = [map.start];
    while (queue.length > 0) {
      const [r, c] = queue.pop()!;
      for (const [dc, dr] of DIRS) {
        const key = `${r + dr},${c + dc}`;
        if (isFloor(map, r + dr, c + dc) && !seen.has(key)) {
          seen.add(key);
          queue.push([r + dr, c + dc]);
        }
      }
    }
    expect(seen.size).toBe(floor.length);
    const triangles = flattenTriangles(scene).count;
    console.log(`dungeon: ${floor.length} floor tiles, ${triangles} triangles (level ${scene.meshes[0]!.indices.length / 3}, phantom ${scene.meshes[1]!.indices.length / 3})`);
    expect(triangles).toBeGreaterThan(2600);
    expect(triangles).toBeLessThan(3600);
    expect(() => validateScene(scene)).not.toThrow();
  });

  it('refuses malformed maps with the problem named', () => {
    expectLanternError(() => parseTileMap('###\n#S#\n##'), /row 2 has 2 tiles, not 3/);
    expectLanternError(() => parseTileMap('###\n#.#\n###'), /no start/);
    expectLanternError(() => parseTileMap('####\n#SS#\n####'), /two starts/);
    expectLanternError(() => parseTileMap('###\n#x#\n###'), /unknown tile 'x'/);
    expectLanternError(() => parseTileMap('#S#\n#.#\n###'), /row 0 column 1: floor on the edge/);
  });

  it('every flame emits into the floor tile in front of its wall', () => {
    const mesh = scene.meshes[0]!;
    const flames = new Set(scene.materials.flatMap((m, i) => (m.name.startsWith('flame') ? [i] : [])));
    expect(flames.size).toBe(2);
    const P = mesh.positions;
    const v = (i: number): Vec3 => [P[i * 3]!, P[i * 3 + 1]!, P[i * 3 + 2]!];
    let flameTriangles = 0;
    for (let t = 0; t < mesh.indices.length / 3; t++) {
      if (!flames.has(mesh.materialIds[t]!)) continue;
      flameTriangles++;
      const [a, b, c] = [0, 1, 2].map((k) => v(mesh.indices[t * 3 + k]!)) as [Vec3, Vec3, Vec3];
      const n = normalize(cross(sub(b, a), sub(c, a)));
      const centroid: Vec3 = [(a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3, (a[2] + b[2] + c[2]) / 3];
      // A step along the normal moves away from the wall (toward the tile's centre), a step against it toward the wall.
      const ahead = wallDistance(centroid[0] + n[0] * 2, centroid[2] + n[2] * 2), behind = wallDistance(centroid[0] - n[0] * 2, centroid[2] - n[2] * 2);
      expect(ahead).toBeGreaterThan(behind);
      expect(isFloor(map, ...tileOf(centroid[0], centroid[2]))).toBe(true);
    }
    // Per torch face, two planes of a six-triangle teardrop and a two-triangle core.
    let torchFaces = 0;
    for (let r = 0; r < map.rows; r++) for (let c = 0; c < map.columns; c++) if (isFloor(map, r, c)) for (const [dc, dr] of DIRS) if (map.cells[(r + dr) * map.columns + c + dc] === 'torch') torchFaces++;
    expect(torchFaces).toBeGreaterThan(10);
    expect(flameTriangles).toBe(16 * torchFaces);
  });
});

describe('dungeon walk map', () => {
  it('puts every floor tile in the one sector and every wall tile outside it', () => {
    for (let r = 0; r < map.rows; r++) {
      for (let c = 0; c < map.columns; c++) {
        const [x, , z] = tileCentre(r, c);
        expect(sectorAt(walk, x, z)).toBe(isFloor(map, r, c) ? 0 : NO_SECTOR);
      }
    }
    expect(walk.ceilings[0]! - walk.floors[0]!).toBe(DUNGEON_HEIGHT);
  });

  it('stops a walker pushed into a wall inside its tile, and lets it through an opening', () => {
    let blocked = 0, open = 0;
    for (let r = 0; r < map.rows; r++) {
      for (let c = 0; c < map.columns; c++) {
        if (!isFloor(map, r, c)) continue;
        const [x, , z] = tileCentre(r, c);
        for (const [dc, dr] of DIRS) {
          const end = moveWalker(walk, { x, z, sector: 0 }, dc * 100, dr * 100);
          if (isFloor(map, r + dr, c + dc)) {
            // Through the opening: it leaves its tile.
            expect(tileOf(end.x, end.z)).not.toEqual([r, c]);
            open++;
          } else {
            expect(tileOf(end.x, end.z)).toEqual([r, c]);
            // Against the wall, a body radius from it.
            expect(wallDistance(end.x, end.z)).toBeGreaterThanOrEqual(walk.radius * 0.999);
            expect(end.sector).toBe(0);
            blocked++;
          }
        }
      }
    }
    expect(blocked).toBeGreaterThan(150);
    expect(open).toBeGreaterThan(150);
  });
});

describe('the phantom', () => {
  const path = new CompiledPath(scene.dynamics!.paths![0]!);

  it('walks only floor tiles and never comes within its radius of a wall', () => {
    let nearest = Infinity;
    for (let i = 0; i < 5000; i++) {
      const [x, , z] = path.positionAt((i / 5000) * path.length);
      expect(isFloor(map, ...tileOf(x, z))).toBe(true);
      nearest = Math.min(nearest, wallDistance(x, z));
    }
    console.log(`phantom: lap ${path.length.toFixed(0)} units in ${path.lapSeconds.toFixed(1)} s; nearest wall ${nearest.toFixed(1)} units, its radius ${PHANTOM_RADIUS.toFixed(1)}`);
    expect(nearest).toBeGreaterThan(PHANTOM_RADIUS);
    // Its crown stays under the ceiling through the bob.
    const ys = Array.from({ length: 500 }, (_, i) => transformPoint(path.poseAt((i / 500) * path.lapSeconds), [0, PHANTOM_HEIGHT, 0])[1]);
    expect(Math.max(...ys)).toBeLessThan(DUNGEON_HEIGHT);
    expect(Math.min(...ys)).toBeGreaterThan(0);
  });

  it('moves at 1.5 m/s, continuously and periodically, facing its way', () => {
    expect(PHANTOM_SPEED * scene.metersPerUnit!).toBeCloseTo(1.5, 12);
    const dt = 1 / 120;
    for (let i = 0; i < 600; i++) {
      const t = (i / 600) * path.lapSeconds;
      const a = path.poseAt(t), b = path.poseAt(t + dt);
      const step = Math.hypot(b[12]! - a[12]!, b[14]! - a[14]!);
      expect(step).toBeGreaterThan(PHANTOM_SPEED * dt * 0.97);
      expect(step).toBeLessThan(PHANTOM_SPEED * dt * 1.01);
      for (let k = 0; k < 12; k++) expect(Math.abs(b[k]! - a[k]!)).toBeLessThan(0.05);
      const later = path.poseAt(t + path.lapSeconds);
      for (let k = 0; k < 16; k++) expect(later[k]!).toBeCloseTo(a[k]!, 5);
      // Object +z along the way it goes.
      const facing = transformDirection(a, [0, 0, 1]);
      const way = normalize([b[12]! - a[12]!, 0, b[14]! - a[14]!]);
      expect(facing[0] * way[0] + facing[2] * way[2]).toBeGreaterThan(0.95);
    }
  });

  it('is loaded where the world puts it at t = 0, coming toward the player, and the World moves it', () => {
    const instance = scene.instances.find((i) => i.id === PHANTOM_ID)!;
    expect(instance.moves).toBe(true);
    const atZero = sceneUpdateAt(scene, 0, VIEW).instances.get(PHANTOM_ID)!.worldFromObject!;
    for (let k = 0; k < 16; k++) expect(instance.worldFromObject[k]!).toBeCloseTo(atZero[k]!, 9);
    // In the player's corridor, ahead of the camera, facing it.
    const p = transformPoint(atZero, [0, 0, 0]);
    expect(tileOf(p[0], p[2])[0]).toBe(map.start[0]);
    expect(p[0]).toBeGreaterThan(scene.camera.position[0] + 2 * DUNGEON_TILE);
    expect(transformDirection(atZero, [0, 0, 1])[0]).toBeLessThan(-0.99);
    const later = sceneUpdateAt(scene, 2, VIEW).instances.get(PHANTOM_ID)!.worldFromObject!;
    expect(p[0] - later[12]!).toBeCloseTo(2 * PHANTOM_SPEED, 0);
  });
});
