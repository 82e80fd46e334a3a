/**
 * world/material-animation.ts: cycle frames, scroll offsets and the light patterns against hand-
 * computed sequences of p_lights.c's thinkers; the animator writes what changed and only that.
 */
import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../expect-lantern-error.ts';
import {
  cycleFrameAt,
  LightPatternPlayer,
  materialAnimator,
  patternEmission,
  patternLevelAt,
  patternRandom,
  scrollOffsetAt,
  startLightPattern,
  tickLightPattern,
} from './material-animation.ts';
import type { EmissionPattern, LightPattern, MaterialAnimations, TextureCycle, UvScroll } from '../scene/dynamics-types.ts';
import { diffuse, type Scene } from '../scene/types.ts';
import type { Viewpoint } from './animator.ts';
import { sceneUpdateAt, World } from './world.ts';

const TIC = 1 / 35;
const view: Viewpoint = { position: [0, 0, 0], forward: [0, 0, -1] };

/** The levels of tics 0..n-1, with Doom's P_Random replaced by a script. */
function scripted(p: LightPattern, randoms: readonly number[], n: number): number[] {
  let k = 0;
  const random = () => {
    if (k >= randoms.length) throw new Error(`the pattern drew random number ${k + 1}; the script has ${randoms.length}`);
    return randoms[k++]!;
  };
  const s = startLightPattern(p, random);
  const out = [s.level];
  for (let t = 1; t < n; t++) {
    tickLightPattern(p, s, random);
    out.push(s.level);
  }
  return out;
}

const runs = (...parts: [number, number][]) => parts.flatMap(([level, n]) => Array<number>(n).fill(level));

describe('texture cycles', () => {
  const cycle: TextureCycle = { material: 0, frames: [10, 11, 12], secondsPerFrame: 8 * TIC, firstFrame: 1 };
  it('advance one frame every 8 tics from their first frame and wrap', () => {
    expect(cycleFrameAt(cycle, 0)).toBe(1);
    expect(cycleFrameAt(cycle, 7.99 * TIC)).toBe(1);
    expect(cycleFrameAt(cycle, 8 * TIC)).toBe(2);
    expect(cycleFrameAt(cycle, 15 * TIC)).toBe(2);
    expect(cycleFrameAt(cycle, 16 * TIC)).toBe(0);
    expect(cycleFrameAt(cycle, 24 * TIC)).toBe(1);
    // A minute in: 2100 tics = 262 whole frames, 262 + 1 ≡ 2 (mod 3).
    expect(cycleFrameAt(cycle, 60)).toBe(2);
  });
});

describe('uv scrolls', () => {
  const scroll: UvScroll = { material: 0, velocity: [35 / 64, 0], stepSeconds: TIC };
  it('move one texel of a 64-wide texture per tic, in whole tics, and wrap', () => {
    expect(scrollOffsetAt(scroll, 0)).toEqual([0, 0]);
    expect(scrollOffsetAt(scroll, 0.99 * TIC)[0]).toBe(0);
    expect(scrollOffsetAt(scroll, TIC)[0]).toBeCloseTo(1 / 64, 12);
    expect(scrollOffsetAt(scroll, 1.5 * TIC)[0]).toBeCloseTo(1 / 64, 12);
    expect(scrollOffsetAt(scroll, 10 * TIC)[0]).toBeCloseTo(10 / 64, 12);
    expect(scrollOffsetAt(scroll, 64 * TIC)[0]).toBeCloseTo(0, 9);
    expect(scrollOffsetAt(scroll, 65 * TIC)[0]).toBeCloseTo(1 / 64, 9);
  });
  it('without a step move continuously, in both directions', () => {
    const [u, v] = scrollOffsetAt({ material: 0, velocity: [0.25, -0.1] }, 3);
    expect(u).toBeCloseTo(0.75, 12);
    expect(v).toBeCloseTo(0.7, 12);
  });
});

