import { existsSync, readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { translation } from '../math/mat4.ts';
import { dungeonScene, PHANTOM_ID } from '../loaders/builtin/dungeon.ts';
import { loadDoomMap } from '../loaders/doom/load.ts';
import { animatedRoomWad, twoRooms } from '../loaders/doom/test-wad.ts';
import { doomMapToScene } from '../loaders/doom/to-scene.ts';
import { readWad, WadStack } from '../loaders/doom/wad.ts';
import { testGame, testMap } from '../loaders/wolf3d/test-game.ts';
import { PUSH_WALL_SECONDS_PER_TILE, WOLF_EYE_HEIGHT, WOLF_TILE, wolfMapToScene } from '../loaders/wolf3d/to-scene.ts';
import { CompiledPath } from '../scene/paths.ts';
import { diffuse, type Scene } from '../scene/types.ts';
import type { Animator, AnimatorFactory, Viewpoint } from './animator.ts';
import { billboardAnimator } from './billboards.ts';
import { materialAnimator } from './material-animation.ts';
import { moverAnimator, MoverAnimator } from './movers.ts';
import { pathAnimator } from './paths.ts';
import { pushWallAnimator, PushWallAnimator } from './push-walls.ts';
import { slidingDoorAnimator, SlidingDoorAnimator } from './sliding-doors.ts';
import { mergeUpdates, sceneUpdateAt, TICKS_PER_SECOND, World } from './world.ts';

const scene: Scene = {
  name: 'moving',
  meshes: [],
  instances: [],
  materials: [diffuse('grey', [0.5, 0.5, 0.5])],
  camera: { position: [0, 0, 0], forward: [0, 0, -1], up: [0, 1, 0], vfovDegrees: 60 },
  dynamics: {},
};
const view = { position: [0, 0, 0] as const, forward: [0, 0, -1] as const };

/** Moves instance 1 along x at 1 unit/s, writing only when the position changed; counts uses and walks. */
function slider(log: string[]): AnimatorFactory {
  return () => {
    let x = NaN;
    const a: Animator = {
      step(t, _dt, _view, out) {
        if (t === x) return;
        x = t;
        out.pose(1, { worldFromObject: translation([t, 0, 0]) });
      },
      use: () => {
        log.push('use');
        return true;
      },
      walked: (x0, _z0, x1) => void log.push(`walk ${x0}->${x1}`),
    };
    return a;
  };
}

describe('World', () => {
  it('exists only for scenes with dynamics and at least one animator', () => {
    expect(World.of({ ...scene, dynamics: undefined }, [slider([])])).toBeUndefined();
    expect(World.of(scene, [() => undefined])).toBeUndefined();
    expect(World.of(scene, [slider([])])).toBeDefined();
  });

  it('advances the clock and reports only what changed', () => {
    const world = World.of(scene, [slider([])])!;
    const first = world.advance(0, view)!;
    expect(first.instances.get(1)?.worldFromObject?.[12]).toBe(0);
    expect(world.advance(0, view)).toBeUndefined();
    expect(world.advance(0.5, view)!.instances.get(1)?.worldFromObject?.[12]).toBe(0.5);
    expect(world.seconds).toBe(0.5);
    expect(() => world.advance(-1, view)).toThrow(RangeError);
  });

  it('advanceTo brings the world to the target time in one update', () => {
    const world = World.of(scene, [slider([])])!;
    const u = world.advanceTo(2, view);
    expect(u.instances.get(1)?.worldFromObject?.[12]).toBeCloseTo(2, 12);
    expect(world.seconds).toBeCloseTo(2, 12);
    expect(() => world.advanceTo(1, view)).toThrow(RangeError);
  });

  it('steps an integrating animator at every tick while it moves, and not at all at rest', () => {
    const ticks: number[] = [];
    let until = 0.5;
    const integrator: AnimatorFactory = () => ({
      moving: () => (ticks.at(-1) ?? 0) < until,
      step: (t, dt, _view, _out, first) => void (first || (ticks.push(t), expect(dt).toBe(1 / TICKS_PER_SECOND))),
    });
    const world = World.of(scene, [integrator])!;
    world.advance(1e6, view);
    // Half a second of ticks, on the tick grid; then nothing for the rest of a million seconds.
    expect(ticks).toHaveLength(TICKS_PER_SECOND / 2);
    expect(ticks.at(-1)).toBe(0.5);
    until = Infinity;
    world.advance(1 / 30, view);
    expect(ticks).toHaveLength(TICKS_PER_SECOND / 2 + TICKS_PER_SECOND / 30);
    expect(ticks.at(-1)).toBe(1e6 + 1 / 30);
  });

  it('passes the use key and walks to the animators', () => {
    const log: string[] = [];
    const world = World.of(scene, [slider(log)])!;
    expect(world.use(view)).toBe(true);
    world.walked(1, 0, 2, 0);
    expect(log).toEqual(['use', 'walk 1->2']);
  });

  it('mergeUpdates: later updates win, poses and edits merge field by field', () => {
    const a = { instances: new Map([[1, { material: 3 }]]), morphWeights: new Map(), materials: new Map([[0, { roughness: 0.5 }]]), walkHeights: new Map() };
    const b = { instances: new Map([[1, { worldFromObject: translation([1, 2, 3]) }]]), morphWeights: new Map([[0, new Float32Array([1])]]), materials: new Map([[0, { metallic: 1 }]]), walkHeights: new Map([[4, [0, 8] as const]]) };
    const m = mergeUpdates([a, undefined, b]);
    expect(m.instances.get(1)).toEqual({ material: 3, worldFromObject: translation([1, 2, 3]) });
    expect(m.materials.get(0)).toEqual({ roughness: 0.5, metallic: 1 });
    expect(m.walkHeights.get(4)).toEqual([0, 8]);
  });
});

/** Every kind of motion, as World.of plays them (each animator kept, to read its own state). */
const FACTORIES: readonly AnimatorFactory[] = [materialAnimator, moverAnimator, pathAnimator, billboardAnimator, slidingDoorAnimator, pushWallAnimator];

/** What an animator keeps beyond what its updates say: door and lift heights and motions, door actions, push wall offsets. */
function stateOf(a: Animator): Record<string, unknown> {
  if (a instanceof MoverAnimator) return { movers: { floors: a.floors, ceilings: a.ceilings, active: a.set.movers.map((_, i) => a.active(i)) } };
  if (a instanceof SlidingDoorAnimator) return { doors: a.set.doors.map((_, i) => a.state(i)) };
  if (a instanceof PushWallAnimator) return { pushWalls: a.set.walls.map((_, i) => a.offset(i)) };
  return {};
}

/**
 * Plays `scene` for `seconds` in `frames` equal frames seen from `view`, after `act` (the use key, a
 * walk-over line) at time 0: everything the world said since its first step (instance poses, morph
 * weights, material edits, walk heights: the whole state, since the first step writes it all), and
 * the animators' own states.
 */
function play(scene: Scene, seconds: number, frames: number, view: Viewpoint, act: (w: World) => void = () => {}) {
  const animators: Animator[] = [];
  const world = World.of(scene, FACTORIES.map((make) => (s: Scene) => {
    const a = make(s);
    if (a) animators.push(a);
    return a;
  }))!;
  const updates = [world.advance(0, view)];
  act(world);
  for (let i = 0; i < frames; i++) updates.push(world.advance(seconds / frames, view));
  return { world: mergeUpdates(updates), animators: Object.assign({}, ...animators.map(stateOf)) as { movers?: unknown; doors?: unknown; pushWalls?: { cells: number }[] } };
}

/** The world after one frame of `seconds` equals the world after frames of 1/30 s, exactly; and equals `render --time`'s. */
function expectFrameFree(scene: Scene, seconds: number, view: Viewpoint, act?: (w: World) => void) {
  const slow = play(scene, seconds, 1, view, act);
  const fast = play(scene, seconds, Math.round(seconds * 30), view, act);
  expect(slow).toEqual(fast);
  return slow;
}

const doomNone = { texture: () => undefined, flat: () => undefined };
const FREEDOOM1 = '/usr/share/games/doom/freedoom1.wad';

describe('the world follows elapsed time, however the frames fall', () => {
  it('a Doom door (use key) and lift (walk-over line): one frame of 3 s (7 s, 8 s) is 90 (210, 240) frames of 1/30 s', () => {
    const door = doomMapToScene(twoRooms({}, 'door'), doomNone).scene;
    // In room A, 28 units from the door's face, facing it (within the use key's 64 units).
    const atDoor: Viewpoint = { position: [100, 41, -64], forward: [1, 0, 0], walking: true };
    const lift = doomMapToScene(twoRooms({ floorHeight: 64, ceilingHeight: 128 }, 'lift', { floorHeight: 64 }), doomNone).scene;
    // Up at 70 units a second to its top (124, 4 under the rooms' ceilings) by 1.77 s, a 150-tic wait
    // (4.29 s), down again from 6.06 s to 7.83 s.
    for (const [seconds, ceiling] of [[3, 124], [7, 124 - 70 * (7 - 124 / 70 - 150 / 35)], [8, 0]] as const) {
      const d = expectFrameFree(door, seconds, atDoor, (w) => expect(w.use(atDoor)).toBe(true));
      expect(d.world.walkHeights.get(door.dynamics!.movers!.movers[0]!.sector)![1]).toBeCloseTo(ceiling, 6);
    }
    // Down at 140 units a second (0.46 s), a 3 s wait at the bottom, back up by 3.9 s.
    for (const [seconds, floor] of [[3, 0], [8, 64]] as const) {
      const l = expectFrameFree(lift, seconds, { position: [60, 41, -64], forward: [1, 0, 0] }, (w) => w.walked(120, -64, 136, -64));
      expect(l.world.walkHeights.get(lift.dynamics!.movers!.movers[0]!.sector)![0]).toBe(floor);
    }
  });

  it.skipIf(!existsSync(FREEDOOM1))("Freedoom's E1M1: its first door, sprites, animated flats and flickering lights", () => {
    const { scene } = loadDoomMap(new WadStack([readWad(readFileSync(FREEDOOM1), 'freedoom1.wad')]), 'E1M1');
    // 30 units south of the first door's face (z = −512), facing it, on the room's floor (−128).
    const atDoor: Viewpoint = { position: [832, -87, -482], forward: [0, 0, -1], walking: true };
    const { world } = expectFrameFree(scene, 3, atDoor, (w) => expect(w.use(atDoor)).toBe(true));
    expect(world.morphWeights.size).toBeGreaterThan(0);
    expect(world.materials.size).toBeGreaterThan(0);
    expect(world.instances.size).toBeGreaterThan(100);
  });

  it('the dungeon\'s phantom: where one 3 s frame leaves it is where 90 frames do, and where --time 3 puts it', () => {
    const scene = dungeonScene();
    const view: Viewpoint = { position: [0, 1.6, 0], forward: [0, 0, -1] };
    const { world } = expectFrameFree(scene, 3, view);
    const pose = world.instances.get(PHANTOM_ID)!.worldFromObject!;
    expect(pose).toEqual(new CompiledPath(scene.dynamics!.paths![0]!).poseAt(3));
    expect(sceneUpdateAt(scene, 3, view).instances.get(PHANTOM_ID)!.worldFromObject).toEqual(pose);
  });

  it('Wolfenstein 3D: a sliding door (use key, and by proximity) and a push wall', () => {
    const T = WOLF_TILE;
    const wolf = (rows: string[]) => {
      const map = testMap(rows);
      return wolfMapToScene(testGame([map]), map);
    };
    const view = (x: number, z: number, walking?: boolean): Viewpoint => ({ position: [x * T, WOLF_EYE_HEIGHT, z * T], forward: [1, 0, 0.2], ...(walking ? { walking } : {}) });
    const doors = wolf(['#######', '#>.|..#', '#######']);
    const beside = view(2.6, 1.5, true);
    for (const seconds of [3, 8]) {
      const used = expectFrameFree(doors, seconds, beside, (w) => expect(w.use(beside)).toBe(true));
      // Open 0.91 s after the use key and waiting at 3 s; closed again by 8 s (4.3 s wait, 0.91 s back).
      expect(used.animators.doors).toEqual([{ action: seconds === 3 ? 'open' : 'closed', position: seconds === 3 ? 1 : 0 }]);
      // By proximity (a flying camera in front of it): open, and held open.
      expect(expectFrameFree(doors, seconds, view(2.2, 1.5)).animators.doors).toEqual([{ action: 'open', position: 1 }]);
    }
    const push = wolf(['########', '########', '#>.P..##', '########']);
    const front = view(2.5, 2.5, true);
    const pushed = expectFrameFree(push, 3, front, (w) => expect(w.use(front)).toBe(true));
    // 1.83 s a tile: 3 s in, it is 1.64 tiles along.
    expect(pushed.animators.pushWalls![0]!.cells).toBeCloseTo(3 / PUSH_WALL_SECONDS_PER_TILE, 9);
  });

  it('material animations: texture cycles, scrolls and light patterns (a Doom map\'s)', () => {
    const { scene } = loadDoomMap(new WadStack([readWad(animatedRoomWad(), 'animated.wad')]), undefined);
    const view: Viewpoint = { position: [0, 41, 0], forward: [0, 0, -1] };
    const { world } = expectFrameFree(scene, 3, view);
    expect(world.materials.size).toBeGreaterThanOrEqual(3);
    for (const [k, edit] of sceneUpdateAt(scene, 3, view).materials) expect(world.materials.get(k)).toMatchObject(edit);
  });
});
