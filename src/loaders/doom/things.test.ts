/**
 * Doom's things end to end on WADs built in code: sprite lump names, the sprite index of a WAD stack,
 * which things appear at which skill, and the scene's sprite instances and materials.
 */
import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../../expect-lantern-error.ts';
import type { DiffuseMaterial, Scene } from '../../scene/types.ts';
import { validateScene } from '../../scene/validate.ts';
import { sceneUpdateAt } from '../../world/world.ts';
import { FIRE_THING_STRENGTH, LAMP_STRENGTH } from './light-table.ts';
import { loadDoomMap } from './load.ts';
import type { Thing } from './map-types.ts';
import { readPalette } from './palette.ts';
import { parseSpriteLumpName, SpriteSet } from './sprites.ts';
import { encodeMap, encodePalette, encodePatch, squareRoom, squareRoomWad, testPaletteColor, WadBuilder } from './test-wad.ts';
import { thingAppears, THING_TYPES } from './thing-types.ts';
import { readWad, WadStack } from './wad.ts';

describe('parseSpriteLumpName', () => {
  it('reads sprite, frame and rotation', () => {
    expect(parseSpriteLumpName('TROOA1')).toEqual({ sprite: 'TROO', frame: 'A', rotation: 1 });
    expect(parseSpriteLumpName('COLUA0')).toEqual({ sprite: 'COLU', frame: 'A', rotation: 0 });
  });

  it('reads the mirrored second frame and rotation', () => {
    expect(parseSpriteLumpName('TROOA2A8')).toEqual({ sprite: 'TROO', frame: 'A', rotation: 2, mirror: { frame: 'A', rotation: 8 } });
    expect(parseSpriteLumpName('SARGB3C7')).toEqual({ sprite: 'SARG', frame: 'B', rotation: 3, mirror: { frame: 'C', rotation: 7 } });
  });

  it.each(['TROO', 'TROOA9', 'TROOa1', 'TROOA1A', 'TROOA1A9', 'TROOAA', 'S_START'])('refuses %s', (name) => {
    expect(parseSpriteLumpName(name)).toBeUndefined();
  });
});

// ---- a small WAD with sprites ----

/** A w×h picture of palette index `index`, transparent on its left half when `holes`. */
const picture = (w: number, h: number, index: (x: number, y: number) => number, offsets: { leftOffset: number; topOffset: number }) =>
  encodePatch(w, h, Array.from({ length: w * h }, (_, i) => index(i % w, Math.floor(i / w))), offsets);

const IMP = (tag: number) => picture(8, 12, (x) => (x < 4 ? -1 : tag), { leftOffset: 4, topOffset: 12 });
/** A lamp: a bright top (palette index 1) over a dark stand (index 2). */
const LAMP = picture(4, 16, (_x, y) => (y < 4 ? 1 : 2), { leftOffset: 2, topOffset: 16 });
const HANGING = picture(6, 68, () => 3, { leftOffset: 3, topOffset: 68 });

/** Palette: index 1 bright yellow, 2 dark grey, 3 red; others from testPaletteColor. */
const PALETTE = Array.from({ length: 256 }, (_, i) => (i === 1 ? [255, 240, 160] : i === 2 ? [40, 40, 40] : i === 3 ? [200, 0, 0] : testPaletteColor(i))) as [number, number, number][];

function spritesWad(things: readonly Thing[], extra: (b: WadBuilder) => WadBuilder = (b) => b): WadStack {
  const base = readWad(squareRoomWad('MAP01'), 'room.wad');
  const room = squareRoom('MAP01');
  const map = { ...room, sectors: [{ ...room.sectors[0]!, floorHeight: 16, ceilingHeight: 144 }], things: [...room.things, ...things] };
  const pwad = extra(
    new WadBuilder()
      .lump('PLAYPAL', encodePalette(PALETTE))
      .lumps(encodeMap(map))
      .marker('S_START')
      .lump('TROOA1', IMP(10))
      .lump('TROOA2A8', IMP(11))
      .lump('TROOA3A7', IMP(12))
      .lump('TROOA4A6', IMP(13))
      .lump('TROOA5', IMP(14))
      .lump('TROOB0', IMP(15)) // the imp's second standing frame, one picture for every angle
      .lump('COLUA0', LAMP)
      .lump('GOR1A0', HANGING)
      .lump('GOR1B0', HANGING)
      .lump('GOR1C0', HANGING)
      .lump('POSSA1', IMP(20)) // a zombieman with only one of its eight rotations
      .marker('S_END'),
  ).build('PWAD');
  return new WadStack([base, readWad(pwad, 'things.wad')]);
}

