import { describe, expect, it } from 'vitest';
import { transformPoint, type Mat4 } from '../../math/mat4.ts';
import { cross, normalize, sub, type Vec3 } from '../../math/vec3.ts';
import { validateScene } from '../../scene/validate.ts';
import { eyeLevel, moveWalker, sectorAt, type WalkMap, type WalkPosition } from '../../scene/walk-map.ts';
import type { Viewpoint } from '../../world/animator.ts';
import { World } from '../../world/world.ts';
import type { Scene } from '../../scene/types.ts';
import { PUSH_DIRECTIONS } from '../../scene/dynamics-types.ts';
import { DIRECTIONS } from './level.ts';
import { testGame, testMap, TEST_PALETTE } from './test-game.ts';
import {
  DOOR_THICKNESS, DOOR_TRAVEL_SECONDS, DOOR_WAIT_SECONDS, LAMPS, lampRadiance, paletteLinear, PUSH_WALL_SECONDS_PER_TILE,
  WOLF_EYE_HEIGHT, WOLF_TILE, wolfMapToScene,
} from './to-scene.ts';
import { ceilingColourIndex, FLOOR_COLOUR_INDEX } from './palette.ts';

const T = WOLF_TILE;

function build(rows: readonly string[], warnings: string[] = []): Scene {
  const map = testMap(rows);
  const scene = wolfMapToScene(testGame([map]), map, { onWarning: (w) => warnings.push(w) });
  validateScene(scene);
  return scene;
}

interface Tri {
  readonly a: Vec3;
  readonly b: Vec3;
  readonly c: Vec3;
  readonly normal: Vec3;
  readonly centroid: Vec3;
  readonly material: string;
  /** uv per corner. */
  readonly uv: readonly [number, number][];
  readonly instance: string;
}

