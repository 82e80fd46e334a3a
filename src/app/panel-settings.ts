/**
 * Which render settings the panel shows and with what Tweakpane limits, from their schema entries,
 * and the same for the viewer's own settings (viewer-settings.ts); each control's one-line tooltip;
 * and which controls do nothing for the scene and settings shown (the panel disables those, saying
 * why). Pure (no Tweakpane, no DOM), so that unit tests hold the panel's ranges to the schema's
 * (and so to the links') and every control to a tooltip.
 */
import { settingDescription, type SettingEntry } from '../renderer/settings-schema.ts';
import { SETTING_ENTRIES, type RenderSettings } from '../renderer/settings.ts';
import { viewerEntry } from './viewer-settings.ts';

/** The settings the panel shows. */
export const PANEL_SETTINGS: readonly SettingEntry[] = SETTING_ENTRIES.filter((e) => e.spec.panel !== undefined);

/**
 * The viewer's settings the panel binds (panel.ts binds each by hand, as each has its own way to
 * apply), keyed by their panel key (TOOLTIPS, notApplicable) with the viewer setting each binds.
 */
export const VIEWER_PANEL_BINDINGS = {
  samplesPerFrame: 'samplesPerFrame',
  scale: 'scale',
  accumulate: 'accumulate',
  animate: 'animate',
  convergeWhenStill: 'convergeWhenStill',
  fov: 'fovDegrees',
  sunElevation: 'sky.elevation',
  sunAzimuth: 'sky.azimuth',
  turbidity: 'sky.turbidity',
  skyIntensity: 'envIntensity',
} as const;
export type ViewerPanelKey = keyof typeof VIEWER_PANEL_BINDINGS;

/**
 * The Tweakpane parameters of the binding of a viewer setting (by its panel key): the label of its
 * panel hint and, for a number, the limits, step and slider span of numberBindingLimits, so the
 * panel takes what a link takes.
 */
export function viewerBinding(key: ViewerPanelKey): { label: string; min?: number; max?: number; step?: number; slider?: readonly [number, number] } {
  const entry = viewerEntry(VIEWER_PANEL_BINDINGS[key]);
  const hint = entry.spec.panel;
  if (!hint) throw new Error(`viewer setting ${entry.id} has no panel binding`);
  return { label: hint.label, ...numberBindingLimits(entry) };
}

/** A bound setting's key in the panel's own object: for 'integer-or-unlimited', the key of its checkbox. */
export const unlimitedKey = (id: string) => `${id}#unlimited`;

/**
 * The Tweakpane parameters of a numeric setting: the schema's limits constrain what is accepted (typed
 * values too); `slider` is the span the slider covers, narrower where the valid range is too wide to drag.
 */
export function numberBindingLimits(entry: SettingEntry): { min?: number; max?: number; step?: number; slider?: readonly [number, number] } {
  const spec = entry.spec;
  if (spec.type === 'boolean' || spec.type === 'choice' || spec.type === 'color' || spec.type === 'numbers' || spec.type === 'text') return {};
  const hint = spec.panel;
  return {
    // An exclusive lower bound cannot be a Tweakpane limit: such values are refused when applied instead.
    ...(Number.isFinite(spec.min) && !spec.above ? { min: spec.min } : {}),
    // 'auto' is shown as the exclusive lower bound (0 for the heat maximum), so that bound must be enterable.
    ...(spec.type === 'number-or-auto' && spec.above ? { min: spec.min } : {}),
    ...(Number.isFinite(spec.max) ? { max: spec.max } : {}),
    ...(hint?.step !== undefined ? { step: hint.step } : {}),
    ...(hint?.slider ? { slider: hint.slider } : {}),
  };
}

/**
 * One line for each control's tooltip: what it does, in words a new user has (the schema's
 * descriptions are written for the CLI's help and run longer). Keyed by setting id; the panel's own
 * controls (not render settings) by their panel key. A setting added to the schema without an entry
 * here gets its schema description (settingTooltip).
 */