const thing = (type: number, x: number, y: number, flags = 7, angle = 0): Thing => ({ type, x, y, angle, flags });

describe('SpriteSet', () => {
  it('collects the eight rotations of a frame, the second half mirrored from the paired lumps', () => {
    const stack = spritesWad([]);
    const sprites = new SpriteSet(stack, readPalette(stack));
    const imp = sprites.frame('TROO', 'A')!;
    expect(imp.views.map((v) => v.lump)).toEqual(['TROOA1', 'TROOA2A8', 'TROOA3A7', 'TROOA4A6', 'TROOA5', 'TROOA4A6', 'TROOA3A7', 'TROOA2A8']);
    expect(imp.views.map((v) => v.mirrored)).toEqual([false, false, false, false, false, true, true, true]);
    expect(sprites.frame('COLU', 'A')!.views).toEqual([{ lump: 'COLUA0', mirrored: false }]);
    expect(sprites.frame('TROO', 'C')).toBeUndefined();
  });

  it('refuses a frame with missing rotations, saying which', () => {
    const stack = spritesWad([]);
    const warnings: string[] = [];
    const sprites = new SpriteSet(stack, readPalette(stack), (w) => warnings.push(w));
    expect(sprites.frame('POSS', 'A')).toBeUndefined();
    expect(warnings).toEqual(['sprite POSS frame A lacks rotation(s) 2, 3, 4, 5, 6, 7, 8; not drawn']);
  });

  it("lets a later WAD's single picture replace an earlier WAD's eight rotations", () => {
    const stack = spritesWad([]);
    const over = new WadBuilder().marker('SS_START').lump('TROOA0', IMP(30)).marker('SS_END').build('PWAD');
    const layered = new WadStack([...stack.files, readWad(over, 'over.wad')]);
    expect(new SpriteSet(layered, readPalette(layered)).frame('TROO', 'A')!.views).toEqual([{ lump: 'TROOA0', mirrored: false }]);
  });

  it('decodes pictures with their offsets, transparent where no post covers', () => {
    const stack = spritesWad([]);
    const p = new SpriteSet(stack, readPalette(stack)).picture('TROOA1')!;
    expect([p.width, p.height, p.leftOffset, p.topOffset]).toEqual([8, 12, 4, 12]);
    expect(p.rgba[3]).toBe(0);
    expect([...p.rgba.subarray(16, 20)]).toEqual([...testPaletteColor(10), 255]);
  });
});

