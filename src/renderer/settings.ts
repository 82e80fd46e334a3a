/**
 * Render settings: what a user can change without changing the scene. The closed lists mirror WGSL
 * constants by position (passes/variants.ts says which); a unit test keeps the two in step.
 */
import { LanternError } from '../errors.ts';
import type { Vec3 } from '../math/vec3.ts';
import type { Scene, Torch } from '../scene/types.ts';
import { DEBUG_LAYOUTS, DEBUG_VIEWS, DENOISE_VIEWS, LIGHT_SAMPLING, TONE_MAPPERS, type DebugLayout, type DebugView, type DenoiseView, type LightSampling, type ToneMapper } from '../passes/variants.ts';

// The closed lists live beside the passes that turn them into WGSL constants (passes sit below the renderer).
export { DEBUG_LAYOUTS, DEBUG_VIEWS, DENOISE_VIEWS, LIGHT_SAMPLING, TONE_MAPPERS } from '../passes/variants.ts';
export type { DebugLayout, DebugView, DenoiseView, LightSampling, ToneMapper } from '../passes/variants.ts';

/**
 * The torch at the camera: on or off, and any of its parameters overriding the scene's own torch.
 * A scene without a torch gets one only when intensity and range are both given.
 */
export interface TorchSettings {
  readonly enabled: boolean;
  readonly color?: Vec3;
  readonly intensity?: number;
  readonly range?: number;
  readonly radius?: number;
}

/** The deepest wireframe depth accepted (the builder caps BVH depth at 60). */
export const MAX_WIREFRAME_DEPTH = 64;

/** Frames of temporal history: a cap, or no cap (a still camera then converges like progressive rendering). */
export type HistoryCap = number | 'unlimited';
export const MAX_HISTORY_CAP = 65536;

export interface RenderSettings {
  /** Scattering events per path: 0 shows emitters only, 1 direct light, ... */
  readonly maxBounces: number;
  readonly lightSampling: LightSampling;
  readonly toneMapper: ToneMapper;
  /** Exposure in photographic stops: radiance is scaled by 2^stops before the tone curve. */
  readonly exposureStops: number;
  /** Seed of every random stream: the same seed, scene and settings give the same image. */
  readonly seed: number;
  readonly torch: TorchSettings;
  readonly debugView: DebugView;
  readonly debugLayout: DebugLayout;
  /** Wireframe view: the depth whose boxes are drawn (0 = the root, the scene bounds). */
  readonly wireframeDepth: number;
  /** Heat views: the count at the top of the colour scale, or 'auto' for the image's own maximum. */
  readonly heatMax: number | 'auto';
  /** Real-time frames: accumulate each pixel's history over frames, reprojected as the camera moves. */
  readonly temporal: boolean;
  /** Real-time frames: the edge-aware spatial (à-trous) filter. */
  readonly denoise: boolean;
  /** Temporal history clamp: mean ± clampK·σ of the current 3×3 neighbourhood (0: no clamp). */
  readonly clampK: number;
  /** Largest history length N (blend weight 1/N); 'unlimited' also lifts the clamp while the camera is still. */
  readonly historyCap: HistoryCap;
  readonly denoiseView: DenoiseView;
}

export const DEFAULT_SETTINGS: RenderSettings = Object.freeze({
  maxBounces: 8,
  lightSampling: 'mis',
  toneMapper: 'aces',
  exposureStops: 0,
  seed: 1,
  torch: Object.freeze({ enabled: true }),
  debugView: 'none',
  debugLayout: 'replace',
  wireframeDepth: 0,
  heatMax: 'auto',
  temporal: true,
  denoise: true,
  clampK: 1.25,
  historyCap: 32,
  denoiseView: 'output',
});

/** Settings that change the estimate itself: changing one restarts accumulation. */
export const ESTIMATE_SETTINGS: readonly (keyof RenderSettings)[] = ['maxBounces', 'lightSampling', 'seed', 'torch'];

/** The torch that lights the scene under these settings, or undefined when there is none. */
export function effectiveTorch(scene: Pick<Scene, 'torch'> | undefined, t: TorchSettings): Torch | undefined {
  if (!t.enabled) return undefined;
  const base = scene?.torch;
  const intensity = t.intensity ?? base?.intensity;
  const range = t.range ?? base?.range;
  if (intensity === undefined || range === undefined) return undefined;
  return { color: t.color ?? base?.color ?? [1, 1, 1], intensity, range, radius: t.radius ?? base?.radius ?? range / 256 };
}