export const TOOLTIPS: Readonly<Record<string, string>> = {
  // The panel's own controls.
  samplesPerFrame: 'Paths traced per pixel each frame: more gives a cleaner frame, at a lower frame rate.',
  scale: 'Render resolution as a fraction of the canvas: below 1 renders fewer pixels, faster, and scales the image up. Moving it fixes the resolution.',
  autoScale: 'The frame budget picks the resolution and samples per frame that keep the page interactive on this GPU (the status line says what and why).',
  accumulate: 'Keep adding frames into one estimate while nothing changes, so the noise fades; off, every frame stands alone.',
  animate: "Run the scene's clock: animated textures, flickering lights, doors and lifts in motion. Off, the image can converge.",
  convergeWhenStill: 'When the view holds still, switch from the denoised real-time frame to the exact progressive estimate once it has 64 samples per pixel.',
  fov: 'Vertical field of view in degrees.',
  mode: 'Walk keeps the eye at head height on the floor and stops at walls (Doom and Wolfenstein maps); fly goes anywhere.',
  // Render settings.
  recipe: 'How a frame is made: path traces every pixel; hybrid rasterises what the camera sees first and ray-traces the light (faster, approximate).',
  integrator: 'How the real-time path tracer runs on the GPU: one thread per path (megakernel) or separate kernels over queues of paths (wavefront); same image.',
  maxBounces: 'Longest path in bounces: 1 is direct light only; more lets light reach corners by bouncing.',
  toneMapper: 'The curve that maps the scene’s light to screen brightness (ACES keeps highlights from clipping).',
  spectral: 'Trace wavelengths instead of RGB: glass splits white light into colours. Slower.',
  sampler: 'Where the random numbers come from: Sobol spreads samples evenly; random is white noise; auto uses Sobol to converge and random in the real-time denoiser.',
  'torch.enabled': 'The light carried at the camera, as in Doom.',
  'torch.color': 'Colour of the torch light (linear RGB).',
  'torch.intensity': 'Strength of the torch in watts per steradian; 0 is off.',
  'torch.range': 'Distance, in scene units, at which the torch light fades out.',
  debugView: 'Show what the renderer sees instead of (or beside) the image: BVH cost heat maps, boxes, normals, albedo…',
  debugLayout: 'The debug view instead of the image (nothing is path traced), beside it, or blended over it.',
  heatMax: 'The count at the top of the heat map colour scale; 0 follows the image’s own maximum.',
  wireframeDepth: 'Which level of the BVH tree to draw boxes for (0: the whole scene’s box).',
  tileCulling: 'Trace only what lies within 10 m of the tile you stand on: faster in big walk maps, but farther lights vanish.',
  accel: 'The structure rays are traced through: a BVH (tree of boxes), a uniform grid, or a wider BVH with 4 or 8 children per node.',
  wireframeLevel: 'Draw the boxes of the static world’s BVH, or of the top level over moving things (doors, lifts, sprites).',
  temporal: 'Reuse earlier frames, moved to where the camera is now (reprojection): much less noise while moving.',
  denoise: 'Blur noise away while keeping edges: an edge-aware à-trous (“with holes”) wavelet filter over the frame.',
  clampK: 'Limits reused history to the mean ± k standard deviations (k·σ) of each pixel’s neighbours: smaller k ghosts less but is noisier; 0 turns it off.',
  historyCap: 'At most this many past frames are blended into a pixel: fewer follow changes faster, more are smoother.',
  denoiseView: 'Show the denoiser’s inner buffers (history length, variance, normals, depth, motion…) instead of its output.',
  'hybrid.giScale': 'Resolution of the indirect light (GI) buffer per axis: 0.5 traces one GI path per four pixels, then upsamples.',
  'hybrid.giBounces': 'Bounces of each indirect light (GI) path.',
  'hybrid.giSamples': 'Indirect light (GI) paths per GI texel per frame.',
  'hybrid.giFilter': 'Run the edge-aware à-trous filter on the indirect light before upsampling it.',
  'hybrid.lightSamples': 'Lights sampled per pixel per frame, each with a shadow ray.',
  'hybrid.reflections': 'Trace reflections from glossy, mirror and glass surfaces.',
  'hybrid.reflectionBounces': 'Bounces a reflection path may take after the reflection.',
  'hybrid.taa': 'Temporal anti-aliasing: smooth jagged edges by blending jittered frames over time.',
};

/** The tooltip of a render setting: its entry in TOOLTIPS, else its schema description (with its mode) as a sentence. */
export function settingTooltip(entry: SettingEntry): string {
  const own = TOOLTIPS[entry.id];
  if (own) return own;
  const d = settingDescription(entry.spec);
  return `${d.charAt(0).toUpperCase()}${d.slice(1)}.`;
}

/** What the panel knows about the scene shown and the settings in force when it decides what applies. */
export interface PanelContext {
  readonly render: RenderSettings;
  /** The scene has a torch of its own, or the settings give it one (an intensity and a range): effectiveTorch with the torch on. */
  readonly hasTorch: boolean;
  /** The scene has a walk map (Doom, Wolfenstein, the dungeon). */
  readonly canWalk: boolean;
  /** Something in the scene moves on its own or on use (doors, lifts, animated textures). */
  readonly moving: boolean;
  /** The scene has a walk map and a metre size, which tile culling needs. */
  readonly tileGrid: boolean;
  /** The page renders with WebGL2's fragment path tracer (backend-choice.ts), which has the progressive recipe only. */
  readonly webgl2?: boolean;
}

