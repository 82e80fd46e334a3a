/**
 * Materials that change with time: the animator of Scene.dynamics.materialAnimations (the data:
 * scene/dynamics-types.ts), its checks, and the pure functions of time it steps:
 * - texture cycles: a material shows the frames of a cycle in turn (Doom's animated flats and wall
 *   textures: NUKAGE1–3, FIREWALA–FIREWALL, ...);
 * - uv scrolls: a material's textures slide at a constant uv velocity (Doom's linedef special 48);
 * - emission patterns: a material's emission follows a light level that a small state machine
 *   steps once per tic (Doom's sector light specials, p_lights.c: flash, strobe, glow, flicker).
 *
 * Everything is a pure function of time: the random patterns draw from a hash of their seed and the
 * draw's number, never from a shared generator, so `lantern render --time t` shows the same frame
 * every time and the viewer shows what --time would at the same instant. Each step writes a
 * MaterialEdit only for materials whose state changed (a frame, a texel of scroll, a light level).
 * Pure: no DOM, no GPU.
 */
import { LanternError } from '../errors.ts';
import type { Vec3 } from '../math/vec3.ts';
import type { EmissionPattern, LightPattern, MaterialAnimations, TextureCycle, UvScroll } from '../scene/dynamics-types.ts';
import type { MaterialEdit } from '../scene/material-edit.ts';
import type { Scene } from '../scene/types.ts';
import type { Animator, AnimatorFactory, UpdateBuilder } from './animator.ts';

/** A count of whole periods in `t` (seconds), robust to `t` being a float multiple of `period`. */
function wholeSteps(t: number, period: number): number {
  return Math.floor(t / period + 1e-9);
}

/** The frame (index into cycle.frames) the cycle shows at `t` seconds. */
export function cycleFrameAt(cycle: TextureCycle, t: number): number {
  const n = cycle.frames.length;
  const k = (cycle.firstFrame ?? 0) + wholeSteps(Math.max(0, t), cycle.secondsPerFrame);
  return ((k % n) + n) % n;
}

/** The uv offset of a scroll at `t` seconds, each component wrapped to [0, 1). */
export function scrollOffsetAt(scroll: UvScroll, t: number): [number, number] {
  const step = scroll.stepSeconds ?? 0;
  const time = step > 0 ? wholeSteps(Math.max(0, t), step) * step : Math.max(0, t);
  const wrap = (x: number) => {
    const f = x - Math.floor(x);
    return f >= 1 ? 0 : f;
  };
  return [wrap(scroll.velocity[0] * time), wrap(scroll.velocity[1] * time)];
}

/**
 * The n-th pseudo-random byte (0–255) of `seed`: a 32-bit integer hash (lowbias32, Chris Wellons'
 * hash-prospector) of seed and n. Doom's P_Random is one table shared by the whole game, so its
 * sequence depends on everything else that happens; Lantern's patterns each draw their own.
 */
export function patternRandom(seed: number, n: number): number {
  let x = (Math.imul(seed | 0, 0x9e3779b1) ^ (n | 0)) >>> 0;
  x ^= x >>> 16;
  x = Math.imul(x, 0x7feb352d);
  x ^= x >>> 15;
  x = Math.imul(x, 0x846ca68b);
  x ^= x >>> 16;
  return (x >>> 0) & 255;
}

/** The state a light pattern carries from tic to tic (a thinker's fields). */
export interface LightPatternState {
  level: number;
  count: number;
  direction: -1 | 1;
}

/** The state at tic 0 (P_Spawn*: the level is the sector's own); `random` gives Doom's P_Random(). */
export function startLightPattern(p: LightPattern, random: () => number): LightPatternState {
  const s: LightPatternState = { level: p.maxLevel, count: 0, direction: -1 };
  switch (p.kind) {
    case 'flash':
      s.count = (random() & p.maxTime) + 1;
      break;
    case 'strobe':
      s.count = p.inSync ? 1 : (random() & 7) + 1;
      break;
    case 'glow':
      break;
    case 'flicker':
      s.count = 4;
      break;
  }
  return s;
}