describe('which things appear', () => {
  it.each([
    // flags, skills 1..5 single player, multiplayer at skill 3
    [0b00001, [true, true, false, false, false], false],
    [0b00010, [false, false, true, false, false], true],
    [0b00100, [false, false, false, true, true], false],
    [0b01111, [true, true, true, true, true], true], // deaf changes nothing
    [0b10111, [false, false, false, false, false], true], // multiplayer only
    [0b00000, [false, false, false, false, false], false],
  ] as const)('flags %i', (flags, single, multi) => {
    expect([1, 2, 3, 4, 5].map((s) => thingAppears(flags, s))).toEqual(single);
    expect(thingAppears(flags, 3, true)).toBe(multi);
  });

  it('filters the things of a map by skill and the multiplayer flag', () => {
    const stack = spritesWad([thing(3001, 64, 64, 1), thing(3001, 96, 64, 2), thing(3001, 128, 64, 4), thing(3001, 160, 64, 7 | 16), thing(2028, 192, 64, 7 | 8)]);
    const drawn = (skill?: number) => loadDoomMap(stack, 'MAP01', skill === undefined ? {} : { things: { skill } }).stats.sprites;
    expect([1, 2, 3, 4, 5].map(drawn)).toEqual([2, 2, 2, 2, 2]);
    expect(drawn()).toBe(2);
    const positions = (skill: number) => loadDoomMap(stack, 'MAP01', { things: { skill } }).scene.dynamics!.billboards!.map((b) => b.position[0]);
    expect(positions(1)).toEqual([64, 192]);
    expect(positions(3)).toEqual([96, 192]);
    expect(positions(5)).toEqual([128, 192]);
    expect(loadDoomMap(stack, 'MAP01', { things: { skill: 3, multiplayer: true } }).stats.sprites).toBe(3);
  });

  it('refuses a skill outside 1–5', () => {
    const stack = spritesWad([]);
    expectLanternError(() => loadDoomMap(stack, 'MAP01', { things: { skill: 6 } }), /skill 6 is not a Doom skill level/);
  });
});