/**
 * What the WebGL2 backend does not have, and why: controls of these ids (and every hybrid.* and
 * restir* one) are greyed out on it.
 */
const WEBGPU_ONLY: Readonly<Record<string, string>> = {
  recipe: 'the hybrid recipe rasterises with compute passes',
  integrator: 'the real-time frame needs compute',
  temporal: 'real-time denoising needs compute',
  denoise: 'real-time denoising needs compute',
  clampK: 'real-time denoising needs compute',
  historyCap: 'real-time denoising needs compute',
  denoiseView: 'real-time denoising needs compute',
  convergeWhenStill: 'the real-time frame needs compute',
  spectral: 'the fragment tracer is built for RGB',
  sampler: 'the page carries the tracer built for Sobol sampling',
  accel: 'the fragment tracer is built for the binary BVH',
  tileCulling: 'scene swaps per tile are WebGPU uploads',
  debugView: 'the debug views are compute passes',
  debugLayout: 'the debug views are compute passes',
  heatMax: 'the debug views are compute passes',
  wireframeDepth: 'the debug views are compute passes',
  wireframeLevel: 'the debug views are compute passes',
  restir: 'ReSTIR needs storage buffers',
  restirCandidates: 'ReSTIR needs storage buffers',
};

/** Why a control is WebGPU-only, or undefined where WebGL2 has it. */
export function webGpuOnly(id: string): string | undefined {
  const why = WEBGPU_ONLY[id] ?? (id.startsWith('hybrid.') ? WEBGPU_ONLY.recipe : id.startsWith('restir') ? WEBGPU_ONLY.restir : undefined);
  return why && `WebGPU only: ${why} (this page renders with WebGL2).`;
}

const HEAT_VIEWS: readonly string[] = ['heat-nodes', 'heat-triangles'];

/**
 * Why a control does nothing for this scene and these settings, or undefined where it applies: the
 * panel disables it and shows this as its tooltip. Keyed as TOOLTIPS is. Each reason says what
 * would make the control apply.
 */
export function notApplicable(id: string, c: PanelContext): string | undefined {
  const onWebGl2 = c.webgl2 ? webGpuOnly(id) : undefined;
  if (onWebGl2) return onWebGl2;
  const r = c.render;
  const hybrid = r.recipe === 'hybrid';
  const realTimePath = !hybrid && (r.temporal || r.denoise);
  const onlyPath = 'Not used by the hybrid recipe (it has its own passes: see Hybrid recipe).';
  switch (id) {
    case 'mode':
      return c.canWalk ? undefined : 'This scene has no walk map (Doom and Wolfenstein maps have one): here you can only fly.';
    case 'animate':
      return c.moving ? undefined : 'Nothing in this scene moves or animates.';
    case 'torch.enabled':
      return c.hasTorch ? undefined : 'This scene has no torch of its own: set an intensity above 0 to give it one.';
    case 'tileCulling':
      return c.tileGrid ? undefined : 'Only for walk maps with a known size (the dungeon, Doom and Wolfenstein maps).';
    case 'samplesPerFrame':
    case 'spectral':
      return hybrid ? onlyPath : undefined;
    case 'convergeWhenStill':
      return hybrid || realTimePath ? undefined : 'Only for the real-time frame (temporal or spatial denoising on): progressive rendering always converges.';
    case 'integrator':
      if (hybrid) return onlyPath;
      return realTimePath ? undefined : 'Only for the real-time frame: turn on temporal or spatial denoising.';
    case 'temporal':
    case 'denoise':
      return hybrid ? onlyPath : undefined;
    case 'clampK':
    case 'historyCap':
      if (hybrid) return onlyPath;
      return r.temporal ? undefined : 'Only with temporal denoising on (it limits the reused history).';
    case 'denoiseView':
      if (hybrid) return onlyPath;
      return realTimePath ? undefined : 'Only for the real-time frame: turn on temporal or spatial denoising.';
    case 'debugLayout':
      return r.debugView === 'none' ? 'Choose a debug view first.' : undefined;
    case 'heatMax':
      return HEAT_VIEWS.includes(r.debugView) ? undefined : 'Only for the heat map debug views (nodes, triangles).';
    case 'wireframeDepth':
    case 'wireframeLevel':
      return r.debugView === 'wireframe' ? undefined : 'Only for the wireframe debug view.';
    case 'hybrid.reflectionBounces':
      if (!hybrid) return 'Only with the hybrid recipe (Render → recipe).';
      return r.hybrid.reflections ? undefined : 'Only with reflections on.';
    default:
      if (id.startsWith('hybrid.')) return hybrid ? undefined : 'Only with the hybrid recipe (Render → recipe).';
      return undefined;
  }
}
