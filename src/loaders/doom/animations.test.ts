/**
 * Doom's animated flats and textures, scrolling walls and sector light specials (animations.ts),
 * from the table and lumps to the scene's material animations (to-scene.ts), on tiny WADs built in
 * code and on Freedoom's E1M1 (skipped where the IWAD is absent).
 */
import { existsSync, readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../../expect-lantern-error.ts';
import { sceneUpdateAt } from '../../world/world.ts';
import { DOOM_ANIMATIONS, readAnimatedLump, resolveCycles, sectorLightPattern, sectorNeighbours } from './animations.ts';
import { DEFAULT_LIGHT_TABLE, emissionOf } from './light-table.ts';
import { loadDoomMap } from './load.ts';
import { LINEDEF_FLAGS } from './map-types.ts';
import { animatedRoomWad, ccw, cw, MapBuilder, type AnimatedRoomOptions } from './test-wad.ts';
import { readWad, WadStack } from './wad.ts';

const TIC = 1 / 35;

/** A BOOM ANIMATED record. */
function animatedRecord(kind: 'flat' | 'texture', last: string, first: string, tics: number): number[] {
  const out = new Uint8Array(23);
  out[0] = kind === 'texture' ? 1 : 0;
  for (let i = 0; i < last.length; i++) out[1 + i] = last.charCodeAt(i);
  for (let i = 0; i < first.length; i++) out[10 + i] = first.charCodeAt(i);
  new DataView(out.buffer).setInt32(19, tics, true);
  return Array.from(out);
}

describe('animation definitions', () => {
  it('run over every name between the first and the last in WAD order, and skip cycles the WAD lacks', () => {
    const warnings: string[] = [];
    const cycles = resolveCycles(DOOM_ANIMATIONS, { flats: ['FLOOR1', 'NUKAGE1', 'NUKAGE2', 'ODD', 'NUKAGE3', 'LAVA1', 'LAVA2'], textures: ['FIREWALB', 'FIREWALA', 'FIREWALL'] }, (w) => warnings.push(w));
    expect(cycles.of('flat', 'ODD')).toEqual({ cycle: { kind: 'flat', names: ['NUKAGE1', 'NUKAGE2', 'ODD', 'NUKAGE3'], ticsPerFrame: 8 }, frame: 2 });
    expect(cycles.of('flat', 'NUKAGE3')?.frame).toBe(3);
    expect(cycles.of('flat', 'FLOOR1')).toBeUndefined();
    // LAVA4 is absent: vanilla would stop; Lantern leaves LAVA still.
    expect(cycles.of('flat', 'LAVA1')).toBeUndefined();
    // FIREWALA–FIREWALL in this WAD's order leaves FIREWALB out.
    expect(cycles.of('texture', 'FIREWALA')?.cycle.names).toEqual(['FIREWALA', 'FIREWALL']);
    expect(cycles.of('texture', 'FIREWALB')).toBeUndefined();
    // A name of the other namespace is not a member.
    expect(cycles.of('texture', 'NUKAGE1')).toBeUndefined();
    expect(warnings).toEqual([]);
    const backwards = resolveCycles(DOOM_ANIMATIONS, { flats: ['NUKAGE3', 'NUKAGE2', 'NUKAGE1'], textures: [] }, (w) => warnings.push(w));
    expect(backwards.cycles).toEqual([]);
    expect(warnings).toEqual(['animated flat NUKAGE1–NUKAGE3: NUKAGE3 comes before NUKAGE1 in the WAD, so there is nothing to cycle; not animated']);
  });

  it('read from a BOOM ANIMATED lump (last name first, speed in tics)', () => {
    const lump = new Uint8Array([...animatedRecord('flat', 'NUKAGE3', 'NUKAGE1', 4), ...animatedRecord('texture', 'BLODGR4', 'BLODGR1', 12), 0xff]);
    expect(readAnimatedLump(lump)).toEqual([
      { kind: 'flat', first: 'NUKAGE1', last: 'NUKAGE3', ticsPerFrame: 4 },
      { kind: 'texture', first: 'BLODGR1', last: 'BLODGR4', ticsPerFrame: 12 },
    ]);
    expectLanternError(() => readAnimatedLump(lump.subarray(0, 23)), /not ended by a record of type 255/);
    expectLanternError(() => readAnimatedLump(lump.subarray(0, 30)), /record 1 is cut short/);
    expectLanternError(() => readAnimatedLump(new Uint8Array([...animatedRecord('flat', 'A', 'B', 0), 0xff])), /0 tics per frame/);
  });
});

/** Sector 0 a 256-unit room around sector 1, a 64-unit square; sector 2 a room east of 0 through a two-sided line. */
function lightMap(special0: number, light1: number, light2 = 255) {
  const b = new MapBuilder();
  const s0 = b.sector({ lightLevel: 160, special: special0 });
  const s1 = b.sector({ lightLevel: light1 });
  b.loop(cw(0, 0, 256), s0);
  b.loop(ccw(96, 96, 64), s0, s1);
  const s2 = b.sector({ lightLevel: light2 });
  b.loop(cw(512, 0, 64), s2);
  return { map: b.build(), s0, s1, s2 };
}

describe('sector light specials (P_SpawnSpecials)', () => {
  it('take min light from the darkest neighbour across two-sided lines', () => {
    const { map } = lightMap(1, 96);
    const n = sectorNeighbours(map);
    expect(n[0]).toEqual([1]);
    expect(sectorLightPattern(map, 0, n, 5)).toEqual({ kind: 'flash', maxLevel: 160, minLevel: 96, maxTime: 64, minTime: 7, seed: 5 });
    expect(sectorLightPattern(map, 1, n, 5)).toBeUndefined();
  });

  it('give each special its thinker: 2/4 fast and 3 slow strobes, 12 slow and 13 fast in sync, 8 glow, 17 flicker', () => {
    const expectPattern = (special: number) => {
      const { map } = lightMap(special, 96);
      return sectorLightPattern(map, 0, sectorNeighbours(map), 0);
    };
    const strobe = { kind: 'strobe', maxLevel: 160, minLevel: 96, brightTics: 5, seed: 0 };
    expect(expectPattern(2)).toEqual({ ...strobe, darkTics: 15, inSync: false });
    expect(expectPattern(4)).toEqual({ ...strobe, darkTics: 15, inSync: false });
    expect(expectPattern(3)).toEqual({ ...strobe, darkTics: 35, inSync: false });
    expect(expectPattern(12)).toEqual({ ...strobe, darkTics: 35, inSync: true });
    expect(expectPattern(13)).toEqual({ ...strobe, darkTics: 15, inSync: true });
    expect(expectPattern(8)).toEqual({ kind: 'glow', maxLevel: 160, minLevel: 96, step: 8 });
    expect(expectPattern(17)).toEqual({ kind: 'flicker', maxLevel: 160, minLevel: 112, seed: 0 });
    // BOOM's generalised specials keep the light special in bits 0–4 (here with damage bits set).
    expect(expectPattern(12 + 64)).toEqual({ ...strobe, darkTics: 35, inSync: true });
    for (const notLight of [0, 5, 7, 9, 10, 11, 14, 16]) expect(expectPattern(notLight)).toBeUndefined();
  });

  it('with no darker neighbour: a strobe goes down to 0, a flicker up to 16 above its own level, a flash and a glow stay', () => {
    const { map } = lightMap(2, 200);
    const n = sectorNeighbours(map);
    expect(sectorLightPattern({ ...map, sectors: map.sectors.map((s, i) => (i === 0 ? { ...s, special: 2 } : s)) }, 0, n, 0)).toMatchObject({ minLevel: 0, maxLevel: 160 });
    expect(sectorLightPattern({ ...map, sectors: map.sectors.map((s, i) => (i === 0 ? { ...s, special: 17 } : s)) }, 0, n, 0)).toMatchObject({ minLevel: 176, maxLevel: 160 });
    expect(sectorLightPattern({ ...map, sectors: map.sectors.map((s, i) => (i === 0 ? { ...s, special: 8 } : s)) }, 0, n, 0)).toMatchObject({ minLevel: 160, maxLevel: 160 });
  });

  it('ignore one-sided lines and lines without the two-sided flag (getNextSector)', () => {
    const { map } = lightMap(1, 96);
    const flagless = { ...map, linedefs: map.linedefs.map((l) => ({ ...l, flags: l.flags & ~LINEDEF_FLAGS.TWO_SIDED })) };
    expect(sectorNeighbours(flagless)).toEqual([[], [], []]);
  });
});

function animatedWad(options: AnimatedRoomOptions = {}): WadStack {
  return new WadStack([readWad(animatedRoomWad(options), 'animated.wad')]);
}

describe('a Doom map with animations', () => {
  it('has a texture cycle for its NUKAGE floor, a scroll for its special-48 wall and emission patterns for its strobing sector\'s emitters', () => {
    const { scene, stats } = loadDoomMap(animatedWad(), undefined);
    const a = scene.dynamics!.materialAnimations!;
    const names = (ts: readonly number[]) => ts.map((t) => scene.textures![t]!.name);
    const material = (i: number) => scene.materials[i]!;

    expect(a.cycles).toHaveLength(1);
    const cycle = a.cycles![0]!;
    expect(material(cycle.material).name).toMatch(/^NUKAGE2/);
    expect(names(cycle.frames)).toEqual(['NUKAGE1', 'NUKAGE2', 'FLOOR4_8', 'NUKAGE3']);
    expect(cycle.firstFrame).toBe(1);
    expect(cycle.secondsPerFrame).toBeCloseTo(8 * TIC, 15);
    // Nukage emits through its own picture: the emission texture follows the frames.
    expect(cycle.emissionFrames).toEqual(cycle.frames);

    expect(a.scrolls).toHaveLength(1);
    const scroll = a.scrolls![0]!;
    expect(material(scroll.material).name).toBe('STARTAN3');
    expect(scroll.velocity).toEqual([35 / 64, 0]);
    expect(scroll.stepSeconds).toBeCloseTo(TIC, 15);
    // The other STARTAN3 walls are another material, which does not scroll.
    const startan = scene.materials.flatMap((m, i) => (m.name === 'STARTAN3' ? [i] : []));
    expect(startan).toHaveLength(2);

    // Special 12: a slow strobe in sync between 160 and the neighbour's 96, on the nukage and the lamp.
    expect(a.patterns!.map((p) => material(p.material).name.replace(/ .*/, '')).sort()).toEqual(['CEIL1_2', 'NUKAGE2']);
    for (const p of a.patterns!) {
      expect(p.pattern).toEqual({ kind: 'strobe', maxLevel: 160, minLevel: 96, brightTics: 5, darkTics: 35, inSync: true, seed: 0 });
      const source = DEFAULT_LIGHT_TABLE.flats[material(p.material).name.replace(/ .*/, '')];
      expect(p.emission).toEqual(emissionOf(source, 255));
      // At rest the material emits what a still sector at 160 would.
      expect(material(p.material).emission).toEqual(emissionOf(source, 160));
    }
    expect(stats).toMatchObject({ cycledMaterials: 1, scrollingLines: 1, lightSpecialSectors: 1, patternedMaterials: 2 });

    // 9 tics in: the cycle shows its third frame (FLOOR4_8), the wall has moved 9 texels, the sector is dark.
    const u = sceneUpdateAt(scene, 9 * TIC, { position: [0, 0, 0], forward: [1, 0, 0] });
    expect(scene.textures![u.materials.get(cycle.material)!.albedoTexture!]!.name).toBe('FLOOR4_8');
    expect(u.materials.get(scroll.material)!.uvOffset![0]).toBeCloseTo(9 / 64, 9);
    const lamp = a.patterns!.find((p) => material(p.material).name.startsWith('CEIL1_2'))!;
    expect(u.materials.get(lamp.material)!.emission).toEqual(emissionOf(DEFAULT_LIGHT_TABLE.flats.CEIL1_2, 96));
  });

  it('keeps a sector without a light special, and a cycle with a missing frame, still', () => {
    const { scene, stats } = loadDoomMap(animatedWad({ special: 0, withNukage3: false }), undefined);
    const a = scene.dynamics!.materialAnimations!;
    expect(a.cycles).toBeUndefined();
    expect(a.patterns).toBeUndefined();
    expect(a.scrolls).toHaveLength(1);
    expect(stats).toMatchObject({ cycledMaterials: 0, scrollingLines: 1, lightSpecialSectors: 0, patternedMaterials: 0 });
  });

  it('takes its cycles from an ANIMATED lump when the WAD has one', () => {
    const lump = new Uint8Array([...animatedRecord('flat', 'NUKAGE2', 'NUKAGE1', 4), 0xff]);
    const cycles = loadDoomMap(animatedWad({ animated: lump }), undefined).scene.dynamics!.materialAnimations!.cycles!;
    expect(cycles).toHaveLength(1);
    expect(cycles[0]!.frames).toHaveLength(2);
    expect(cycles[0]!.secondsPerFrame).toBeCloseTo(4 * TIC, 15);
  });
});

const FREEDOOM1 = '/usr/share/games/doom/freedoom1.wad';

describe.skipIf(!existsSync(FREEDOOM1))('Freedoom E1M1 and E1M2', () => {
  const stack = existsSync(FREEDOOM1) ? new WadStack([readWad(readFileSync(FREEDOOM1), 'freedoom1.wad')]) : undefined;
  it('E1M1: 7 cycling materials, no scrolling lines, 6 light-special sectors of which 3 hold emitters', () => {
    const { scene, stats } = loadDoomMap(stack!, 'E1M1');
    // Counted by hand from the map's lumps: NUKAGE1 floors and ceilings in sectors at light 224,
    // 208 and 192 (nukage emits, so each level is a material), FWATER1 ceilings (no emission: one
    // material), SFALL1 walls at 208 and 224, WFALL1 walls (one): 3 + 1 + 2 + 1.
    expect(stats.cycledMaterials).toBe(7);
    const cycled = scene.dynamics!.materialAnimations!.cycles!.map((c) => scene.materials[c.material]!.name.replace(/ .*/, '')).sort();
    expect(cycled).toEqual(['FWATER1', 'NUKAGE1', 'NUKAGE1', 'NUKAGE1', 'SFALL1', 'SFALL1', 'WFALL1']);
    // No linedef of E1M1 has special 48.
    expect(stats.scrollingLines).toBe(0);
    // Sectors 32, 33 and 48 (special 1), 90 and 96 (12), 92 (2). Only 32 and 33 (LITE5 walls) and
    // 90 (AQLITE02 walls) hold emitting surfaces; the others' blinking changes no emitter.
    expect(stats.lightSpecialSectors).toBe(6);
    expect(stats.patternedMaterials).toBe(3);
    const patterned = scene.dynamics!.materialAnimations!.patterns!.map((p) => `${scene.materials[p.material]!.name.replace(/ .*/, '')}:${p.pattern.kind}`).sort();
    expect(patterned).toEqual(['AQLITE02:strobe', 'LITE5:flash', 'LITE5:flash']);
  });

  it('E1M2: its two special-48 lines scroll', () => {
    const { scene, stats } = loadDoomMap(stack!, 'E1M2');
    expect(stats.scrollingLines).toBe(2);
    expect(scene.dynamics!.materialAnimations!.scrolls!.length).toBeGreaterThanOrEqual(1);
  });
});