describe('things in the scene', () => {
  const load = (things: readonly Thing[], options: Parameters<typeof loadDoomMap>[2] = {}) => {
    const warnings: string[] = [];
    const loaded = loadDoomMap(spritesWad(things), 'MAP01', { onWarning: (w) => warnings.push(w), ...options });
    validateScene(loaded.scene);
    return { ...loaded, warnings };
  };
  const instanceOf = (scene: Scene, id: number) => scene.instances.find((i) => i.id === id)!;

  it('places an imp as a moving instance of the sprite quad, its material the sprite rotation facing the player', () => {
    // The player stands at (128, 128) facing north (90°); the imp north of it faces south, at him.
    const { scene, stats } = load([thing(3001, 128, 224, 7, 270)]);
    expect(stats.sprites).toBe(1);
    expect(stats.emittingSprites).toBe(0);
    const [b] = scene.dynamics!.billboards!;
    expect(b!.position).toEqual([128, 16, -224]);
    const inst = instanceOf(scene, b!.instance);
    expect(inst.moves).toBe(true);
    expect(inst.name).toBe('Imp');
    expect(scene.meshes[inst.mesh]!.name).toBe('sprite quad');
    const m = scene.materials[inst.material!] as DiffuseMaterial;
    expect(m.name).toBe('TROOA1');
    expect(m.alphaMode).toBe('mask');
    expect(m.emission).toEqual([0, 0, 0]);
    const tex = scene.textures![m.albedoTexture!.texture]!;
    expect(tex.filter).toBe('nearest');
    expect([tex.width, tex.height]).toEqual([8, 12]);
    // Opaque right half in palette colour 10, transparent left half.
    expect(tex.rgba[4 * 1 + 3]).toBe(0);
    expect([...tex.rgba.subarray(4 * 5, 4 * 6)]).toEqual([...testPaletteColor(10), 255]);
    // The first pose is the one the world's animator gives from the player's view.
    const view = { position: scene.camera.position, forward: scene.camera.forward };
    expect(sceneUpdateAt(scene, 0, view).instances.get(b!.instance)).toEqual({ worldFromObject: inst.worldFromObject, material: inst.material });
  });

  it("animates the imp through its standing states, A and B for 10 tics each, starting part-way into A", () => {
    const { scene } = load([thing(3001, 128, 224, 7, 270), thing(3001, 64, 224, 7, 270), thing(3001, 192, 224, 7, 270)]);
    const billboards = scene.dynamics!.billboards!;
    for (const b of billboards) {
      expect(b.frames.map((f) => [f.duration, f.images.length])).toEqual([[10 / 35, 8], [10 / 35, 1]]);
      expect(b.frames[1]!.images[0]!.material).not.toBe(b.frames[0]!.images[0]!.material);
      expect(scene.materials[b.frames[1]!.images[0]!.material]!.name).toBe('TROOB0');
      // P_SpawnMapThing: the first state lasts 1..10 tics, so the cycle starts 0..9 tics in.
      const phase = Math.round((b.phase ?? 0) * 35);
      expect(phase).toBeGreaterThanOrEqual(0);
      expect(phase).toBeLessThanOrEqual(9);
      expect(b.phase ?? 0).toBeCloseTo(phase / 35, 12);
    }
    // Deterministic, and not all in step.
    expect(new Set(billboards.map((b) => b.phase ?? 0)).size).toBeGreaterThan(1);
    expect(load([thing(3001, 128, 224, 7, 270), thing(3001, 64, 224, 7, 270), thing(3001, 192, 224, 7, 270)]).scene.dynamics!.billboards!.map((b) => b.phase)).toEqual(billboards.map((b) => b.phase));
  });

  it('shows the imp from behind (rotation 5) when it faces away', () => {
    const { scene } = load([thing(3001, 128, 224, 7, 90)]);
    const inst = instanceOf(scene, scene.dynamics!.billboards![0]!.instance);
    expect(scene.materials[inst.material!]!.name).toBe('TROOA5');
  });

  it('hangs a hanging thing its height below the ceiling', () => {
    const { scene } = load([thing(49, 64, 64)]);
    expect(THING_TYPES.get(49)!.height).toBe(68);
    expect(scene.dynamics!.billboards![0]!.position[1]).toBe(144 - 68);
  });

  it('makes a floor lamp emit from its bright texels on both faces, whatever the sector light, unless the light table says otherwise', () => {
    const { scene, stats } = load([thing(2028, 64, 64)]);
    expect(stats.emittingSprites).toBe(1);
    const inst = instanceOf(scene, scene.dynamics!.billboards![0]!.instance);
    const m = scene.materials[inst.material!] as DiffuseMaterial;
    // The room's sector is at light 160, which scales wall lamps; things are full bright.
    expect(m.emission).toEqual([LAMP_STRENGTH, LAMP_STRENGTH, LAMP_STRENGTH]);
    expect(m.twoSidedEmission).toBe(true);
    const glow = scene.textures![m.emissionTexture!.texture]!;
    expect([...glow.rgba.subarray(0, 4)]).toEqual([255, 240, 160, 255]);
    expect([...glow.rgba.subarray(4 * 4 * 8, 4 * 4 * 8 + 4)]).toEqual([0, 0, 0, 255]);

    const off = load([thing(2028, 64, 64)], { lightTable: { things: { colu: { strength: 0 } } } });
    expect(off.stats.emittingSprites).toBe(0);
    const offMaterial = off.scene.materials[instanceOf(off.scene, off.scene.dynamics!.billboards![0]!.instance).material!]!;
    expect(offMaterial.emission).toEqual([0, 0, 0]);
    expect(offMaterial.twoSidedEmission).toBeUndefined();
    expect(FIRE_THING_STRENGTH).toBeGreaterThan(0);
  });

  it('leaves out player starts, warns about unknown things and things without sprites, and draws the rest', () => {
    const { stats, warnings, scene } = load([thing(3001, 64, 64), thing(1, 96, 96), thing(14, 100, 100), thing(9999, 70, 70), thing(3004, 80, 80)]);
    expect(stats.sprites).toBe(1);
    expect(warnings).toContain('MAP01: 1 thing(s) of unknown type 9999; not drawn');
    expect(warnings).toContain('MAP01: the WADs have no usable sprite POSS frame A for 1 thing(s); not drawn');
    // Level meshes and the quad, each placed; ids unique (validateScene checked).
    expect(scene.instances.filter((i) => i.moves && i.material !== undefined)).toHaveLength(1);
  });

  it('draws nothing, and adds no quad, for a map without visible things', () => {
    const { scene, stats } = load([]);
    expect(stats.sprites).toBe(0);
    expect(scene.dynamics).toBeUndefined();
    expect(scene.meshes.some((m) => m.name === 'sprite quad')).toBe(false);
  });
});
