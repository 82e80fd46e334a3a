/**
 * The scene of the real E1L1 (Wolfenstein 3D v1.4 shareware, read in place from
 * ../shared/assets/wolf3d-shareware; skipped where absent): what the builder makes of it, counted
 * against the map's own codes.
 */
import { existsSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { validateScene } from '../../scene/validate.ts';
import { moveWalker, sectorAt } from '../../scene/walk-map.ts';
import { World } from '../../world/world.ts';
import { readWolfGame } from './game.ts';
import { WOLF_EYE_HEIGHT, WOLF_TILE, wolfMapToScene } from './to-scene.ts';

const CANDIDATES = ['../shared/assets/wolf3d-shareware', '/work/shared/assets/wolf3d-shareware'];
const DIR = CANDIDATES.find((d) => ['MAPHEAD.WL1', 'GAMEMAPS.WL1', 'VSWAP.WL1'].every((f) => existsSync(join(d, f))));
if (!DIR) console.warn(`Wolfenstein 3D shareware files not found in ${CANDIDATES.join(' or ')}: skipping the E1L1 scene tests`);
const file = (name: string) => ({ name, bytes: new Uint8Array(readFileSync(join(DIR!, name))) });
const T = WOLF_TILE;

describe.skipIf(!DIR)('E1L1 as a scene', () => {
  const game = DIR ? readWolfGame({ maphead: file('MAPHEAD.WL1'), gamemaps: file('GAMEMAPS.WL1'), vswap: file('VSWAP.WL1') }) : undefined!;

  it('has a door per door tile, a block per push-wall mark, a sprite per object and actor of the skill, an emitter per lamp', () => {
    const map = game.map('E1L1');
    const warnings: string[] = [];
    const scene = wolfMapToScene(game, map, { onWarning: (w) => warnings.push(w) });
    validateScene(scene);
    const [walls, objects] = map.planes;
    const count = (plane: Uint16Array, test: (c: number) => boolean) => [...plane].filter(test).length;
    const d = scene.dynamics!;
    expect(d.slidingDoors!.doors).toHaveLength(count(walls, (c) => c >= 90 && c <= 101));
    expect(d.slidingDoors!.doors).toHaveLength(22);
    expect(d.pushWalls!.walls).toHaveLength(count(objects, (c) => c === 98));
    expect(d.pushWalls!.walls).toHaveLength(5);
    // Objects, and the guards, SS and dogs of skill 3 (the first two blocks of 36 actor codes; the dead guard only in the first).
    const statics = count(objects, (c) => c >= 23 && c <= 71);
    const drawnActor = (c: number) => {
      const o = (c - 108) % 36, block = Math.floor((c - 108) / 36);
      return c >= 108 && block <= 1 && (o < 8 || (o === 16 && block === 0) || (o >= 18 && o < 34));
    };
    expect(statics).toBe(121);
    expect(d.billboards).toHaveLength(statics + count(objects, drawnActor));
    expect(d.billboards!.filter((b) => b.frames[0]!.images.length === 8).length).toBe(count(objects, (c) => drawnActor(c) && c !== 124));
    const lamps = count(objects, (c) => c === 26 || c === 27 || c === 37);
    const emitterTriangles = scene.meshes.filter((m, i) => scene.instances.some((inst) => inst.mesh === i) && scene.materials[m.materialIds[0]!]!.kind === 'emissive').reduce((n, m) => n + m.indices.length / 3, 0);
    expect(emitterTriangles).toBe(2 * lamps);
    expect(lamps).toBeGreaterThan(10);
    // A wall face wherever a wall tile (push walls aside: they are blocks of their own) borders a
    // tile one sees into: floor, door or push wall.
    const at = (x: number, y: number) => (x >= 0 && y >= 0 && x < 64 && y < 64 ? y * 64 + x : -1);
    const push = (i: number) => objects[i] === 98;
    const solid = (i: number) => i < 0 || (walls[i]! >= 1 && walls[i]! <= 63 && !push(i));
    let faces = 0;
    for (let y = 0; y < 64; y++) for (let x = 0; x < 64; x++) if (solid(at(x, y))) for (const [dx, dy] of [[1, 0], [0, -1], [-1, 0], [0, 1]]) if (!solid(at(x + dx!, y + dy!))) faces++;
    const wallTriangles = scene.instances.filter((i) => !i.moves).map((i) => scene.meshes[i.mesh]!).filter((m) => scene.materials[m.materialIds[0]!]!.name.startsWith('wall page')).reduce((n, m) => n + m.indices.length / 3, 0);
    expect(wallTriangles).toBe(2 * faces);
    expect(faces).toBe(758);
    // E1L1 has only guards, SS and dogs: nothing is left out.
    expect(warnings).toEqual([]);
  });

  it('starts in the cell at (29, 57) at eye height, facing east at its door, which opens as the camera nears it', () => {
    const scene = wolfMapToScene(game, game.map('E1L1'));
    expect(scene.camera.position).toEqual([29.5 * T, WOLF_EYE_HEIGHT, 57.5 * T]);
    expect(scene.camera.forward).toEqual([1, 0, 0]);
    const map = scene.walkMap!;
    const start = { x: 29.5 * T, z: 57.5 * T, sector: sectorAt(map, 29.5 * T, 57.5 * T) };
    // The cell door at (32, 57) stops the walker; the World opens it for a viewer beside it.
    expect(moveWalker(map, start, 4 * T, 0).x).toBeLessThan(32 * T);
    const door = scene.dynamics!.slidingDoors!.doors.find((x) => x.cell[0] === 32 && x.cell[1] === 57)!;
    const world = World.of(scene)!;
    const near = { position: [31.5 * T, WOLF_EYE_HEIGHT, 57.5 * T] as const, forward: [1, 0, 0] as const };
    const u = world.advanceTo(2, { position: [...near.position], forward: [...near.forward] });
    expect(u.walkHeights.get(door.sector)).toEqual([0, T]);
  });
});
