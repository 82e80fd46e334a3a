import { describe, expect, it } from 'vitest';
import { dungeonScene, PHANTOM_ID } from '../loaders/builtin/dungeon.ts';
import { twoRooms } from '../loaders/doom/test-wad.ts';
import { doomMapToScene } from '../loaders/doom/to-scene.ts';
import { CompiledPath } from '../scene/paths.ts';
import { World } from '../world/world.ts';
import { CameraController, DOOM_WALK_SPEED, NO_INPUT, type HeldSpan } from './camera-controller.ts';
import { MAX_WORLD_SECONDS, playFrame } from './frame-clock.ts';

const W: HeldSpan['input'] = { ...NO_INPUT, forward: 1 };

/** Room A (x 0..128), a closed door (x 128..144), room B (x 144..272); the walker in A, facing the door. */
function doorRooms() {
  const { scene } = doomMapToScene(twoRooms({}, 'door'), { texture: () => undefined, flat: () => undefined });
  const c = new CameraController({ ...scene.camera, position: [100, 41, -64], forward: [1, 0, 0] }, DOOM_WALK_SPEED, scene.walkMap);
  expect(c.setMode('walk')).toBe(true);
  const world = World.of(scene)!;
  playFrame(c, world, [{ input: NO_INPUT, seconds: 0 }], true);
  // Up against the closed door: one radius (16) short of its face at x = 128.
  playFrame(c, world, [{ input: W, seconds: 0.5 }], true);
  expect(c.pose.position[0]).toBeCloseTo(112, 1);
  const camera = c.camera();
  expect(world.use({ position: camera.position, forward: camera.forward, walking: true })).toBe(true);
  return { c, world, door: scene.dynamics!.movers!.movers[0]!.sector };
}

describe('playFrame: the camera and the world take turns through a frame', () => {
  it('a walker holding W through one 1.2 s frame passes the door opened before it, as at 30 fps', () => {
    const slow = doorRooms();
    playFrame(slow.c, slow.world, [{ input: W, seconds: 1.2 }], true);
    const fast = doorRooms();
    for (let i = 0; i < 36; i++) playFrame(fast.c, fast.world, [{ input: W, seconds: 1 / 30 }], true);
    // The door rises at 70 units a second: the walker (56 tall) gets under it after 0.8 s and is in
    // room B, past the far face (x = 144) by more than a radius, short of its far wall (256), where
    // 36 frames of 1/30 s leave it. (Moving the camera for the whole frame before the world would
    // leave it at the door, 112.)
    expect(fast.c.pose.position[0]).toBeGreaterThan(144 + 16);
    expect(fast.c.pose.position[0]).toBeLessThan(250);
    for (let k = 0; k < 3; k++) expect(slow.c.pose.position[k]).toBeCloseTo(fast.c.pose.position[k]!, 6);
    // The door is where it is at 30 fps: 84 units up.
    expect(slow.c.sectorHeights(slow.door)).toEqual(fast.c.sectorHeights(fast.door));
    expect(slow.c.sectorHeights(slow.door)![1]).toBeCloseTo(84, 3);
    expect(slow.world.seconds).toBeCloseTo(1.7, 12);
  });

  it('the world follows real time at 0.5 fps: the phantom walks at its speed', () => {
    const scene = dungeonScene();
    const c = new CameraController(scene.camera, 1);
    const world = World.of(scene)!;
    let pose;
    for (let i = 0; i < 5; i++) pose = playFrame(c, world, [{ input: NO_INPUT, seconds: 2 }], true).update?.instances.get(PHANTOM_ID)?.worldFromObject;
    expect(world.seconds).toBeCloseTo(10, 9);
    expect(pose).toEqual(new CompiledPath(scene.dynamics!.paths![0]!).poseAt(10));
  });

  it('a frame longer than any of play (a machine that slept) plays the world MAX_WORLD_SECONDS; held keys still move by their time', () => {
    const scene = dungeonScene();
    const c = new CameraController({ ...scene.camera, position: [0, 0, 0], forward: [0, 0, -1] }, 1);
    const world = World.of(scene)!;
    playFrame(c, world, [{ input: NO_INPUT, seconds: MAX_WORLD_SECONDS + 50 }, { input: W, seconds: 10 }], true);
    expect(world.seconds).toBeCloseTo(MAX_WORLD_SECONDS, 9);
    expect(c.pose.position[2]).toBeCloseTo(-10, 6);
  });

  it('with animation off the world holds its clock; the camera moves', () => {
    const scene = dungeonScene();
    const c = new CameraController({ ...scene.camera, position: [0, 0, 0], forward: [0, 0, -1] }, 1);
    const world = World.of(scene)!;
    expect(playFrame(c, world, [{ input: W, seconds: 2 }], false).moved).toBe(true);
    expect(world.seconds).toBe(0);
    expect(c.pose.position[2]).toBeCloseTo(-2, 9);
  });
});