export const MAX_BOUNCES_LIMIT = 1024;

export function validateSettings(s: RenderSettings): RenderSettings {
  if (!Number.isInteger(s.maxBounces) || s.maxBounces < 0 || s.maxBounces > MAX_BOUNCES_LIMIT) {
    throw new LanternError(`bounces must be a whole number from 0 to ${MAX_BOUNCES_LIMIT}, not ${s.maxBounces}`);
  }
  if (!LIGHT_SAMPLING.includes(s.lightSampling)) {
    throw new LanternError(`unknown light sampling '${s.lightSampling}'`, `Use one of: ${LIGHT_SAMPLING.join(', ')}`);
  }
  if (!TONE_MAPPERS.includes(s.toneMapper)) {
    throw new LanternError(`unknown tone mapper '${s.toneMapper}'`, `Use one of: ${TONE_MAPPERS.join(', ')}`);
  }
  if (!Number.isFinite(s.exposureStops) || Math.abs(s.exposureStops) > 64) {
    throw new LanternError(`exposure must be a number of stops between -64 and 64, not ${s.exposureStops}`);
  }
  if (!Number.isInteger(s.seed) || s.seed < 0 || s.seed > 0xffffffff) {
    throw new LanternError(`seed must be a whole number from 0 to 4294967295, not ${s.seed}`);
  }
  const t = s.torch;
  if (t.color && (t.color.length !== 3 || !t.color.every((c) => Number.isFinite(c) && c >= 0))) {
    throw new LanternError(`torch colour must be three non-negative numbers, not ${t.color.join(', ')}`);
  }
  if (t.intensity !== undefined && !(Number.isFinite(t.intensity) && t.intensity >= 0)) throw new LanternError(`torch intensity must be a non-negative number, not ${t.intensity}`);
  if (t.range !== undefined && !(Number.isFinite(t.range) && t.range > 0)) throw new LanternError(`torch range must be a positive number, not ${t.range}`);
  if (t.radius !== undefined && !(Number.isFinite(t.radius) && t.radius > 0)) throw new LanternError(`torch radius must be a positive number, not ${t.radius}`);
  if (!DEBUG_VIEWS.includes(s.debugView)) throw new LanternError(`unknown debug view '${s.debugView}'`, `Use one of: ${DEBUG_VIEWS.join(', ')}`);
  if (!DEBUG_LAYOUTS.includes(s.debugLayout)) throw new LanternError(`unknown debug layout '${s.debugLayout}'`, `Use one of: ${DEBUG_LAYOUTS.join(', ')}`);
  if (!Number.isInteger(s.wireframeDepth) || s.wireframeDepth < 0 || s.wireframeDepth > MAX_WIREFRAME_DEPTH) {
    throw new LanternError(`wireframe depth must be a whole number from 0 to ${MAX_WIREFRAME_DEPTH}, not ${s.wireframeDepth}`);
  }
  if (s.heatMax !== 'auto' && !(Number.isFinite(s.heatMax) && s.heatMax > 0)) throw new LanternError(`heat map maximum must be a positive number or 'auto', not ${s.heatMax}`);
  validateDenoiseSettings(s);
  return s;
}

function validateDenoiseSettings(s: RenderSettings): void {
  if (typeof s.temporal !== 'boolean') throw new LanternError(`temporal must be true or false, not ${String(s.temporal)}`);
  if (typeof s.denoise !== 'boolean') throw new LanternError(`denoise must be true or false, not ${String(s.denoise)}`);
  if (!Number.isFinite(s.clampK) || s.clampK < 0 || s.clampK > 16) throw new LanternError(`clamp k must be a number from 0 (no clamp) to 16, not ${s.clampK}`);
  const cap = s.historyCap;
  if (cap !== 'unlimited' && !(Number.isInteger(cap) && cap >= 1 && cap <= MAX_HISTORY_CAP)) {
    throw new LanternError(`history cap must be a whole number of frames from 1 to ${MAX_HISTORY_CAP}, or 'unlimited', not ${String(cap)}`);
  }
  if (!DENOISE_VIEWS.includes(s.denoiseView)) {
    throw new LanternError(`unknown denoise view '${s.denoiseView}'`, `Use one of: ${DENOISE_VIEWS.join(', ')}`);
  }
}
