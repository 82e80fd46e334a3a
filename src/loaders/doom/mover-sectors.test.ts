import { existsSync, readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { morphMesh } from '../../scene/morph.ts';
import type { Mesh, Scene, Texture } from '../../scene/types.ts';
import { validateScene } from '../../scene/validate.ts';
import type { DoomImageSource, DoomMap, Sector } from './map-types.ts';
import { findMovers } from './mover-sectors.ts';
import { twoRooms } from './test-wad.ts';
import { readMap } from './map-lumps.ts';
import { DoomGraphics } from './textures.ts';
import { doomMapToScene } from './to-scene.ts';
import { readWad, WadStack } from './wad.ts';

const solid = (name: string, width: number, height: number): Texture => ({ name, width, height, rgba: new Uint8Array(width * height * 4).fill(128) });
const IMAGES: DoomImageSource = {
  texture: (name) => ({ WALL: solid('WALL', 64, 128), DOOR: solid('DOOR', 64, 72), JAMB: solid('JAMB', 8, 128) })[name],
  flat: (name) => (['FLOOR4_8', 'CEIL3_5'].includes(name) ? solid(name, 64, 64) : undefined),
};

function convert(map: DoomMap): Scene {
  const { scene } = doomMapToScene(map, IMAGES);
  validateScene(scene);
  return scene;
}

const withSector = (map: DoomMap, index: number, change: Partial<Sector>): DoomMap => ({
  ...map,
  sectors: map.sectors.map((s, i) => (i === index ? { ...s, ...change } : s)),
});

function moverMesh(scene: Scene): Mesh {
  const moving = scene.instances.filter((i) => i.moves);
  expect(moving).toHaveLength(1);
  return scene.meshes[moving[0]!.mesh]!;
}

function expectSameMesh(actual: Mesh, expected: Mesh): void {
  expect(actual.indices).toEqual(expected.indices);
  expect(actual.materialIds).toEqual(expected.materialIds);
  expect(actual.positions.length).toBe(expected.positions.length);
  actual.positions.forEach((p, i) => expect(p).toBeCloseTo(expected.positions[i]!, 4));
  actual.uvs!.forEach((p, i) => expect(p).toBeCloseTo(expected.uvs![i]!, 5));
}

describe('moving sectors', () => {
  it('finds the door behind manual lines and the lift tagged by a walk-over line, with Doom targets', () => {
    const door = findMovers(twoRooms({}, 'door', { ceilingHeight: 112 }));
    expect(door.sectors.map((s) => [s.sector, s.kinds, s.doorTop])).toEqual([[1, ['door'], 112 - 4]]);
    expect(door.triggers.map((t) => [t.activation, t.repeatable, t.sectors, t.speed, t.wait])).toEqual([
      ['use', true, [1], 70, 150 / 35],
      ['use', true, [1], 70, 150 / 35],
    ]);
    const lift = findMovers(twoRooms({ floorHeight: 64, ceilingHeight: 128 }, 'lift', { floorHeight: 64 }));
    expect(lift.sectors.map((s) => [s.sector, s.kinds, s.liftBottom, s.range.floor])).toEqual([[1, ['lift'], 0, [-64, 0]]]);
    expect(lift.triggers.map((t) => [t.activation, t.repeatable, t.speed, t.wait])).toEqual([['walk', true, 140, 3]]);
  });

  it('gives the door its own moving mesh; morphed to ceiling rest + h it is the mesh the loader builds at rest + h', () => {
    const map = twoRooms({}, 'door');
    const scene = convert(map);
    const mesh = moverMesh(scene);
    expect(mesh.morphTargets).toHaveLength(2);
    expect(scene.dynamics?.movers?.movers).toHaveLength(1);
    const staticMeshes = scene.meshes.filter((m) => m !== mesh);
    for (const h of [0, 1, 37.5, 124]) {
      const moved = convert(withSector(map, 1, { ceilingHeight: h }));
      expectSameMesh(morphMesh(mesh, [0, h]), moverMesh(moved));
      // Nothing else depends on the door's heights.
      expect(moved.meshes.filter((m) => !m.morphTargets)).toEqual(staticMeshes);
    }
    // Closed, the door's faces and jambs are there with no height: the triangle count never changes.
    const heights = (m: Mesh) => new Set(Array.from({ length: m.positions.length / 3 }, (_, i) => m.positions[3 * i + 1]));
    expect([...heights(mesh)]).toEqual([0, 128]);
    expect([...heights(morphMesh(mesh, [0, 124]))].sort((x, y) => x! - y!)).toEqual([0, 124, 128]);
  });

  it('morphs the lift floor: at weights (f, 0) it is the mesh the loader builds with the floor at rest + f', () => {
    const map = twoRooms({ floorHeight: 64, ceilingHeight: 128 }, 'lift', { floorHeight: 64 });
    const mesh = moverMesh(convert(map));
    // Short of the bottom: a map whose lift rests at the bottom cannot move, and has no sections that only show while it is up.
    for (const f of [0, -10, -63.5]) expectSameMesh(morphMesh(mesh, [f, 0]), moverMesh(convert(withSector(map, 1, { floorHeight: 64 + f }))));
  });

  it('at rest shows exactly the triangles of the same map without specials (a half-open door)', () => {
    const map = twoRooms({ ceilingHeight: 50 }, 'door');
    const plain: DoomMap = { ...map, linedefs: map.linedefs.map((l) => ({ ...l, special: 0 })) };
    const plainScene = convert(plain);
    expect(plainScene.dynamics).toBeUndefined();
    expect(plainScene.meshes.some((m) => m.morphTargets)).toBe(false);
    expect(plainScene.instances.some((i) => i.moves)).toBe(false);
    expect(triangleSet(convert(map))).toEqual(triangleSet(plainScene));
  });
});

const FREEDOOM1 = '/usr/share/games/doom/freedoom1.wad';

describe.skipIf(!existsSync(FREEDOOM1))('moving sectors of Freedoom E1M1', () => {
  it('open, every closed door is the mesh the loader builds with that door open (the real pegging of a real map)', () => {
    const stack = new WadStack([readWad(readFileSync(FREEDOOM1), 'freedoom1.wad')]);
    const graphics = new DoomGraphics(stack);
    const map = readMap(stack, 'E1M1');
    const { scene } = doomMapToScene(map, graphics);
    const movers = scene.dynamics!.movers!.movers;
    const doors = movers.filter((m) => m.kinds.includes('door') && m.restCeiling === m.restFloor);
    expect(doors.length).toBeGreaterThanOrEqual(10);
    for (const door of doors) {
      const open = doomMapToScene(withSector(map, door.sector, { ceilingHeight: door.doorTop }), graphics).scene;
      const mesh = scene.meshes[door.mesh]!;
      expectSameMesh(morphMesh(mesh, [0, door.doorTop - door.restCeiling]), open.meshes[door.mesh]!);
    }
  });
});

/** Every triangle with area, as text: material, corners and uvs (v modulo 1: whole repeats are invisible). */
function triangleSet(scene: Scene): string[] {
  const out: string[] = [];
  for (const mesh of scene.meshes) {
    for (let t = 0; t < mesh.indices.length / 3; t++) {
      const idx = [0, 1, 2].map((k) => mesh.indices[3 * t + k]!);
      const p = idx.map((i) => [0, 1, 2].map((k) => mesh.positions[3 * i + k]!));
      const [a, b, c] = p as [number[], number[], number[]];
      const e1 = [b[0]! - a[0]!, b[1]! - a[1]!, b[2]! - a[2]!], e2 = [c[0]! - a[0]!, c[1]! - a[1]!, c[2]! - a[2]!];
      const area = Math.hypot(e1[1]! * e2[2]! - e1[2]! * e2[1]!, e1[2]! * e2[0]! - e1[0]! * e2[2]!, e1[0]! * e2[1]! - e1[1]! * e2[0]!);
      if (area < 1e-6) continue;
      const frac = (v: number) => (((v % 1) + 1) % 1).toFixed(4).replace('1.0000', '0.0000');
      const uv = idx.map((i) => `${mesh.uvs![2 * i]!.toFixed(4)},${frac(mesh.uvs![2 * i + 1]!)}`);
      out.push(`${scene.materials[mesh.materialIds[t]!]!.name} ${p.map((q) => q.join(',')).join(' ')} ${uv.join(' ')}`);
    }
  }
  return out.sort();
}