describe('light patterns (p_lights.c)', () => {
  it('a synchronised slow strobe (special 12): dark after one tic for 35 tics, bright for 5', () => {
    const p: LightPattern = { kind: 'strobe', maxLevel: 200, minLevel: 100, brightTics: 5, darkTics: 35, inSync: true, seed: 1 };
    expect(scripted(p, [], 82)).toEqual(runs([200, 1], [100, 35], [200, 5], [100, 35], [200, 5], [100, 1]));
  });
  it('an unsynchronised fast strobe (special 2) waits (random & 7) + 1 tics first', () => {
    const p: LightPattern = { kind: 'strobe', maxLevel: 160, minLevel: 0, brightTics: 5, darkTics: 15, inSync: false, seed: 1 };
    // 13 & 7 = 5: six tics at the start level, then 15 dark, 5 bright.
    expect(scripted(p, [13], 30)).toEqual(runs([160, 6], [0, 15], [160, 5], [0, 4]));
  });
  it('a glow (special 8) steps 8 a tic down to just above its minimum and back up to just below its maximum', () => {
    const p: LightPattern = { kind: 'glow', maxLevel: 160, minLevel: 120, step: 8 };
    expect(scripted(p, [], 12)).toEqual([160, 152, 144, 136, 128, 128, 136, 144, 152, 152, 144, 136]);
  });
  it('a flash (special 1): bright for (random & 64) + 1 tics, dark for (random & 7) + 1', () => {
    const p: LightPattern = { kind: 'flash', maxLevel: 176, minLevel: 144, maxTime: 64, minTime: 7, seed: 1 };
    // 64 & 64 = 64: 65 bright tics; 3 & 7: 4 dark; 0 & 64: 1 bright; 15 & 7: 8 dark; then 200 & 64 = 64.
    expect(scripted(p, [64, 3, 0, 15, 200], 80)).toEqual(runs([176, 65], [144, 4], [176, 1], [144, 8], [176, 2]));
  });
  it('a fire flicker (special 17): every 4 tics max − 16·(random & 3), or min when the current level minus that is below it', () => {
    const p: LightPattern = { kind: 'flicker', maxLevel: 160, minLevel: 128, seed: 1 };
    // tic 4: amount 0 → 160; tic 8: 48 → 112 < 128 → 128; tic 12: 16, from 128 → 128;
    // tic 16: 0 → 160; tic 20: 16 → 144.
    expect(scripted(p, [0, 3, 1, 0, 1], 24)).toEqual(runs([160, 8], [128, 8], [160, 4], [144, 4]));
  });
  it('random patterns are pure functions of time: the same level at t however they got there, and only allowed levels', () => {
    const flicker: EmissionPattern = { material: 0, emission: [48, 48, 48], fullLevel: 255, exponent: 2, ticsPerSecond: 35, pattern: { kind: 'flicker', maxLevel: 192, minLevel: 144, seed: 7 } };
    const flash: EmissionPattern = { ...flicker, pattern: { kind: 'flash', maxLevel: 176, minLevel: 96, maxTime: 64, minTime: 7, seed: 3 } };
    for (const p of [flicker, flash]) {
      const player = new LightPatternPlayer(p.pattern);
      const seen = new Set<number>();
      for (let tic = 0; tic < 1000; tic += 7) {
        const level = player.levelAt(tic);
        seen.add(level);
        expect(level).toBe(patternLevelAt(p, tic * TIC));
      }
      // Asked for an earlier tic, the player starts again and agrees.
      expect(player.levelAt(35)).toBe(patternLevelAt(p, 1));
      const allowed = p.pattern.kind === 'flicker' ? [192, 176, 160, 144] : [176, 96];
      expect([...seen].every((l) => allowed.includes(l))).toBe(true);
      expect(seen.size).toBeGreaterThan(1);
    }
    expect(patternRandom(7, 0)).toBe(patternRandom(7, 0));
    expect(new Set(Array.from({ length: 64 }, (_, i) => patternRandom(7, i))).size).toBeGreaterThan(32);
  });
  it('scale emission by (level / full)^exponent, clamped at full', () => {
    const p: EmissionPattern = { material: 0, emission: [10, 20, 40], fullLevel: 255, exponent: 2, ticsPerSecond: 35, pattern: { kind: 'glow', maxLevel: 255, minLevel: 0, step: 8 } };
    expect(patternEmission(p, 127.5)).toEqual([2.5, 5, 10]);
    expect(patternEmission(p, 300)).toEqual([10, 20, 40]);
    expect(patternEmission(p, -5)).toEqual([0, 0, 0]);
  });
});