/** Every triangle of the scene in world space, by instance (as posed when loaded). */
function triangles(scene: Scene, filter: (name: string) => boolean = () => true): Tri[] {
  const out: Tri[] = [];
  for (const inst of scene.instances) {
    if (!filter(inst.name ?? '')) continue;
    const mesh = scene.meshes[inst.mesh]!;
    for (let t = 0; t < mesh.indices.length / 3; t++) {
      const idx = [0, 1, 2].map((k) => mesh.indices[3 * t + k]!);
      const [a, b, c] = idx.map((i) => transformPoint(inst.worldFromObject as Mat4, [mesh.positions[3 * i]!, mesh.positions[3 * i + 1]!, mesh.positions[3 * i + 2]!])) as [Vec3, Vec3, Vec3];
      const m = inst.material ?? mesh.materialIds[t]!;
      out.push({
        a, b, c,
        normal: normalize(cross(sub(b, a), sub(c, a))),
        centroid: [(a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3, (a[2] + b[2] + c[2]) / 3],
        material: scene.materials[m]!.name,
        uv: idx.map((i) => [mesh.uvs![2 * i]!, mesh.uvs![2 * i + 1]!] as [number, number]),
        instance: inst.name ?? '',
      });
    }
  }
  return out;
}

const isWall = (t: Tri) => t.material.startsWith('wall page') && Math.abs(t.normal[1]) < 1e-6;
const tileOf = (p: Vec3): [number, number] => [Math.floor(p[0] / T), Math.floor(p[2] / T)];
const pageOf = (material: string) => Number(/wall page (\d+)/.exec(material)?.[1]);

const ROOM = ['#####', '#...#', '#.^.#', '#...#', '#####'];

describe('wolfMapToScene: walls, floor, ceiling', () => {
  it('gives a closed room a face per wall side it sees, each facing into an open tile', () => {
    const scene = build(ROOM);
    const walls = triangles(scene).filter(isWall);
    // 3 × 3 open tiles: 12 faces, two triangles each.
    expect(walls).toHaveLength(24);
    for (const t of walls) {
      const [x, y] = tileOf([t.centroid[0] + t.normal[0] * 8, 0, t.centroid[2] + t.normal[2] * 8]);
      expect(ROOM[y]![x], `face at ${t.centroid} faces tile (${x}, ${y})`).not.toBe('#');
      // And its back is in the wall.
      const [bx, by] = tileOf([t.centroid[0] - t.normal[0] * 8, 0, t.centroid[2] - t.normal[2] * 8]);
      expect(ROOM[by]![bx]).toBe('#');
    }
  });

  it('shows the light page on north and south faces and the dark page on east and west ones', () => {
    const walls = triangles(build(['#####', '#...#', '#.^.#', '#...#', '##5##'])).filter(isWall);
    for (const t of walls) {
      const northSouth = Math.abs(t.normal[2]) > 0.99;
      const [x, y] = tileOf([t.centroid[0] - t.normal[0] * 8, 0, t.centroid[2] - t.normal[2] * 8]);
      const code = x === 2 && y === 4 ? 5 : 1;
      expect(pageOf(t.material)).toBe((code - 1) * 2 + (northSouth ? 0 : 1));
    }
    expect(walls.filter((t) => pageOf(t.material) === 8)).toHaveLength(2);
  });

  it('maps a page across one face, left to right as seen from the open side, top row at the ceiling', () => {
    const walls = triangles(build(ROOM)).filter(isWall);
    for (const t of walls) {
      // Seen from the open side, "right" is up × (−normal)... the viewer looks along −normal: right = forward × up.
      const forward: Vec3 = [-t.normal[0], 0, -t.normal[2]];
      const right = cross(forward, [0, 1, 0]);
      for (const [p, q] of [[t.a, t.b], [t.b, t.c], [t.a, t.c]] as const) {
        const uvP = t.uv[[t.a, t.b, t.c].indexOf(p)]!, uvQ = t.uv[[t.a, t.b, t.c].indexOf(q)]!;
        const along = (q[0] - p[0]) * right[0] + (q[2] - p[2]) * right[2];
        expect(uvQ[0] - uvP[0]).toBeCloseTo(along / T, 6);
        expect(uvQ[1] - uvP[1]).toBeCloseTo(-(q[1] - p[1]) / T, 6);
      }
    }
  });

  it('lays a floor quad facing up and a ceiling quad facing down on every open tile, in the game colours', () => {
    const scene = build(ROOM);
    const all = triangles(scene);
    const floor = all.filter((t) => t.material === 'floor');
    const ceiling = all.filter((t) => t.material === 'ceiling');
    expect(floor).toHaveLength(18);
    expect(ceiling).toHaveLength(18);
    for (const t of floor) expect(t.normal[1]).toBeCloseTo(1, 9);
    for (const t of ceiling) {
      expect(t.normal[1]).toBeCloseTo(-1, 9);
      expect(t.a[1]).toBe(T);
    }
    const albedo = (name: string) => {
      const m = scene.materials.find((x) => x.name === name)!;
      return m.kind === 'diffuse' ? m.albedo : undefined;
    };
    expect(albedo('floor')).toEqual(paletteLinear(TEST_PALETTE, FLOOR_COLOUR_INDEX));
    expect(albedo('ceiling')).toEqual(paletteLinear(TEST_PALETTE, ceilingColourIndex(0)));
    // sRGB decoding: the grey 0x19 = 25 is 25/255 in display values, about 0.0097 linear.
    expect(paletteLinear(TEST_PALETTE, 25)[0]).toBeCloseTo(0.00972, 4);
  });

  it('uses nearest-filtered textures and the level grid hint', () => {
    const scene = build(ROOM);
    expect(scene.textures!.every((t) => t.filter === 'nearest')).toBe(true);
    expect(scene.tileGrid).toEqual({ origin: [0, 0, 0], cellSize: [T, T, T], dims: [5, 1, 5] });
    expect(scene.metersPerUnit! * T).toBe(2);
  });
});

describe('wolfMapToScene: the player start', () => {
  it.each([
    ['^', [0, 0, -1]],
    ['>', [1, 0, 0]],
    ['v', [0, 0, 1]],
    ['<', [-1, 0, 0]],
  ] as const)('puts the camera at eye height in the start tile (%s)', (ch, forward) => {
    const scene = build(['#####', '#...#', `#.${ch}.#`, '#...#', '#####']);
    expect(scene.camera.position).toEqual([2.5 * T, WOLF_EYE_HEIGHT, 2.5 * T]);
    expect(scene.camera.forward).toEqual(forward);
    expect(scene.torch).toBeDefined();
    expect(eyeLevel(scene.walkMap!, sectorAt(scene.walkMap!, 2.5 * T, 2.5 * T))).toBe(WOLF_EYE_HEIGHT);
  });

  it('says so when the map has no start', () => {
    const warnings: string[] = [];
    const scene = build(['###', '#.#', '###'], warnings);
    expect(scene.camera.position).toEqual([1.5 * T, WOLF_EYE_HEIGHT, 1.5 * T]);
    expect(warnings.join('\n')).toMatch(/no player start/);
  });
});

// A corridor west–east through a vertical door at (3, 1): frame walls above and below it.
const DOOR_MAP = ['#######', '#>.|..#', '#######'];
const doorFrameWalls = ['#######', '#>.|..#', '###4###'];

describe('wolfMapToScene: doors', () => {
  it('places a thin panel across the middle of the door tile, with the door page, as a moving instance', () => {
    const scene = build(DOOR_MAP);
    const door = scene.dynamics!.slidingDoors!.doors[0]!;
    const inst = scene.instances.find((i) => i.id === door.instance)!;
    expect(inst.moves).toBe(true);
    const panel = triangles(scene, (n) => n === inst.name);
    const xs = panel.flatMap((t) => [t.a[0], t.b[0], t.c[0]]);
    const zs = panel.flatMap((t) => [t.a[2], t.b[2], t.c[2]]);
    expect(Math.min(...xs)).toBeCloseTo(3.5 * T - DOOR_THICKNESS / 2, 6);
    expect(Math.max(...xs)).toBeCloseTo(3.5 * T + DOOR_THICKNESS / 2, 6);
    expect([Math.min(...zs), Math.max(...zs)]).toEqual([T, 2 * T]);
    // A vertical door shows DOORWALL + 1 (the shareware's DOORWALL is 98).
    expect(new Set(panel.map((t) => pageOf(t.material)))).toEqual(new Set([99]));
    // Its broad faces face east and west; its trailing (north) end faces north, a hair inside the
    // panel so that, fully open, it hides behind the frame; the leading end, always in the wall, has no face.
    expect(panel.filter((t) => Math.abs(t.normal[0]) > 0.99)).toHaveLength(4);
    const ends = panel.filter((t) => Math.abs(t.normal[2]) > 0.99);
    expect(ends).toHaveLength(2);
    for (const t of ends) {
      expect(t.normal[2]).toBeCloseTo(-1, 9);
      expect(t.a[2]).toBeGreaterThan(T);
      expect(t.a[2]).toBeLessThan(T + 1);
    }
  });

  it('gives the walls beside a door the door-frame page on their faces toward it', () => {
    const walls = triangles(build(doorFrameWalls)).filter(isWall);
    const frame = walls.filter((t) => tileOf([t.centroid[0], 0, t.centroid[2] + t.normal[2] * 8]).join() === '3,1' && Math.abs(t.normal[2]) > 0.99);
    expect(frame).toHaveLength(4);
    // North and south faces beside a vertical door: DOORWALL + 2.
    for (const t of frame) expect(pageOf(t.material)).toBe(100);
    // The same wall's other faces keep their own pages (wall 4 below: light page 6 on its north face... toward (3,1) is the frame).
    expect(walls.filter((t) => pageOf(t.material) === 100)).toHaveLength(4);
  });

  it('uses DOORWALL + 3 for the frame of a horizontal door, + 0 for its panel, + 7 for a locked vertical door', () => {
    const scene = build(['###', '#v#', '#-#', '#.#', '#G#', '#.#', '###']);
    const walls = triangles(scene).filter(isWall);
    const frame = walls.filter((t) => tileOf([t.centroid[0] + t.normal[0] * 8, 0, t.centroid[2]]).join() === '1,2' && Math.abs(t.normal[0]) > 0.99);
    expect(frame.map((t) => pageOf(t.material))).toEqual([101, 101, 101, 101]);
    const doors = scene.dynamics!.slidingDoors!.doors;
    const page = (k: number) => pageOf(triangles(scene, (n) => n === scene.instances.find((i) => i.id === doors[k]!.instance)!.name)[0]!.material);
    expect(page(0)).toBe(98);
    expect(page(1)).toBe(98 + 7);
  });
});

/** Walks in small steps from `from` by (dx, dz) on `map`. */
function walk(map: WalkMap, from: WalkPosition, dx: number, dz: number): WalkPosition {
  return moveWalker(map, from, dx, dz);
}

/** The walk map with an update's heights applied. */
function withHeights(map: WalkMap, heights: ReadonlyMap<number, readonly [number, number]>): WalkMap {
  const floors = new Float32Array(map.floors), ceilings = new Float32Array(map.ceilings);
  for (const [s, [f, c]] of heights) [floors[s], ceilings[s]] = [f, c];
  return { ...map, floors, ceilings };
}

describe('doors in the world', () => {
  const view = (x: number, z: number, fx = 1, fz = 0): Viewpoint => ({ position: [x, WOLF_EYE_HEIGHT, z], forward: [fx, 0, fz] });
  const FAR = view(1.5 * T, 1.5 * T);

  it('is shut at the start: the walker cannot pass the closed door', () => {
    const scene = build(DOOR_MAP);
    const map = scene.walkMap!;
    const start = { x: 2.5 * T, z: 1.5 * T, sector: sectorAt(map, 2.5 * T, 1.5 * T) };
    const end = walk(map, start, 3 * T, 0);
    expect(end.x).toBeLessThan(3 * T);
  });

  it('opens as the viewer comes near, lets the walker through, waits and closes; never on the player', () => {
    const scene = build(DOOR_MAP);
    const world = World.of(scene)!;
    const door = scene.dynamics!.slidingDoors!.doors[0]!;
    let map = withHeights(scene.walkMap!, world.advance(0, FAR)!.walkHeights);
    expect(map.ceilings[door.sector]).toBe(0);
    // 1.5 tiles west of the panel is not yet in front (the viewer at 2.1 tiles).
    world.advance(1, view(1.4 * T, 1.5 * T));
    const near = view(2.2 * T, 1.5 * T);
    // Opening: half way after half the travel time, still shut for walking.
    let u = world.advance(0.01, near)!;
    u = world.advance(DOOR_TRAVEL_SECONDS / 2, near)!;
    const pose = u.instances.get(door.instance)!.worldFromObject!;
    // The closed panel's tile starts at z = T; half open, it has slid half a tile south (0.01 s early start aside).
    expect(Math.abs(pose[14]! - 1.5 * T)).toBeLessThan(1);
    expect(u.walkHeights.has(door.sector)).toBe(false);
    u = world.advance(DOOR_TRAVEL_SECONDS, near)!;
    expect(u.instances.get(door.instance)!.worldFromObject![14]).toBeCloseTo(2 * T, 6);
    map = withHeights(map, u.walkHeights);
    expect(map.ceilings[door.sector]).toBe(T);
    const through = walk(map, { x: 2.5 * T, z: 1.5 * T, sector: sectorAt(map, 2.5 * T, 1.5 * T) }, 2 * T, 0);
    expect(through.x).toBeCloseTo(4.5 * T, 3);
    // Standing in the doorway: it stays open well past its wait.
    const inDoor = view(3.5 * T, 1.5 * T);
    for (let t = 0; t < 3 * DOOR_WAIT_SECONDS; t += 0.1) expect(world.advance(0.1, inDoor)?.walkHeights.get(door.sector)).toBeUndefined();
    // Gone (out of reach of the proximity trigger, east of it): it closes after its wait and travel.
    const gone = view(5.5 * T, 1.5 * T);
    const all = world.advanceTo(world.seconds + DOOR_WAIT_SECONDS + DOOR_TRAVEL_SECONDS + 0.1, gone);
    expect(all.walkHeights.get(door.sector)).toEqual([0, 0]);
    expect(all.instances.get(door.instance)!.worldFromObject![14]).toBeCloseTo(T, 6);
  });

  it('opens on the use key from the tile next to it, facing it; not facing away', () => {
    const scene = build(DOOR_MAP);
    const set = { ...scene.dynamics!.slidingDoors!, trigger: 'use' as const };
    const world = World.of({ ...scene, dynamics: { ...scene.dynamics, slidingDoors: set } })!;
    const door = set.doors[0]!;
    const beside = view(2.6 * T, 1.5 * T);
    world.advance(0, beside);
    world.advance(2, beside);
    expect(world.use(view(2.6 * T, 1.5 * T, -1, 0))).toBe(false);
    expect(world.use(view(1.6 * T, 1.5 * T, 1, 0))).toBe(false);
    expect(world.use(beside)).toBe(true);
    const u = world.advance(DOOR_TRAVEL_SECONDS + 0.01, beside)!;
    expect(u.walkHeights.get(door.sector)).toEqual([0, T]);
  });

  it('reopens when the player steps into the doorway while it closes', () => {
    const scene = build(DOOR_MAP);
    const world = World.of(scene)!;
    const door = scene.dynamics!.slidingDoors!.doors[0]!;
    world.advance(0, view(2.2 * T, 1.5 * T));
    world.advance(DOOR_TRAVEL_SECONDS + 0.1, view(2.2 * T, 1.5 * T));
    world.advance(DOOR_WAIT_SECONDS + DOOR_TRAVEL_SECONDS / 2, view(5.5 * T, 1.5 * T));
    // Half closed: the body comes into the door tile (from the east, as if it had just walked through).
    const u = world.advance(DOOR_TRAVEL_SECONDS / 4, view(4 * T + 10, 1.5 * T, -1, 0))!;
    const z = u.instances.get(door.instance)!.worldFromObject![14]! - T;
    expect(z).toBeGreaterThan(T / 2);
  });
});

describe('push walls', () => {
  // A push wall at (3, 2) in a west–east corridor, two free tiles east of it, then a wall.
  const PUSH = ['########', '########', '#>.P..##', '########'];
  const view = (x: number, z: number, fx = 1, fz = 0): Viewpoint => ({ position: [x, WOLF_EYE_HEIGHT, z], forward: [fx, 0, fz] });

  it('is a moving block of four faces with its wall pages', () => {
    const scene = build(PUSH);
    const wall = scene.dynamics!.pushWalls!.walls[0]!;
    const inst = scene.instances.find((i) => i.id === wall.instance)!;
    expect(inst.moves).toBe(true);
    const faces = triangles(scene, (n) => n === inst.name);
    expect(faces).toHaveLength(8);
    for (const t of faces) expect(pageOf(t.material)).toBe(Math.abs(t.normal[2]) > 0.99 ? 4 : 5);
    // The static walls around it show faces toward its tile (they are seen once it moves).
    const around = triangles(scene).filter(isWall).filter((t) => tileOf([t.centroid[0] + t.normal[0] * 8, 0, t.centroid[2] + t.normal[2] * 8]).join() === '3,2');
    expect(around).toHaveLength(4);
  });

  it('slides two tiles away from the player who uses it, and the walk map follows', () => {
    const scene = build(PUSH);
    const world = World.of(scene)!;
    const wall = scene.dynamics!.pushWalls!.walls[0]!;
    let map = withHeights(scene.walkMap!, world.advance(0, view(2.5 * T, 2.5 * T))!.walkHeights);
    const blocked = walk(map, { x: 2.5 * T, z: 2.5 * T, sector: sectorAt(map, 2.5 * T, 2.5 * T) }, T, 0);
    expect(blocked.x).toBeLessThan(3 * T);
    expect(world.use(view(2.5 * T, 2.5 * T, 1, 0.2))).toBe(true);
    // Half way through the first tile.
    let u = world.advance(PUSH_WALL_SECONDS_PER_TILE / 2, view(2.5 * T, 2.5 * T));
    expect(u!.instances.get(wall.instance)!.worldFromObject![12]).toBeCloseTo(3.5 * T, 3);
    u = world.advanceTo(world.seconds + 2 * PUSH_WALL_SECONDS_PER_TILE, view(2.5 * T, 2.5 * T));
    expect(u.instances.get(wall.instance)!.worldFromObject![12]).toBeCloseTo(5 * T, 6);
    map = withHeights(map, u.walkHeights);
    // The walker now walks into the two tiles the block left, and is stopped by the block at 5.
    const end = walk(map, { x: 2.5 * T, z: 2.5 * T, sector: sectorAt(map, 2.5 * T, 2.5 * T) }, 3 * T, 0);
    expect(end.x).toBeGreaterThan(4.5 * T);
    expect(end.x).toBeLessThan(5 * T);
    // It moves once.
    expect(world.use(view(4.5 * T, 2.5 * T, 1, 0))).toBe(false);
  });

  it('stops after one tile when the second is not free, and does not move when the first is not', () => {
    const one = build(['#######', '#>.P.b#', '#######']);
    const w1 = World.of(one)!;
    w1.advance(0, view(2.5 * T, 1.5 * T));
    expect(w1.use(view(2.5 * T, 1.5 * T))).toBe(true);
    const u = w1.advanceTo(10, view(2.5 * T, 1.5 * T));
    expect(u.instances.get(one.dynamics!.pushWalls!.walls[0]!.instance)!.worldFromObject![12]).toBeCloseTo(4 * T, 6);
    const none = build(['#####', '#>.P#', '#####']);
    const w2 = World.of(none)!;
    w2.advance(0, view(2.5 * T, 1.5 * T));
    expect(w2.use(view(2.5 * T, 1.5 * T))).toBe(false);
  });

  it('agrees with the level on the order of directions', () => {
    expect(PUSH_DIRECTIONS).toEqual(DIRECTIONS);
  });
});

describe('static objects and lamps', () => {
  it('stands each object at its tile centre as a sprite of its statinfo page', () => {
    const scene = build(['#######', '#>.o.b#', '#.c.lL#', '#######']);
    const billboards = scene.dynamics!.billboards!;
    expect(billboards).toHaveLength(5);
    const byName = new Map(billboards.map((b) => [scene.materials[b.frames[0]!.images[0]!.material]!.name, b]));
    expect(byName.get('puddle')!.position).toEqual([3.5 * T, 0, 1.5 * T]);
    expect(byName.get('barrel')!.position).toEqual([5.5 * T, 0, 1.5 * T]);
    expect(byName.get('chandelier')!.position).toEqual([2.5 * T, 0, 2.5 * T]);
    // The sprite of SPR_STAT_k is sprite page 2 + k (the test sprites are red = their index).
    const textureRed = (name: string) => {
      const m = scene.materials[byName.get(name)!.frames[0]!.images[0]!.material]!;
      expect(m.kind === 'diffuse' && m.alphaMode).toBe('mask');
      return m.kind === 'diffuse' ? scene.textures![m.albedoTexture!.texture]!.rgba[4 * 64 * 63] : undefined;
    };
    expect(textureRed('puddle')).toBe(2);
    expect(textureRed('barrel')).toBe(2 + 35);
    expect(textureRed('chandelier')).toBe(2 + 4);
    const image = billboards[0]!.frames[0]!.images[0]!;
    expect([image.width, image.height, image.left, image.top]).toEqual([T, T, T / 2, T]);
    for (const b of billboards) expect(scene.instances.find((i) => i.id === b.instance)!.moves).toBe(true);
    // No sprite emits.
    for (const b of billboards) expect(scene.materials[b.frames[0]!.images[0]!.material]!.emission).toEqual([0, 0, 0]);
  });

  it('hangs a small emitter facing down under each lamp, and none elsewhere', () => {
    const scene = build(['#######', '#>.o.b#', '#.c.lL#', '#######']);
    const lights = triangles(scene).filter((t) => scene.materials.find((m) => m.name === t.material)!.kind === 'emissive');
    expect(lights).toHaveLength(6);
    for (const t of lights) expect(t.normal[1]).toBeCloseTo(-1, 9);
    const at = (x: number, y: number) => lights.filter((t) => tileOf(t.centroid).join() === `${x},${y}`);
    expect(at(2, 2)[0]!.a[1]).toBe(LAMPS.chandelier.height);
    expect(at(4, 2)[0]!.a[1]).toBe(LAMPS['ceiling light'].height);
    expect(at(5, 2)[0]!.a[1]).toBe(LAMPS['floor lamp'].height);
    for (const [x, y] of [[2, 2], [4, 2], [5, 2]]) {
      const xs = at(x!, y!).flatMap((t) => [t.a[0], t.b[0], t.c[0]]);
      expect((Math.min(...xs) + Math.max(...xs)) / 2).toBeCloseTo((x! + 0.5) * T, 9);
    }
    // Radiance: the floor straight beneath gets irradiance ≈ π (L · A / h² for a small source).
    const lamp = LAMPS.chandelier;
    expect((lampRadiance(lamp) * lamp.size ** 2) / lamp.height ** 2).toBeCloseTo(Math.PI, 9);
  });

  it('blocks the walker at a blocking object, not at a puddle', () => {
    const scene = build(['#######', '#>.o.b#', '#######']);
    const map = scene.walkMap!;
    const end = moveWalker(map, { x: 2.5 * T, z: 1.5 * T, sector: sectorAt(map, 2.5 * T, 1.5 * T) }, 4 * T, 0);
    expect(end.x).toBeGreaterThan(4 * T);
    expect(end.x).toBeLessThan(5 * T);
  });

  it('stands guards and dogs still, with eight rotations facing their way; officers are left out, said once', () => {
    const warnings: string[] = [];
    const scene = build(['#######', '#>.gnd#', '#.O...#', '#######'], warnings);
    const billboards = scene.dynamics!.billboards!;
    expect(billboards).toHaveLength(3);
    const [east, north, dog] = billboards;
    expect(east!.position).toEqual([3.5 * T, 0, 1.5 * T]);
    expect(east!.facing).toBe(0);
    expect(north!.facing).toBeCloseTo(Math.PI / 2, 12);
    // SPR_GRD_S_1 = 50 … 57, the dog's first walking frame SPR_DOG_W1_1 = 99 … 106 (test sprites are red = their index).
    const red = (b: typeof east, k: number) => {
      const m = scene.materials[b!.frames[0]!.images[k]!.material]!;
      return m.kind === 'diffuse' ? scene.textures![m.albedoTexture!.texture]!.rgba[4 * 64 * 63] : undefined;
    };
    expect([0, 1, 7].map((k) => red(east, k))).toEqual([50, 51, 57]);
    expect(dog!.facing).toBe(0);
    expect([0, 4].map((k) => red(dog, k))).toEqual([99, 103]);
    expect(warnings.join('\n')).toMatch(/1 officers, mutants, bosses and ghosts are not shown/);
  });

  it('draws the actors of the skill: skill 3 by default, 4 adds the hardest', () => {
    const map = testMap(['#######', '#>.ghH#', '#######']);
    const at = (skill?: number) => wolfMapToScene(testGame([map]), map, skill === undefined ? {} : { skill }).dynamics!.billboards!.length;
    expect([at(1), at(2), at(), at(4), at(5)]).toEqual([1, 1, 2, 3, 3]);
  });
});

describe('validation of the moving parts', () => {
  it('rejects a door whose instance does not move, and a push wall naming a sector past the walk map', () => {
    const scene = build(['#########', '#>.|..P.#', '#########']);
    const set = scene.dynamics!.slidingDoors!;
    const still = scene.instances.find((i) => !i.moves)!.id;
    expect(() => validateScene({ ...scene, dynamics: { ...scene.dynamics, slidingDoors: { ...set, doors: [{ ...set.doors[0]!, instance: still }] } } })).toThrow(/sliding door 0 moves instance/);
    const walls = scene.dynamics!.pushWalls!;
    const far = scene.walkMap!.floors.length;
    expect(() => validateScene({ ...scene, dynamics: { ...scene.dynamics, pushWalls: { ...walls, walls: [{ ...walls.walls[0]!, sector: far }] } } })).toThrow(/push wall 0 names a walk-map sector/);
    expect(() => validateScene({ ...scene, dynamics: { ...scene.dynamics, slidingDoors: { ...set, travelSeconds: 0 } } })).toThrow(/travel time/);
  });
});