/** One tic of the pattern's thinker (p_lights.c), in place. */
export function tickLightPattern(p: LightPattern, s: LightPatternState, random: () => number): void {
  switch (p.kind) {
    case 'flash': // T_LightFlash
      if (--s.count) return;
      if (s.level === p.maxLevel) {
        s.level = p.minLevel;
        s.count = (random() & p.minTime) + 1;
      } else {
        s.level = p.maxLevel;
        s.count = (random() & p.maxTime) + 1;
      }
      return;
    case 'strobe': // T_StrobeFlash
      if (--s.count) return;
      if (s.level === p.minLevel) {
        s.level = p.maxLevel;
        s.count = p.brightTics;
      } else {
        s.level = p.minLevel;
        s.count = p.darkTics;
      }
      return;
    case 'glow': // T_Glow
      if (s.direction === -1) {
        s.level -= p.step;
        if (s.level <= p.minLevel) {
          s.level += p.step;
          s.direction = 1;
        }
      } else {
        s.level += p.step;
        if (s.level >= p.maxLevel) {
          s.level -= p.step;
          s.direction = -1;
        }
      }
      return;
    case 'flicker': {
      // T_FireFlicker
      if (--s.count) return;
      const amount = (random() & 3) * 16;
      s.level = s.level - amount < p.minLevel ? p.minLevel : p.maxLevel - amount;
      s.count = 4;
      return;
    }
  }
}

/** A light pattern played forward tic by tic; `levelAt` restarts it only when asked for an earlier tic. */
export class LightPatternPlayer {
  private draws = 0;
  private tic = 0;
  private state: LightPatternState;
  private readonly random = () => patternRandom(this.seed, this.draws++);

  constructor(private readonly pattern: LightPattern) {
    this.state = startLightPattern(pattern, this.random);
  }

  private get seed(): number {
    return 'seed' in this.pattern ? this.pattern.seed : 0;
  }

  /** The level after `tic` tics (tic 0: the starting level). */
  levelAt(tic: number): number {
    if (tic < this.tic) {
      this.draws = 0;
      this.tic = 0;
      this.state = startLightPattern(this.pattern, this.random);
    }
    for (; this.tic < tic; this.tic++) tickLightPattern(this.pattern, this.state, this.random);
    return this.state.level;
  }
}

/** The pattern's level at `t` seconds: a pure function of the pattern and t (it plays from tic 0). */
export function patternLevelAt(p: EmissionPattern, t: number): number {
  return new LightPatternPlayer(p.pattern).levelAt(wholeSteps(Math.max(0, t), 1 / p.ticsPerSecond));
}

/** The emission of a pattern's material at `level`. */
export function patternEmission(p: EmissionPattern, level: number): Vec3 {
  const f = Math.min(1, Math.max(0, level / p.fullLevel)) ** p.exponent;
  return [p.emission[0] * f, p.emission[1] * f, p.emission[2] * f];
}

