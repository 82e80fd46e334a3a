import { describe, expect, it } from 'vitest';
import type { Camera } from '../scene/types.ts';
import type { WalkMap } from '../scene/walk-map.ts';
import { twoRooms } from '../loaders/doom/test-wad.ts';
import { doomMapToScene } from '../loaders/doom/to-scene.ts';
import { World } from '../world/world.ts';
import { CameraController, DOOM_WALK_SPEED, forwardOf, NO_INPUT, poseFromCamera } from './camera-controller.ts';

const camera: Camera = { position: [0, 0, 0], forward: [0, 0, -1], up: [0, 1, 0], vfovDegrees: 60 };

/** One square room 512 units wide, floor at 0 except a raised half (x > 0) at 16: a step. */
function room(step = 16): WalkMap {
  // Lines around the square (x, z in −256..256), the sector inside on the positive-cross side.
  const corners = [[-256, -256], [-256, 256], [0, 256], [256, 256], [256, -256], [0, -256]] as const;
  const loopA = [[0, 1], [1, 2], [5, 0]], loopB = [[2, 3], [3, 4], [4, 5]];
  const lines: number[] = [], sectors: number[] = [];
  const add = (a: number, b: number, inside: number, other = -1) => {
    lines.push(...corners[a]!, ...corners[b]!);
    sectors.push(inside, other);
  };
  // Orientation chosen so the room's inside is on the positive side of each line.
  for (const [a, b] of loopA) add(b!, a!, 0);
  for (const [a, b] of loopB) add(b!, a!, 1);
  add(2, 5, 1, 0);
  return { lines: new Float32Array(lines), lineSectors: new Int32Array(sectors), lineBlocks: new Uint8Array(lines.length / 4), floors: new Float32Array([0, step]), ceilings: new Float32Array([128, 128]), eyeHeight: 41, stepHeight: 24, bodyHeight: 56, radius: 16 };
}

describe('camera controller', () => {
  it("carries the scene camera's lens, and the lens it is given, through moves", () => {
    const lens = { apertureRadius: 0.1, focusDistance: 3 };
    const c = new CameraController({ ...camera, lens }, 1);
    c.update(1, { ...NO_INPUT, forward: 1 });
    expect(c.camera().lens).toEqual(lens);
    c.lens = undefined;
    expect('lens' in c.camera()).toBe(false);
    c.lens = { apertureRadius: 0, focusDistance: 5 };
    expect(c.camera().lens).toEqual({ apertureRadius: 0, focusDistance: 5 });
  });

  it('round-trips yaw and pitch through the forward vector', () => {
    for (const [yaw, pitch] of [[0, 0], [1, 0.3], [-2.5, -0.7], [3, 1.2]] as const) {
      const pose = poseFromCamera({ ...camera, forward: forwardOf(yaw, pitch) });
      expect(pose.yaw).toBeCloseTo(yaw, 9);
      expect(pose.pitch).toBeCloseTo(pitch, 9);
    }
  });

  it('flies forward along the view, strafes right, rises, and runs twice as fast', () => {
    const c = new CameraController(camera, 10);
    expect(c.update(1, { ...NO_INPUT, forward: 1 })).toBe(true);
    expect(c.pose.position[2]).toBeCloseTo(-10);
    c.update(1, { ...NO_INPUT, right: 1 });
    expect(c.pose.position[0]).toBeCloseTo(10);
    c.update(0.5, { ...NO_INPUT, up: 1, run: true });
    expect(c.pose.position[1]).toBeCloseTo(10);
    expect(c.update(1, NO_INPUT)).toBe(false);
  });

  it('turns left with negative turn input and looks up with the mouse moving up', () => {
    const c = new CameraController(camera, 10);
    c.update(0.5, { ...NO_INPUT, turn: -1 });
    expect(c.camera().forward[0]).toBeLessThan(-0.5);
    c.look(0, -100);
    expect(c.camera().forward[1]).toBeGreaterThan(0.2);
    c.look(0, -100000);
    expect(c.pitch).toBeLessThan(Math.PI / 2);
  });

  it('walks at eye height, climbs a step smoothly and ignores up/down', () => {
    const c = new CameraController({ ...camera, position: [-100, 41, 0], forward: [1, 0, 0] }, 100, room());
    expect(c.setMode('walk')).toBe(true);
    c.update(0.1, { ...NO_INPUT, up: 1 });
    expect(c.pose.position[1]).toBeCloseTo(41, 5);
    const heights: number[] = [];
    for (let i = 0; i < 30; i++) {
      c.update(0.1, { ...NO_INPUT, forward: 1 });
      heights.push(c.pose.position[1]);
    }
    expect(c.pose.position[0]).toBeGreaterThan(100);
    expect(heights.at(-1)).toBeCloseTo(57, 5);
    // Smooth: some frames sit between the two eye heights, and height never goes down.
    expect(heights.some((h) => h > 41.5 && h < 56.5)).toBe(true);
    for (let i = 1; i < heights.length; i++) expect(heights[i]!).toBeGreaterThanOrEqual(heights[i - 1]!);
  });

  it('refuses walk mode without a walk map or outside it', () => {
    expect(new CameraController(camera, 1).setMode('walk')).toBe(false);
    expect(new CameraController({ ...camera, position: [1000, 0, 0] }, 1, room()).setMode('walk')).toBe(false);
  });
});

