/**
 * What a frame is, decided in one place. The renderer, the viewer and the CLI all ask recipeFor: a
 * frame is one of four recipes, and the settings (with whether the front end asks for frames in time)
 * choose it.
 *
 *   debug        a debug view that replaces the image: drawn from the scene, nothing traced
 *   hybrid       settings.recipe 'hybrid': raster first hit, ray-traced light, TAA (recipes/hybrid.ts)
 *   real-time    the real-time path tracing chain: frame paths (megakernel or wavefront, ReSTIR as an
 *                option), temporal accumulation, à-trous (recipes/real-time.ts)
 *   progressive  samples added to the exact running estimate (passes/path-trace-pass.ts)
 *
 * The order is the precedence: a debug view that replaces the image needs no frame, the hybrid
 * recipe is asked for by name, and any switch of the real-time chain (temporal, spatial, ReSTIR,
 * whose reservoirs live only in frames) asks for frames, as does a front end rendering frames in
 * time (the CLI's --frames and --path) with every filter off: raw real-time frames.
 */
import type { RenderSettings } from '../settings.ts';

export const RECIPES = ['progressive', 'real-time', 'hybrid', 'debug'] as const;
export type Recipe = (typeof RECIPES)[number];

/** What the front end asks beyond the settings. */
export interface RecipeIntent {
  /** Frames in time are asked for (the CLI's --frames or --path): the real-time chain even with its filters off. */
  readonly frames?: boolean;
  /** false: nothing is accumulated (a benchmark of rays alone): the progressive path tracer is not compiled for it. */
  readonly accumulate?: boolean;
}

/** The settings that choose the recipe and what it compiles. */
export type RecipeSettings = Pick<RenderSettings, 'recipe' | 'temporal' | 'denoise' | 'restir' | 'integrator' | 'debugView' | 'debugLayout' | 'spectral'>;

/** Whether these settings trace an image: a debug view that replaces it is drawn without one. */
export const tracesImage = (s: Pick<RenderSettings, 'debugView' | 'debugLayout'>): boolean => s.debugView === 'none' || s.debugLayout !== 'replace';

/** The one rule for which recipe a frame runs. */
export function recipeFor(s: RecipeSettings, intent: RecipeIntent = {}): Recipe {
  if (!tracesImage(s)) return 'debug';
  if (s.recipe === 'hybrid') return 'hybrid';
  if (intent.frames || s.temporal || s.denoise || s.restir) return 'real-time';
  return 'progressive';
}

/** Whether a recipe renders frames in time (with a history) rather than a converging estimate. */
export const isFrameRecipe = (recipe: Recipe): boolean => recipe === 'real-time' || recipe === 'hybrid';

/**
 * The kernels a recipe runs beyond those every renderer has (the tone mapper, and the progressive
 * path tracer unless the renderer was made without it): what Renderer.compile compiles before such a
 * frame, and nothing else.
 */
export interface RecipeCompiles {
  /** The progressive path tracer (a renderer made without it compiles it only for a progressive render). */
  readonly progressive: boolean;
  /** The real-time chain's passes (frame path tracer with its G-buffer, temporal, à-trous, output). */
  readonly realTime: boolean;
  /** The wavefront frame path tracer (settings.integrator), within the real-time chain. */
  readonly wavefront: boolean;
  /** The ReSTIR passes (settings.restir), within the real-time chain. */
  readonly restir: boolean;
  /** The hybrid recipe's passes. */
  readonly hybrid: boolean;
  /** The debug views (shown alone or composed with the image). */
  readonly debugViews: boolean;
  /** The spectral variants of the path tracers (the progressive one included: the viewer converges any traced recipe when still). */
  readonly spectral: boolean;
}

/** What the recipe for these settings compiles. */
export function recipeCompiles(s: RecipeSettings, intent: RecipeIntent = {}): RecipeCompiles {
  const recipe = recipeFor(s, intent);
  const realTime = recipe === 'real-time';
  return {
    progressive: recipe === 'progressive' && intent.accumulate !== false,
    realTime,
    wavefront: realTime && s.integrator === 'wavefront',
    restir: realTime && s.restir,
    hybrid: recipe === 'hybrid',
    debugViews: s.debugView !== 'none',
    spectral: s.spectral && recipe !== 'debug',
  };
}

/** What moving from one set of settings to another compiles first, in words (undefined: nothing new). */
export function newlyCompiled(before: RecipeSettings, after: RecipeSettings): string | undefined {
  const was = recipeCompiles(before), now = recipeCompiles(after);
  if (now.hybrid && !was.hybrid) return 'the hybrid recipe';
  if (now.realTime && !was.realTime) return 'the real-time chain';
  if (now.debugViews && !was.debugViews) return 'the debug views';
  if (now.spectral && !was.spectral) return 'spectral rendering';
  return undefined;
}
