/**
 * Doom's things on the GPU: two imps standing in front of a wall, seen through the albedo debug view
 * (the primary hit's linear albedo, no noise). Their picture is transparent on its left half; its
 * right half is one colour above and another below. One imp is seen from rotation 2, which shows the
 * picture as it is; the other from rotation 8, which shows the same lump mirrored (TROOA2A8). Where a
 * quad projects, the opaque half must show the picture's colours, the right way up, and hide the
 * wall; the transparent half must show the wall and floor behind. The projection is computed here:
 * 64×48 pixels, 73.74° vertical field of view, so 32 pixels of focal length; both quads face the view
 * plane, 72 units in front of the eye. Then the world is stepped from another view and its update
 * applied: the imps turn to the new view plane and show the rotation seen from there.
 */
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { loadDoomMap } from '../../src/loaders/doom/load.ts';
import { encodeMap, encodePatch, squareRoom, squareRoomWad, testPaletteColor, WadBuilder } from '../../src/loaders/doom/test-wad.ts';
import { readWad, WadStack } from '../../src/loaders/doom/wad.ts';
import { prepareScene } from '../../src/renderer/prepare.ts';
import { Renderer } from '../../src/renderer/renderer.ts';
import { cameraBasis } from '../../src/gpu/view.ts';
import { determinant3, transformPoint } from '../../src/math/mat4.ts';
import { dot, normalize, sub, type Vec3 } from '../../src/math/vec3.ts';
import type { Camera, Scene } from '../../src/scene/types.ts';
import { World } from '../../src/world/world.ts';
import { testGpu } from './gpu-context.ts';

const W = 64, H = 48;
const FOCAL = H / 2 / 0.75; // tan(73.74° / 2) = 0.75
const [TOP, BOTTOM] = [50, 60];
const [SW, SH] = [32, 48];

/**
 * The room of squareRoomWad (player at (128, 128), eye 41 above the floor, facing north) with two
 * imps 72 units north of him, 32 units to either side, facing south: the left one sees him 24°
 * counter-clockwise of its facing (rotation 2), the right one 24° clockwise (rotation 8, mirrored).
 */
function scene(): Scene {
  const room = squareRoom('MAP01');
  const index = (i: number) => (i % SW < SW / 2 ? -1 : Math.floor(i / SW) < SH / 2 ? TOP : BOTTOM);
  const imp = encodePatch(SW, SH, Array.from({ length: SW * SH }, (_, i) => index(i)), { leftOffset: SW / 2, topOffset: SH });
  const imps = [96, 160].map((x) => ({ type: 3001, x, y: 200, angle: 270, flags: 7 }));
  const builder = new WadBuilder().lumps(encodeMap({ ...room, things: [...room.things, ...imps] })).marker('S_START');
  for (const lump of ['TROOA1', 'TROOA2A8', 'TROOA3A7', 'TROOA4A6', 'TROOA5', 'TROOB0']) builder.lump(lump, imp);
  const stack = new WadStack([readWad(squareRoomWad('MAP01'), 'room.wad'), readWad(builder.marker('S_END').build('PWAD'), 'imps.wad')]);
  return loadDoomMap(stack, 'MAP01').scene;
}

const linear = (c: number) => ((c / 255) <= 0.04045 ? c / 255 / 12.92 : ((c / 255 + 0.055) / 1.055) ** 2.4);
const albedoOf = (index: number) => testPaletteColor(index).map(linear);

let renderer: Renderer;
let albedo: Float32Array;
let shown: string[];
let loaded: Scene;

beforeAll(async () => {
  const s = (loaded = scene());
  shown = s.instances.filter((i) => i.material !== undefined).map((i) => s.materials[i.material!]!.name);
  renderer = await Renderer.create(await testGpu());
  await renderer.setScene(prepareScene(s));
  await renderer.resize(W, H);
  renderer.updateSettings({ debugView: 'albedo', debugLayout: 'replace' });
  albedo = await renderer.readDebugValues();
});

afterAll(() => renderer?.destroy());

const is = (index: number) => {
  const c = albedoOf(index);
  return (i: number) => [0, 1, 2].every((k) => Math.abs(albedo[i * 4 + k]! - c[k]!) < 2e-3);
};
const isSprite = (i: number) => is(TOP)(i) || is(BOTTOM)(i);

// Pixel column of world x on the quads' plane, and row of world height y.
const column = (x: number) => W / 2 + ((x - 128) * FOCAL) / 72;
const row = (y: number) => H / 2 - ((y - 41) * FOCAL) / 72;
/** Pixels whose whole square lies inside the rectangle x0..x1, y0..y1. */
function inside(x0: number, x1: number, y0: number, y1: number): number[] {
  const out: number[] = [];
  for (let py = Math.ceil(row(y1)); py + 1 <= Math.floor(row(y0)); py++) for (let px = Math.ceil(column(x0)); px + 1 <= Math.floor(column(x1)); px++) out.push(py * W + px);
  return out;
}

