/**
 * Render settings: what a user can change without changing the scene, declared once in the table
 * RENDER_SETTINGS below (one entry per setting: type, default, valid range, description, the mode
 * it applies to, CLI flag, link parameter, whether it restarts accumulation, panel hint). The closed lists mirror WGSL
 * constants by position (passes/variants.ts says which); a unit test keeps the two in step.
 */
import type { Scene, Torch } from '../scene/types.ts';
import { ACCELS } from '../bvh/grid.ts';
import {
  boolean, choice, color, defaultsOf, flattenSchema, integer, integerOrUnlimited, number, numberOrAuto, optional, validateAgainst,
  type SettingEntry, type SettingGroup, type SettingsOf, type SettingsPatch,
} from './settings-schema.ts';

// The closed lists live beside the passes that turn them into WGSL constants (passes sit below the renderer).
import { DEBUG_LAYOUTS, DEBUG_VIEWS, DENOISE_VIEWS, LIGHT_SAMPLING, SAMPLER_SETTINGS, TONE_MAPPERS, WIREFRAME_LEVELS } from '../passes/variants.ts';
export { DEBUG_LAYOUTS, DEBUG_VIEWS, DENOISE_VIEWS, LIGHT_SAMPLING, SAMPLERS, SAMPLER_SETTINGS, TONE_MAPPERS, resolveSampler } from '../passes/variants.ts';
export type { DebugLayout, DebugView, DenoiseView, LightSampling, Sampler, ToneMapper } from '../passes/variants.ts';

/** The deepest wireframe depth accepted (the builder caps BVH depth at 60). */
export const MAX_WIREFRAME_DEPTH = 64;

/** The frame recipes (settings.recipe): the path tracer, or the hybrid raster + ray-traced recipe (renderer/recipes/hybrid.ts). */
export const RENDER_MODES = ['path', 'hybrid'] as const;
export type RenderMode = (typeof RENDER_MODES)[number];

/** The real-time frame's path tracers (settings.integrator): one thread per path, or kernels over queues of paths (passes/wavefront-frame-pass.ts). */
export const INTEGRATORS = ['megakernel', 'wavefront'] as const;
export type Integrator = (typeof INTEGRATORS)[number];

/** Frames of temporal history: a cap, or no cap (a still camera then converges like progressive rendering). */
export type HistoryCap = number | 'unlimited';
export const MAX_HISTORY_CAP = 65536;

/** The deepest bounce limit accepted (the panel's slider covers 0–32; longer paths are typed in). */
export const MAX_BOUNCES_LIMIT = 1024;

/**
 * Every render setting, declared once: the type, defaults, validation, CLI options of `render` and
 * `bench`, link parameters and panel bindings are all derived from this table (settings-schema.ts
 * says how). To add a setting, add an entry here; the front ends pick it up.
 */
