/**
 * A Doom thing on the GPU: an imp's sprite standing in front of a wall, seen through the albedo debug
 * view (the primary hit's linear albedo, no noise). Its picture is transparent on its left half and
 * a flat colour on its right half, so where the sprite's quad projects, the opaque half must show the
 * sprite's colour (it hides the wall) and the transparent half must show the wall and floor behind.
 * The quad's projection is computed here from the camera: 64×48 pixels, 73.74° vertical field of view,
 * so 32 pixels of focal length.
 */
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { loadDoomMap } from '../../src/loaders/doom/load.ts';
import { encodeMap, encodePatch, squareRoom, squareRoomWad, testPaletteColor, WadBuilder } from '../../src/loaders/doom/test-wad.ts';
import { readWad, WadStack } from '../../src/loaders/doom/wad.ts';
import { prepareScene } from '../../src/renderer/prepare.ts';
import { Renderer } from '../../src/renderer/renderer.ts';
import { testGpu } from './gpu-context.ts';

const W = 64, H = 48;
const FOCAL = H / 2 / 0.75; // tan(73.74° / 2) = 0.75
const SPRITE_INDEX = 50;
const [SW, SH] = [32, 48];

/** The room of squareRoomWad (player at (128, 128), eye 41 above the floor, facing north) and an imp 72 units north of him, facing him. */
function scene() {
  const room = squareRoom('MAP01');
  const imp = encodePatch(SW, SH, Array.from({ length: SW * SH }, (_, i) => (i % SW < SW / 2 ? -1 : SPRITE_INDEX)), { leftOffset: SW / 2, topOffset: SH });
  const pwad = new WadBuilder()
    .lumps(encodeMap({ ...room, things: [...room.things, { type: 3001, x: 128, y: 200, angle: 270, flags: 7 }] }))
    .marker('S_START')
    .lump('TROOA0', imp)
    .lump('TROOB0', imp) // the imp's second standing frame: the same picture
    .marker('S_END')
    .build('PWAD');
  const stack = new WadStack([readWad(squareRoomWad('MAP01'), 'room.wad'), readWad(pwad, 'imp.wad')]);
  return loadDoomMap(stack, 'MAP01').scene;
}

const linear = (c: number) => ((c / 255) <= 0.04045 ? c / 255 / 12.92 : ((c / 255 + 0.055) / 1.055) ** 2.4);
const SPRITE_ALBEDO = testPaletteColor(SPRITE_INDEX).map(linear);

let renderer: Renderer;
let albedo: Float32Array;

beforeAll(async () => {
  const s = scene();
  expect(s.instances.filter((i) => i.moves)).toHaveLength(1);
  renderer = await Renderer.create(await testGpu());
  await renderer.setScene(prepareScene(s));
  await renderer.resize(W, H);
  renderer.updateSettings({ debugView: 'albedo', debugLayout: 'replace' });
  albedo = await renderer.readDebugValues();
});

afterAll(() => renderer?.destroy());

const isSprite = (i: number) => [0, 1, 2].every((k) => Math.abs(albedo[i * 4 + k]! - SPRITE_ALBEDO[k]!) < 2e-3);

describe('a sprite in front of a wall', () => {
  // World x of the quad: 128 ± 16 (left offset 16); y from 0 to 48 (top offset 48 = height), 72 units
  // in front of the eye at y = 41. Pixel column = 32 + (x − 128)·FOCAL/72, row = 24 − (y − 41)·FOCAL/72.
  const column = (x: number) => W / 2 + ((x - 128) * FOCAL) / 72;
  const row = (y: number) => H / 2 - ((y - 41) * FOCAL) / 72;
  const inside = (x0: number, x1: number, y0: number, y1: number) => {
    const out: number[] = [];
    // Pixels whose whole square lies inside the rectangle.
    for (let py = Math.ceil(row(y1)); py + 1 <= Math.floor(row(y0)); py++) for (let px = Math.ceil(column(x0)); px + 1 <= Math.floor(column(x1)); px++) out.push(py * W + px);
    return out;
  };

  it('hides the wall where its texels are opaque', () => {
    const opaque = inside(128, 144, 0, 48);
    expect(opaque.length).toBeGreaterThan(100);
    expect(opaque.filter((i) => !isSprite(i))).toEqual([]);
  });

  it('shows the wall and floor through its transparent texels', () => {
    const clear = inside(112, 128, 0, 48);
    expect(clear.length).toBeGreaterThan(100);
    // Not the sprite, nor its transparent texels' black: the wall (STARTAN3, palette 100–103) or the floor (10).
    const behind = [100, 101, 102, 103, 10].map((i) => testPaletteColor(i).map(linear));
    const isBehind = (i: number) => behind.some((c) => [0, 1, 2].every((k) => Math.abs(albedo[i * 4 + k]! - c[k]!) < 2e-3));
    expect(clear.filter((i) => !isBehind(i))).toEqual([]);
    expect(clear.filter(isSprite)).toEqual([]);
  });

  it('covers as many pixels as its opaque half projects to, and no others', () => {
    let count = 0;
    for (let i = 0; i < W * H; i++) if (isSprite(i)) count++;
    const area = (column(144) - column(128)) * (row(0) - row(48));
    // Pixel centres sample the rectangle: the count differs from its area by at most its perimeter's worth.
    const perimeter = 2 * (column(144) - column(128) + row(0) - row(48));
    expect(Math.abs(count - area)).toBeLessThan(perimeter / 2);
  });
});