function animatedScene(a: MaterialAnimations): Scene {
  const tex = (name: string) => ({ name, width: 2, height: 2, rgba: new Uint8Array(16).fill(200) });
  return {
    name: 'animated',
    meshes: [],
    instances: [],
    materials: [diffuse('a', [1, 1, 1], [1, 1, 1], { albedoTexture: { texture: 0 }, emissionTexture: { texture: 0 } }), diffuse('b', [1, 1, 1], [0, 0, 0], { albedoTexture: { texture: 1 } })],
    textures: [tex('t0'), tex('t1'), tex('t2')],
    camera: { position: [0, 0, 0], forward: [0, 0, -1], up: [0, 1, 0], vfovDegrees: 60 },
    dynamics: { materialAnimations: a },
  };
}

describe('the material animator', () => {
  const cycle: TextureCycle = { material: 0, frames: [0, 1, 2], emissionFrames: [0, 1, 2], secondsPerFrame: 8 * TIC };
  const scroll: UvScroll = { material: 1, velocity: [35 / 2, 0], stepSeconds: TIC };
  const pattern: EmissionPattern = { material: 0, emission: [4, 4, 4], fullLevel: 255, exponent: 2, ticsPerSecond: 35, pattern: { kind: 'strobe', maxLevel: 255, minLevel: 51, brightTics: 5, darkTics: 35, inSync: true, seed: 0 } };

  it('writes every animated material on the first step, then only what changed', () => {
    const world = World.of(animatedScene({ cycles: [cycle], scrolls: [scroll], patterns: [pattern] }))!;
    const first = world.advance(0, view)!;
    expect(first.materials.get(0)).toEqual({ albedoTexture: 0, emissionTexture: 0, emission: [4, 4, 4] });
    expect(first.materials.get(1)).toEqual({ uvOffset: [0, 0] });
    // Half a tic: nothing moves.
    expect(world.advance(TIC / 2, view)).toBeUndefined();
    // Tic 1: the strobe goes dark ((51/255)² = 0.04) and the scroll moves half a texture.
    const t1 = world.advance(TIC / 2, view)!;
    expect([...t1.materials.keys()].sort()).toEqual([0, 1]);
    expect(t1.materials.get(0)!.emission![0]).toBeCloseTo(0.16, 12);
    expect(t1.materials.get(0)!.albedoTexture).toBeUndefined();
    expect(t1.materials.get(1)!.uvOffset![0]).toBeCloseTo(0.5, 12);
    // Tic 2: the scroll wraps to 0; the cycle and strobe hold.
    const t2 = world.advance(TIC, view)!;
    expect([...t2.materials.keys()]).toEqual([1]);
    expect(t2.materials.get(1)!.uvOffset![0]).toBeCloseTo(0, 9);
  });

  it('shows at --time t what playing up to t shows', () => {
    const scene = animatedScene({ cycles: [cycle], patterns: [pattern] });
    const u = sceneUpdateAt(scene, 17 * TIC, view);
    // 17 tics: frame 2 (16 tics in); the strobe is dark from tic 1 to tic 35.
    expect(u.materials.get(0)!.albedoTexture).toBe(2);
    expect(u.materials.get(0)!.emissionTexture).toBe(2);
    expect(u.materials.get(0)!.emission![0]).toBeCloseTo(0.16, 12);
    const later = sceneUpdateAt(scene, 37 * TIC, view);
    expect(later.materials.get(0)!.emission).toEqual([4, 4, 4]);
  });

  it('refuses animations that name what the scene lacks', () => {
    expect(materialAnimator(animatedScene({}))).toBeUndefined();
    expectLanternError(() => World.of(animatedScene({ cycles: [{ ...cycle, material: 5 }] })), /texture cycle 0 refers to material 5 of 2/);
    expectLanternError(() => World.of(animatedScene({ cycles: [{ ...cycle, frames: [0, 9] , emissionFrames: undefined }] })), /refers to texture 9 of 3/);
    expectLanternError(() => World.of(animatedScene({ cycles: [{ ...cycle, frames: [0] , emissionFrames: undefined }] })), /needs two or more/);
    expectLanternError(() => World.of(animatedScene({ cycles: [{ ...cycle, emissionFrames: [0, 1] }] })), /2 emission frames for 3 frames/);
    expectLanternError(() => World.of(animatedScene({ patterns: [{ ...pattern, pattern: { kind: 'glow', maxLevel: 1, minLevel: 0, step: 0 } }] })), /glow's step must be positive/);
  });
});