export const RENDER_SETTINGS = {
  // The link says `recipe`: `mode` was already the walk/fly mode of the page's links.
  recipe: choice(RENDER_MODES, {
    name: 'recipe', description: "the frame recipe: 'path' traces every pixel's path (progressive, or the real-time denoiser's chain); 'hybrid' rasterises the first hit and ray-traces direct light with shadows, diffuse GI at --gi-scale and reflections, then TAA (docs/hybrid.md)", default: 'path',
    cli: { flag: '--mode', argument: '<path|hybrid>' }, link: 'recipe', restarts: true, panel: { folder: 'render', label: 'recipe' },
  }),
  integrator: choice(INTEGRATORS, {
    name: 'integrator', description: "the path tracer of the real-time frame: one thread follows each path (megakernel), or extend, shade and shadow kernels over compacted queues of paths (wavefront; same image up to rounding)", mode: 'frame', default: 'megakernel',
    cli: { flag: '--integrator', argument: '<megakernel|wavefront>' }, link: 'integrator', restarts: true, panel: { folder: 'render', label: 'integrator' },
  }),
  maxBounces: integer({
    name: 'bounces', description: 'maximum bounces per path (0: emitters only, 1: direct light, ...)', min: 0, max: MAX_BOUNCES_LIMIT, default: 8,
    cli: { flag: '--bounces', short: '-b', argument: '<n>' }, link: 'bounces', restarts: true,
    panel: { folder: 'render', label: 'max bounces', step: 1, slider: [0, 32] },
  }),
  lightSampling: choice(LIGHT_SAMPLING, {
    name: 'light sampling', description: 'BSDF sampling only (bsdf), or next-event estimation combined by MIS (mis)', default: 'mis',
    cli: { flag: '--light-sampling', argument: '<strategy>' }, restarts: true,
  }),
  toneMapper: choice(TONE_MAPPERS, {
    name: 'tone mapper', description: 'tone curve (PNG only)', default: 'aces',
    cli: { flag: '--tonemap', argument: '<curve>' }, link: 'tonemap', restarts: false, panel: { folder: 'exposure', label: 'tone curve' },
  }),
  /**
   * Absent: the scene's kind decides (Scene.autoExposure: automatic for the game maps, the scene's own
   * camera exposure for reference scenes); a number: manual, in stops over the scene's exposure; 'auto':
   * eye adaptation (renderer/exposure.ts). The panel draws its own exposure block (panel.ts).
   */
  exposureStops: optional(numberOrAuto({
    name: 'exposure', description: "exposure in stops over the scene's own: radiance is scaled by 2^stops before the tone curve; 'auto' adapts it to the image's log-average luminance like an eye (default: auto for Doom and Wolfenstein maps, the scene's exposure otherwise; PNG only, EXR stays radiance)", min: -64, max: 64, default: 0,
    cli: { flag: '--exposure', argument: '<stops|auto>' }, link: 'exposure', restarts: false,
  })),
  exposureCompensation: number({
    name: 'exposure compensation', description: 'automatic exposure: stops added to the exposure that brings the log-average luminance to middle grey (0.18)', min: -16, max: 16, default: 0,
    cli: { flag: '--exposure-compensation', argument: '<stops>' }, link: 'exposure-compensation', restarts: false,
    panel: { folder: 'exposure', label: 'compensation (stops)', step: 0.1, slider: [-4, 4] },
  }),
  exposureAdaptation: number({
    name: 'exposure adaptation time', description: 'automatic exposure: seconds for the exposure to close 63 % of the way to the image\'s (the time constant of the exponential adaptation; viewer: wall-clock time, CLI: --frames time)', min: 0, above: true, max: 3600, default: 1,
    cli: { flag: '--exposure-adaptation', argument: '<seconds>' }, link: 'exposure-adaptation', restarts: false,
    panel: { folder: 'exposure', label: 'adaptation (s)', step: 0.05, slider: [0.05, 5] },
  }),
  spectral: boolean({
    name: 'spectral', description: 'spectral rendering: four wavelengths per path (hero wavelength), RGB lifted to spectra, glass disperses (docs/spectral.md)', words: ['0', '1'], default: false,
    cli: { flag: '--spectral', switch: true }, link: 'spectral', restarts: true, panel: { folder: 'render', label: 'spectral' },
  }),
  sampler: choice(SAMPLER_SETTINGS, {
    name: 'sampler', description: "where the path tracers' random numbers come from: 'sobol', an Owen-scrambled Sobol sequence per pixel (its samples stratified, also across real-time frames) with neighbouring pixels given stratified points, so that a frame's error is blue noise; 'random', independent PCG numbers (white noise); 'auto', Sobol for progressive renders and PCG for the real-time chain (docs/denoise.md)", default: 'auto',
    cli: { flag: '--sampler', argument: '<auto|sobol|random>' }, link: 'sampler', restarts: true, panel: { folder: 'render', label: 'sampler' },
  }),
  seed: integer({
    name: 'seed', description: 'seed of every random stream (same seed, scene and settings: same image)', min: 0, max: 0xffffffff, default: 1,
    cli: { flag: '--seed', argument: '<n>' }, restarts: true,
  }),
  /** The torch at the camera: on or off, and any of its parameters overriding the scene's own torch (see effectiveTorch). */
  torch: {
    enabled: boolean({
      name: 'torch', description: 'the light carried at the camera (on where the scene has one, as Doom maps do)', words: ['off', 'on'], default: true,
      cli: { flag: '--torch', argument: '<on|off>' }, link: 'torch', restarts: true, panel: { folder: 'camera', label: 'torch' },
    }),
    color: optional(color({
      name: 'torch colour', description: 'torch colour, linear RGB (it tints; --torch-intensity sets the strength)', min: 0, max: 1, default: [1, 1, 1],
      cli: { flag: '--torch-color', argument: '<r,g,b>' }, link: 'torch-color', restarts: true, panel: { folder: 'camera', label: 'torch colour' },
    })),
    intensity: optional(number({
      name: 'torch intensity', description: 'torch intensity in W/sr (with --torch-range, gives any scene a torch)', min: 0, max: Infinity, default: 0,
      cli: { flag: '--torch-intensity', argument: '<W/sr>' }, link: 'torch-intensity', restarts: true, panel: { folder: 'camera', label: 'intensity (W/sr)' },
    })),
    range: optional(number({
      name: 'torch range', description: 'distance at which the torch fades out', min: 0, above: true, max: Infinity, default: 1,
      cli: { flag: '--torch-range', argument: '<distance>' }, link: 'torch-range', restarts: true, panel: { folder: 'camera', label: 'range' },
    })),
    radius: optional(number({ name: 'torch radius', description: 'radius of the torch (soft shadows)', min: 0, above: true, max: Infinity, default: 1, restarts: true })),
  },
  debugView: choice(DEBUG_VIEWS, {
    name: 'debug view', description: 'show a debug view (from pixel-centre primary rays; the EXR then holds its raw values)', default: 'none',
    // The CLI names a view to show; without --debug there is none.
    cli: { flag: '--debug', argument: '<view>', values: DEBUG_VIEWS.filter((v) => v !== 'none') }, link: 'debug', restarts: false,
    panel: { folder: 'debug', label: 'view' },
  }),
  debugLayout: choice(DEBUG_LAYOUTS, {
    name: 'debug layout', description: 'the debug view instead of the image (no path tracing), beside it, or over it', default: 'replace',
    cli: { flag: '--debug-layout', argument: '<layout>' }, link: 'layout', restarts: false, panel: { folder: 'debug', label: 'layout' },
  }),
  heatMax: numberOrAuto({
    name: 'heat map maximum', description: "heat views: the count at the top of the colour scale ('auto': the image's maximum)", min: 0, above: true, max: Infinity, default: 'auto',
    cli: { flag: '--heat-max', argument: '<n|auto>' }, link: 'heat-max', restarts: false, panel: { folder: 'debug', label: 'scale max (0: auto)', step: 1 },
  }),
  /** The panel's slider reaches the scene's own BVH depth (panel.ts). */
  wireframeDepth: integer({
    name: 'wireframe depth', description: 'wireframe view: the BVH depth whose boxes are drawn (0 = the scene bounds)', min: 0, max: MAX_WIREFRAME_DEPTH, default: 0,
    cli: { flag: '--wireframe-depth', argument: '<d>' }, link: 'depth', restarts: false, panel: { folder: 'debug', label: 'box depth', step: 1 },
  }),
  tileCulling: boolean({
    name: 'tile culling', description: 'walk-map scenes (the dungeon): trace only what lies within 10 m of the tile the camera stands on, one BVH per tile precomputed and swapped as the camera steps (an approximation: farther lights and walls vanish)', words: ['0', '1'], default: false,
    cli: { flag: '--tile-culling', switch: true }, link: 'tile-cull', restarts: true, panel: { folder: 'render', label: 'tile culling' },
  }),
  accel: choice(ACCELS, {
    name: 'accel', description: "how the static world is traced: its BVH, a uniform grid (3D-DDA; a tile map's own 64 × 64 tiles where the scene has them), or a wide BVH collapsed from its BVH (bvh4: 4 fp32 child boxes a node; cwbvh: 8 children a node in 80 bytes, 8-bit boxes)", default: 'bvh',
    cli: { flag: '--accel', argument: '<structure>' }, link: 'accel', restarts: true, panel: { folder: 'render', label: 'acceleration' },
  }),
  wireframeLevel: choice(WIREFRAME_LEVELS, {
    name: 'wireframe level', description: "wireframe view: the static world's BVH boxes, or the top level's (over the moving instances: doors, lifts, sprites)", default: 'static',
    cli: { flag: '--wireframe-level', argument: '<level>' }, link: 'wf-level', restarts: false, panel: { folder: 'debug', label: 'boxes of' },
  }),
  temporal: boolean({
    name: 'temporal', description: 'accumulate over frames with reprojection (temporal denoising)', mode: 'frame', words: ['0', '1'], default: true,
    cli: { flag: '--temporal', switch: true }, link: 'temporal', restarts: false, panel: { folder: 'denoise', label: 'temporal' },
  }),
  denoise: boolean({
    name: 'denoise', description: 'the edge-aware spatial (à-trous) filter', mode: 'frame', words: ['0', '1'], default: true,
    cli: { flag: '--denoise', switch: true }, link: 'denoise', restarts: false, panel: { folder: 'denoise', label: 'spatial (à-trous)' },
  }),
  clampK: number({
    name: 'clamp k', description: 'history clamp to mean ± k·σ of the 3×3 neighbourhood (0: off)', mode: 'frame', min: 0, max: 16, default: 1.25,
    cli: { flag: '--clamp-k', argument: '<k>' }, link: 'clamp-k', restarts: false, panel: { folder: 'denoise', label: 'clamp k·σ (0: off)', step: 0.05, slider: [0, 4] },
  }),
  historyCap: integerOrUnlimited({
    name: 'history cap', description: "longest temporal history in frames ('unlimited' also lifts the clamp while the camera is still)", mode: 'frame', min: 1, max: MAX_HISTORY_CAP, default: 32,
    cli: { flag: '--history-cap', argument: '<n|unlimited>' }, link: 'history-cap', restarts: false,
    panel: { folder: 'denoise', label: 'history cap', step: 1, slider: [1, 256], unlimitedLabel: 'unlimited' },
  }),
  restir: boolean({
    name: 'restir', description: 'direct light at the first bounce by ReSTIR DI (reservoirs of light samples reused over frames and neighbours, unbiased; docs/denoise.md); off: one light sample per bounce', mode: 'frame', words: ['0', '1'], default: false,
    cli: { flag: '--restir', switch: true }, link: 'restir', restarts: false, panel: { folder: 'denoise', label: 'ReSTIR direct light' },
  }),
  restirCandidates: integer({
    name: 'ReSTIR candidates', description: 'light samples per pixel per frame that ReSTIR resamples (before temporal and spatial reuse)', mode: 'frame', min: 1, max: 64, default: 16,
    cli: { flag: '--restir-candidates', argument: '<n>' }, link: 'restir-candidates', restarts: false, panel: { folder: 'denoise', label: 'ReSTIR candidates', step: 1, slider: [1, 32] },
  }),
  denoiseView: choice(DENOISE_VIEWS, {
    name: 'denoise view', description: 'what the real-time chain shows', mode: 'frame', default: 'output',
    cli: { flag: '--denoise-view', argument: '<view>' }, link: 'denoise-view', restarts: false, panel: { folder: 'denoise', label: 'show' },
  }),
  hybrid: {
    giScale: number({
      name: 'GI buffer scale', description: 'GI texels per pixel along each axis (0.5: one GI path per four pixels), upsampled by a joint bilateral filter', mode: 'hybrid', min: 0.25, max: 1, default: 0.5,
      cli: { flag: '--gi-scale', argument: '<0.25..1>' }, link: 'gi-scale', restarts: true, panel: { folder: 'hybrid', label: 'GI buffer scale', step: 0.25 },
    }),
    giBounces: integer({
      name: 'GI bounces', description: 'bounces of each GI path (1: the light its first hit receives)', mode: 'hybrid', min: 0, max: 16, default: 2,
      cli: { flag: '--gi-bounces', argument: '<n>' }, link: 'gi-bounces', restarts: true, panel: { folder: 'hybrid', label: 'GI bounces', step: 1 },
    }),
    giSamples: integer({
      name: 'GI samples', description: 'GI paths per GI texel per frame', mode: 'hybrid', min: 1, max: 64, default: 1,
      cli: { flag: '--gi-samples', argument: '<n>' }, link: 'gi-samples', restarts: true, panel: { folder: 'hybrid', label: 'GI samples', step: 1, slider: [1, 8] },
    }),
    giFilter: boolean({
      name: 'GI filter', description: 'the à-trous filter on the GI target before upsampling', mode: 'hybrid', words: ['0', '1'], default: true,
      cli: { flag: '--gi-filter', argument: '<0|1>' }, link: 'gi-filter', restarts: false, panel: { folder: 'hybrid', label: 'GI à-trous filter' },
    }),
    lightSamples: integer({
      name: 'light samples', description: 'light samples (each with a shadow ray) per pixel per frame', mode: 'hybrid', min: 1, max: 64, default: 1,
      cli: { flag: '--light-samples', argument: '<n>' }, link: 'light-samples', restarts: true, panel: { folder: 'hybrid', label: 'light samples', step: 1, slider: [1, 8] },
    }),
    reflections: boolean({
      name: 'reflections', description: 'trace reflection rays from glossy, mirror and glass surfaces, weighted by their Fresnel reflectance', mode: 'hybrid', words: ['0', '1'], default: true,
      cli: { flag: '--reflections', argument: '<0|1>' }, link: 'reflections', restarts: true, panel: { folder: 'hybrid', label: 'reflections' },
    }),
    reflectionBounces: integer({
      name: 'reflection bounces', description: 'bounces a reflection path may take after the reflection', mode: 'hybrid', min: 0, max: 16, default: 2,
      cli: { flag: '--reflection-bounces', argument: '<n>' }, link: 'reflection-bounces', restarts: true, panel: { folder: 'hybrid', label: 'reflection bounces', step: 1 },
    }),
    taa: boolean({
      name: 'TAA', description: 'temporal anti-aliasing (history reprojected and clamped to the 3×3 neighbourhood)', mode: 'hybrid', words: ['0', '1'], default: true,
      cli: { flag: '--taa', argument: '<0|1>' }, link: 'taa', restarts: false, panel: { folder: 'hybrid', label: 'TAA' },
    }),
  },
} as const satisfies SettingGroup;