describe('sprites in front of a wall', () => {
  it('shows the rotations Doom shows: 2 as it is, 8 mirrored from the same lump', () => {
    expect(shown).toEqual(['TROOA2A8', 'TROOA2A8']);
  });

  // The left imp (x 96, its picture over x 80..112) shows the picture as it is: opaque on x 96..112.
  // The right imp (x 160, over 144..176) mirrors it in place: opaque on x 144..160.
  const opaque = [[96, 112], [144, 160]] as const;
  const clear = [[80, 96], [160, 176]] as const;

  it('hides the wall where the texels are opaque, with the picture the right way up', () => {
    for (const [x0, x1] of opaque) {
      const top = inside(x0, x1, 24, 48);
      const bottom = inside(x0, x1, 0, 24);
      expect(top.length).toBeGreaterThan(40);
      expect(bottom.length).toBeGreaterThan(40);
      expect(top.filter((i) => !is(TOP)(i))).toEqual([]);
      expect(bottom.filter((i) => !is(BOTTOM)(i))).toEqual([]);
    }
  });

  it('shows the wall and floor through the transparent texels', () => {
    // Not the sprite, nor its transparent texels' black: the wall (STARTAN3, palette 100–103) or the floor (10).
    const behind = [100, 101, 102, 103, 10].map(is);
    for (const [x0, x1] of clear) {
      const pixels = inside(x0, x1, 0, 48);
      expect(pixels.length).toBeGreaterThan(100);
      expect(pixels.filter((i) => !behind.some((b) => b(i)))).toEqual([]);
    }
  });

  it('covers as many pixels as the opaque halves project to, and no others', () => {
    let count = 0;
    for (let i = 0; i < W * H; i++) if (isSprite(i)) count++;
    const [w, h] = [column(112) - column(96), row(0) - row(48)];
    // Pixel centres sample each rectangle: the count differs from the area by at most half the perimeter's worth.
    expect(Math.abs(count - 2 * w * h)).toBeLessThan(2 * (w + h));
  });
});

/** The pixel (x, y) whose primary ray passes nearest `p` (gpu/view.ts primaryRay inverted). */
function project(camera: Camera, p: Vec3): [number, number] {
  const b = cameraBasis(camera, W / H);
  const v = sub(p, b.position);
  const t = dot(v, b.forward);
  const nx = dot(v, b.right) / (t * dot(b.right, b.right));
  const ny = -dot(v, b.up) / (t * dot(b.up, b.up));
  return [((nx + 1) * W) / 2, ((ny + 1) * H) / 2];
}

describe('the world turns the sprites toward a new view (World -> applySceneUpdate -> GPU)', () => {
  // From map (250, 100), south-east of both imps and looking between them: R_PointToAngle from there
  // is 147° to the left imp and 132° to the right one; less their facing (270°) plus 202.5°, 79.5°
  // and 64.5°: rotation 2 for both (TROOA2A8 as drawn), so the right imp, mirrored from the player
  // start (rotation 8), turns back. 15° apart, the two quads do not overlap on the screen.
  const camera = (): Camera => ({ ...loaded.camera, position: [250, 41, -100], forward: normalize([-122, -21, -100]) });

  it("shows each imp's new rotation, facing the new view plane, opaque where its texels are", async () => {
    const view = camera();
    const update = World.of(loaded)!.advance(0, { position: view.position, forward: view.forward })!;
    renderer.applySceneUpdate(update);
    renderer.setCamera(view);
    const seen = await renderer.readDebugValues();
    const sprites = loaded.dynamics!.billboards!;
    const poses = sprites.map((b) => update.instances.get(b.instance)!);
    expect(poses.map((p) => loaded.materials[p.material!]!.name)).toEqual(['TROOA2A8', 'TROOA2A8']);
    expect(poses.map((p) => determinant3(p.worldFromObject!) < 0)).toEqual([false, false]);
    const at = (i: number, k: number) => seen[i * 4 + k]!;
    const colour = (i: number) => [at(i, 0), at(i, 1), at(i, 2)];
    const near = (c: number[], index: number) => albedoOf(index).every((x, k) => Math.abs(c[k]! - x) < 2e-3);
    for (const pose of poses) {
      const m = pose.worldFromObject!;
      // The quad's normal (object +z) points against the view's horizontal forward.
      const n = sub(transformPoint(m, [0, 0, 1]), transformPoint(m, [0, 0, 0]));
      expect(Math.sign(determinant3(m)) * dot(n, [view.forward[0], 0, view.forward[2]])).toBeLessThan(0);
      // Object x runs along the picture's columns (u), y up its rows from the bottom.
      for (const [u, v, index] of [[0.7, 0.8, TOP], [0.85, 0.65, TOP], [0.7, 0.2, BOTTOM], [0.85, 0.35, BOTTOM], [0.2, 0.5, -1], [0.3, 0.3, -1]] as const) {
        const [px, py] = project(view, transformPoint(m, [u, v, 0]));
        const i = Math.floor(py) * W + Math.floor(px);
        if (index < 0) expect(near(colour(i), TOP) || near(colour(i), BOTTOM), `transparent (${u}, ${v})`).toBe(false);
        else expect(near(colour(i), index), `opaque (${u}, ${v}) at pixel ${px.toFixed(1)}, ${py.toFixed(1)}`).toBe(true);
      }
    }
  });
});
