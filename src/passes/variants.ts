/**
 * The closed variant sets of the passes, mirroring WGSL constants by position: TONEMAP_* in
 * shaders/lib/color.wgsl, LIGHT_SAMPLING_* in shaders/integrator/path.wgsl, SAMPLER_* in shaders/lib/random.wgsl, DEBUG_VIEW_* and
 * DEBUG_LAYOUT_* in shaders/lib/debug-views.wgsl, DENOISE_VIEW_* in shaders/passes/denoise-output.wgsl
 * (a unit test keeps them in step). Here, below the renderer, because the passes map them to those
 * constants; renderer/settings.ts re-exports them as render settings.
 */

export const TONE_MAPPERS = ['linear', 'reinhard', 'aces'] as const;
export type ToneMapper = (typeof TONE_MAPPERS)[number];

/** 'bsdf': BSDF sampling only (emitters found by chance). 'mis': next-event estimation + BSDF sampling, combined by MIS. */
export const LIGHT_SAMPLING = ['bsdf', 'mis'] as const;
export type LightSampling = (typeof LIGHT_SAMPLING)[number];

/**
 * Where the path tracers' random numbers come from (SAMPLER_* in shaders/lib/random.wgsl): 'random',
 * a PCG stream per pixel and sample (white noise); 'sobol', an Owen-scrambled Sobol sequence per
 * pixel, its pixels ranked in a scrambled Morton order so that a frame's error is blue noise.
 */
export const SAMPLERS = ['random', 'sobol'] as const;
export type Sampler = (typeof SAMPLERS)[number];

/**
 * The sampler setting: one of SAMPLERS, or 'auto', which picks per chain (resolveSampler): Sobol for
 * progressive renders, where it gives less error in the same GPU time in every scene class measured
 * (docs/perf.md, "The sampler at equal time": at 64 spp a Cornell-like closed room 1.58× as
 * efficient, rtiow 1.10×, Doom's E1M1 1.11×, the materials scene under the sun 1.07× with the costs
 * measured after issue #27's fixes; at 16 spp PCG wins on E1M1 and materials), and PCG for the real-time chain, whose frames are 1 spp and
 * where the Sobol points' structure shared by neighbouring pixels within a frame (the blue noise) moves
 * the 3×3 box that clamps the temporal history, frame by frame: measured on the H200 (Cornell box
 * 960×540, 4 spp, still) relMSE 0.00044 with Sobol against 0.00022 with PCG (docs/denoise.md, "The sampler").
 */
export const SAMPLER_SETTINGS = ['auto', ...SAMPLERS] as const;
export type SamplerSetting = (typeof SAMPLER_SETTINGS)[number];

/** The sampler a chain uses for a sampler setting: 'auto' is Sobol for progressive renders and PCG ('random') for the real-time chain. */
export function resolveSampler(setting: SamplerSetting, chain: 'progressive' | 'real-time'): Sampler {
  if (setting !== 'auto') return setting;
  return chain === 'progressive' ? 'sobol' : 'random';
}

/**
 * What the debug views show instead of (or beside, or over) the rendered image: BVH work per primary
 * ray (nodes visited, triangles tested), the boxes at one depth, the size and depth of the leaf hit,
 * and surface attributes. 'none' shows the rendered image only. See renderer/recipes/debug.ts.
 */
export const DEBUG_VIEWS = ['none', 'heat-nodes', 'heat-triangles', 'wireframe', 'leaf-size', 'bvh-depth', 'normals', 'albedo', 'barycentrics', 'triangle-id'] as const;
export type DebugView = (typeof DEBUG_VIEWS)[number];

/** How a debug view meets the image: instead of it, in a pane beside it (both at half size), or blended over it. */
export const DEBUG_LAYOUTS = ['replace', 'side-by-side', 'overlay'] as const;
/** Whose boxes the wireframe view draws: the static world's BVH, or the top level over the moving instances (bvh/levels.ts). */
export const WIREFRAME_LEVELS = ['static', 'top'] as const;
export type WireframeLevel = (typeof WIREFRAME_LEVELS)[number];
export type DebugLayout = (typeof DEBUG_LAYOUTS)[number];

/**
 * What the real-time chain (Renderer.renderFrame) shows: its output, or one of the denoiser's debug
 * views. Mirrors DENOISE_VIEW_* in shaders/passes/denoise-output.wgsl by position.
 */
export const DENOISE_VIEWS = ['output', 'history-length', 'variance', 'normal', 'depth', 'albedo', 'motion', 'id'] as const;
export type DenoiseView = (typeof DENOISE_VIEWS)[number];