export type RenderSettings = SettingsOf<typeof RENDER_SETTINGS>;
export type TorchSettings = RenderSettings['torch'];
export type RenderSettingsPatch = SettingsPatch<RenderSettings>;

/** Every setting with its path, in declaration order. */
export const SETTING_ENTRIES: readonly SettingEntry[] = flattenSchema(RENDER_SETTINGS);

export const DEFAULT_SETTINGS: RenderSettings = defaultsOf(RENDER_SETTINGS);

/** Settings that change the estimate itself: changing one restarts accumulation. */
export const ESTIMATE_SETTINGS: readonly (keyof RenderSettings)[] = [...new Set(SETTING_ENTRIES.filter((e) => e.spec.restarts).map((e) => e.path[0] as keyof RenderSettings))];

/** The torch that lights the scene under these settings, or undefined when there is none. */
export function effectiveTorch(scene: Pick<Scene, 'torch'> | undefined, t: TorchSettings): Torch | undefined {
  if (!t.enabled) return undefined;
  const base = scene?.torch;
  const intensity = t.intensity ?? base?.intensity;
  const range = t.range ?? base?.range;
  if (intensity === undefined || range === undefined) return undefined;
  return { color: t.color ?? base?.color ?? [1, 1, 1], intensity, range, radius: t.radius ?? base?.radius ?? range / 256 };
}

/** Refuses settings outside the schema's ranges with a LanternError that names the setting. */
export function validateSettings(s: RenderSettings): RenderSettings {
  validateAgainst(SETTING_ENTRIES, s);
  return s;
}