describe('walking through a Doom door', () => {
  /** Room A (x 0..128), the door (x 128..144, closed), room B (x 144..272); the start faces the door. */
  function setup() {
    const { scene } = doomMapToScene(twoRooms({}, 'door'), { texture: () => undefined, flat: () => undefined });
    const c = new CameraController({ ...scene.camera, position: [100, 41, -64], forward: [1, 0, 0] }, DOOM_WALK_SPEED, scene.walkMap);
    expect(c.setMode('walk')).toBe(true);
    const world = World.of(scene)!;
    const view = () => ({ position: c.camera().position, forward: c.camera().forward });
    /** Walks forward for `seconds` in frames of 1/35 s, playing the world as the viewer does. */
    const walk = (seconds: number, forward = 1) => {
      for (let i = 0; i < Math.round(seconds * 35); i++) {
        c.update(1 / 35, { ...NO_INPUT, forward });
        for (const [x0, z0, x1, z1] of c.takeWalked()) world.walked(x0, z0, x1, z1);
        const update = world.advance(1 / 35, view());
        if (update) c.setSectorHeights(update.walkHeights);
      }
    };
    return { c, world, walk, view, scene };
  }

  it('cannot pass the closed door; after the use key, walks through the open one', () => {
    const { c, world, walk, view, scene } = setup();
    walk(1);
    // Stopped one radius (16) before the door line at x = 128.
    expect(c.pose.position[0]).toBeCloseTo(128 - 16, 0);
    expect(c.pose.position[0]).toBeLessThan(128);
    expect(world.use(view())).toBe(true);
    walk(2); // 62 tics to open; the walker presses on meanwhile
    const door = scene.dynamics!.movers!.movers[0]!.sector;
    expect(c.sectorHeights(door)).toEqual([0, 124]);
    expect(c.pose.position[0]).toBeGreaterThan(144 + 16);
    // The scene's own walk map is untouched: the controller keeps heights of its own.
    expect(scene.walkMap!.ceilings[door]).toBe(0);
  });

  it('reports the walker\'s moves for walk-over lines', () => {
    const { c } = setup();
    c.update(0.1, { ...NO_INPUT, forward: -1 });
    const walks = c.takeWalked();
    expect(walks).toHaveLength(1);
    expect(walks[0]![0]).toBe(100);
    expect(walks[0]![2]).toBeCloseTo(100 - DOOM_WALK_SPEED * 0.1, 6);
    expect(c.takeWalked()).toEqual([]);
  });
});

describe('camera controller: held time', () => {
  it('moves by the held time however the frames fall: one 3 s frame equals ninety 1/30 s frames', () => {
    const slow = new CameraController(camera, 10);
    const fast = new CameraController(camera, 10);
    const walkAndTurn = { ...NO_INPUT, forward: 1, turn: 1 };
    slow.advance([{ input: walkAndTurn, seconds: 3 }]);
    for (let i = 0; i < 90; i++) fast.advance([{ input: walkAndTurn, seconds: 1 / 30 }]);
    for (let i = 0; i < 3; i++) expect(slow.pose.position[i]).toBeCloseTo(fast.pose.position[i]!, 9);
    expect(slow.pose.yaw).toBeCloseTo(fast.pose.yaw, 12);
    // Three seconds of turning at 120°/s is a full turn, and walking while turning follows a circle
    // back to where it began (a 3 s frame that moved by the held keys at its end would be 30 units off).
    expect(slow.pose.yaw).toBeCloseTo(2 * Math.PI, 9);
    expect(Math.hypot(...slow.pose.position)).toBeLessThan(0.5);
  });

  it('a 30 s frame of walking into a wall stops at the wall', () => {
    const c = new CameraController({ ...camera, position: [-128, 41, 0] }, 200, room());
    expect(c.setMode('walk')).toBe(true);
    expect(c.advance([{ input: { ...NO_INPUT, forward: 1 }, seconds: 30 }])).toBe(true);
    const [x, , z] = c.pose.position;
    expect(z).toBeGreaterThanOrEqual(-256 + 16 - 1e-3);
    expect(z).toBeLessThan(-256 + 17);
    expect(x).toBeCloseTo(-128, 6);
  });
});