/** What is wrong with a scene's material animations, or undefined. */
export function materialAnimationProblem(scene: Scene, a: MaterialAnimations): string | undefined {
  const materials = scene.materials.length;
  const textures = scene.textures?.length ?? 0;
  const material = (i: number, what: string) => (Number.isInteger(i) && i >= 0 && i < materials ? undefined : `${what} refers to material ${i} of ${materials}`);
  for (const [k, c] of (a.cycles ?? []).entries()) {
    const what = `texture cycle ${k}`;
    const bad = material(c.material, what);
    if (bad) return bad;
    if (c.frames.length < 2) return `${what} has ${c.frames.length} frame(s); a cycle needs two or more`;
    if (c.emissionFrames && c.emissionFrames.length !== c.frames.length) return `${what} has ${c.emissionFrames.length} emission frames for ${c.frames.length} frames`;
    for (const t of [...c.frames, ...(c.emissionFrames ?? [])]) if (!(Number.isInteger(t) && t >= 0 && t < textures)) return `${what} refers to texture ${t} of ${textures}`;
    if (!(c.secondsPerFrame > 0 && Number.isFinite(c.secondsPerFrame))) return `${what}: secondsPerFrame must be a positive number, not ${c.secondsPerFrame}`;
  }
  for (const [k, s] of (a.scrolls ?? []).entries()) {
    const bad = material(s.material, `uv scroll ${k}`);
    if (bad) return bad;
    if (!(s.velocity.length === 2 && s.velocity.every(Number.isFinite))) return `uv scroll ${k}: velocity must be two finite numbers`;
    if (s.stepSeconds !== undefined && !(s.stepSeconds >= 0 && Number.isFinite(s.stepSeconds))) return `uv scroll ${k}: stepSeconds must be ≥ 0`;
  }
  for (const [k, p] of (a.patterns ?? []).entries()) {
    const what = `emission pattern ${k}`;
    const bad = material(p.material, what);
    if (bad) return bad;
    if (!(p.ticsPerSecond > 0 && p.fullLevel > 0 && p.exponent >= 0)) return `${what}: ticsPerSecond and fullLevel must be positive and exponent ≥ 0`;
    if (!p.emission.every((c) => Number.isFinite(c) && c >= 0)) return `${what}: emission must be three numbers ≥ 0`;
    const q = p.pattern;
    if (q.kind === 'glow' && !(q.step > 0)) return `${what}: a glow's step must be positive`;
    if (q.kind === 'strobe' && !(Number.isInteger(q.brightTics) && q.brightTics > 0 && Number.isInteger(q.darkTics) && q.darkTics > 0)) return `${what}: a strobe's bright and dark times must be whole tics ≥ 1`;
  }
  return undefined;
}

/** The animator of Scene.dynamics.materialAnimations (registered in world/world.ts ANIMATORS). */
export const materialAnimator: AnimatorFactory = (scene) => {
  const a = scene.dynamics?.materialAnimations;
  if (!a || (a.cycles?.length ?? 0) + (a.scrolls?.length ?? 0) + (a.patterns?.length ?? 0) === 0) return undefined;
  const problem = materialAnimationProblem(scene, a);
  if (problem) throw new LanternError(`scene '${scene.name}': ${problem}`);
  return new MaterialAnimator(a);
};

class MaterialAnimator implements Animator {
  private readonly frames: number[];
  private readonly offsets: string[];
  private readonly levels: number[];
  private readonly players: LightPatternPlayer[];

  constructor(private readonly a: MaterialAnimations) {
    this.frames = (a.cycles ?? []).map(() => -1);
    this.offsets = (a.scrolls ?? []).map(() => '');
    this.levels = (a.patterns ?? []).map(() => NaN);
    this.players = (a.patterns ?? []).map((p) => new LightPatternPlayer(p.pattern));
  }

  step(t: number, _dt: number, _view: unknown, out: UpdateBuilder, first: boolean): void {
    (this.a.cycles ?? []).forEach((c, i) => {
      const f = cycleFrameAt(c, t);
      if (!first && f === this.frames[i]) return;
      this.frames[i] = f;
      const edit: MaterialEdit = { albedoTexture: c.frames[f]!, ...(c.emissionFrames ? { emissionTexture: c.emissionFrames[f]! } : {}) };
      out.material(c.material, edit);
    });
    (this.a.scrolls ?? []).forEach((s, i) => {
      const uv = scrollOffsetAt(s, t);
      const key = uv.join(',');
      if (!first && key === this.offsets[i]) return;
      this.offsets[i] = key;
      out.material(s.material, { uvOffset: uv });
    });
    (this.a.patterns ?? []).forEach((p, i) => {
      const level = this.players[i]!.levelAt(wholeSteps(Math.max(0, t), 1 / p.ticsPerSecond));
      if (!first && level === this.levels[i]) return;
      this.levels[i] = level;
      out.material(p.material, { emission: patternEmission(p, level) });
    });
  }
}
