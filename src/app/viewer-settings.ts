/**
 * The viewer's own settings, declared once: what the page sets besides the render settings
 * (renderer/settings.ts) — samples per frame, resolution scale, accumulation, the scene's clock,
 * converging when still, the camera's field of view and the sky that replaces a scene's environment.
 * Each has one type, default and valid range, its link parameter and its panel binding, in the table
 * VIEWER_SETTINGS below, written with the schema's constructors (renderer/settings-schema.ts). Links
 * (view-params.ts), the panel (panel.ts, through panel-settings.ts), DEFAULT_VIEWER_SETTINGS
 * (viewer-types.ts) and the Environment folder's defaults (environment-choice.ts) read them from here, so
 * that a link and the panel accept the same values. Pure: no DOM.
 *
 * A panel hint's `slider` is the span its slider covers where that is narrower than the valid range;
 * a typed value still goes to the limit (as for the render settings' bounces).
 */
import { boolean, defaultsOf, flattenSchema, integer, number, numbers, optional, type Component, type Setting, type SettingEntry, type SettingGroup, type SettingSpec, type SettingsOf } from '../renderer/settings-schema.ts';
import { SCALE_STEPS } from './frame-budget.ts';

/** The bounds of a number setting, as a component of a setting of several numbers (the link's sky). */
function component(name: string, setting: Setting<number>): Component {
  const spec = setting.spec;
  if (spec.type !== 'number' && spec.type !== 'integer') throw new Error(`${spec.name} is not a number setting`);
  return { name, min: spec.min, max: spec.max, ...(spec.above ? { above: true } : {}) };
}

// The sun and sky (the Hosek–Wilkie model, scene/sky.ts): apart, so that the link's sky parameter can take their bounds.
const sunElevation = number({
  // The sky is defined for a sun from −90° to 90° (scene/environment.ts; gpu/pack checks it, and the
  // CLI's --sky accepts as much). Its model is fitted for 0–90°: below the horizon every elevation gives
  // the same sky (a sun at the horizon, hidden), so the slider spans −10–90° where the sky changes.
  name: 'sun elevation', description: 'the sun, degrees above the horizon', min: -90, max: 90, default: 35, restarts: true,
  panel: { folder: 'environment', label: 'sun elevation (°)', step: 0.5, slider: [-10, 90] },
});
const sunAzimuth = number({
  // An angle about +y: any value is one of −180–180°. Links have accepted two turns either way; the slider spans one.
  name: 'sun azimuth', description: 'the sun, degrees about +y from +z toward +x', min: -360, max: 360, default: 45, restarts: true,
  panel: { folder: 'environment', label: 'sun azimuth (°)', step: 1, slider: [-180, 180] },
});
const turbidity = number({
  // The Hosek–Wilkie dataset holds turbidities 1 to 10 (scene/sky-data.ts); 3 is the CLI's --sky default too.
  name: 'turbidity', description: 'the haze of the sky: 1 very clear, 10 hazy', min: 1, max: 10, default: 3, restarts: true,
  panel: { folder: 'environment', label: 'turbidity', step: 0.1 },
});

/**
 * The viewer's settings. The five at the top are ViewerSettings (viewer-types.ts); the field of view is the
 * camera's (a scene's own camera gives it: no default); the sky and its intensity are the environment
 * that replaces every scene's own (a link's `sky=elevation,azimuth[,turbidity]`, SKY_LINK below,
 * carries the sky's three together), its defaults what the panel's sky shows when first picked.
 */
export const VIEWER_SETTINGS = {
  samplesPerFrame: integer({
    // The renderer takes any positive whole number, and the frame budget adds up to 4 on a fast GPU
    // (frame-budget.ts MAX_BUDGET_SAMPLES). 64 is as far as a frame needs to go: converge when still
    // hands over to the progressive estimate at 64 samples per pixel (viewer-types.ts CONVERGE_HANDOFF_SAMPLES),
    // and every frame is split into short submissions, so the page answers during one. Links accepted
    // 1–64 and the panel 1–16: the panel now takes typed values up to 64, its slider spanning 1–16.
    name: 'samples per frame', description: 'paths traced per pixel each frame', min: 1, max: 64, default: 1, link: 'spf', restarts: true,
    panel: { folder: 'render', label: 'samples/frame', step: 1, slider: [1, 16] },
  }),
  scale: number({
    // Render resolution relative to the canvas's device pixels: the renderer takes any size of a pixel or
    // more (viewer.ts resizeRenderer); 2 supersamples (four times the pixels). The slider reaches down to
    // the frame budget's smallest step (1/32), a typed value or a link to 0.01, as links always have.
    name: 'resolution scale', description: "render resolution relative to the canvas's device pixels", min: 0.01, max: 2, default: 1, link: 'scale', restarts: true,
    panel: { folder: 'render', label: 'resolution', step: 0.01, slider: [SCALE_STEPS[SCALE_STEPS.length - 1]!, 2] },
  }),
  accumulate: boolean({
    name: 'accumulate', description: 'keep adding frames into one estimate while the view is still (off: every frame stands alone)', words: ['0', '1'], default: true, link: 'acc', restarts: true,
    panel: { folder: 'render', label: 'accumulate' },
  }),
  animate: boolean({
    name: 'animate', description: "play the scene's clock (animated textures, flickering lights, doors in motion)", words: ['0', '1'], default: true, link: 'anim', restarts: false,
    panel: { folder: 'render', label: 'animate scene' },
  }),
  convergeWhenStill: boolean({
    name: 'converge when still', description: 'while the view holds still, hand over from the real-time frame to the exact progressive estimate', words: ['0', '1'], default: true, link: 'converge', restarts: false,
    panel: { folder: 'denoise', label: 'converge when still' },
  }),
  fovDegrees: optional(number({
    // The camera takes any vertical field of view in (0°, 180°) (scene/validate.ts; the ray through a
    // pixel scales by tan(fov/2), gpu/view.ts). 1–179° is what the CLI's --fov accepts: a link carries
    // any view the CLI renders. Links stopped at 150° and the panel at 120°: both now take 1–179°.
    // `optional` drops the default: the scene's camera gives the field of view (60 is only what the builder needs).
    name: 'field of view', description: 'vertical field of view in degrees', min: 1, max: 179, default: 60, link: 'fov', restarts: true,
    panel: { folder: 'camera', label: 'field of view', step: 1 },
  })),
  sky: { elevation: sunElevation, azimuth: sunAzimuth, turbidity },
  envIntensity: number({
    // Any non-negative factor works (gpu/pack); 10⁶ is ample (the sky is daylight in physical units, so
    // scenes scale it down, not up). The slider spans 0–4.
    name: 'environment intensity', description: "multiplies the sky's radiance", min: 0, max: 1e6, default: 1, link: 'env-intensity', restarts: true,
    panel: { folder: 'environment', label: 'sky intensity', step: 0.01, slider: [0, 4] },
  }),
} as const satisfies SettingGroup;

export type ViewerSettingValues = SettingsOf<typeof VIEWER_SETTINGS>;

/** Every viewer setting with its path ('sky.elevation'), in declaration order. */
export const VIEWER_ENTRIES: readonly SettingEntry[] = flattenSchema(VIEWER_SETTINGS);

/** The defaults (the field of view has none: the scene's camera gives it). */
export const VIEWER_DEFAULTS: ViewerSettingValues = defaultsOf(VIEWER_SETTINGS);

/** The link's `sky=elevation,azimuth[,turbidity]`: the sky's three settings as one parameter, each with its own bounds (a left-off turbidity is its default). */
export const SKY_LINK: SettingSpec = numbers({
  name: 'sky', description: 'the Hosek–Wilkie sky and its sun: elevation and azimuth in degrees, turbidity', link: 'sky', restarts: true,
  components: [component('elevation', sunElevation), component('azimuth', sunAzimuth), component('turbidity', turbidity)],
  required: 2,
  default: [VIEWER_DEFAULTS.sky.elevation, VIEWER_DEFAULTS.sky.azimuth, VIEWER_DEFAULTS.sky.turbidity],
}).spec;

/** The viewer setting of an id ('samplesPerFrame', 'sky.elevation'). */
export function viewerEntry(id: string): SettingEntry {
  const entry = VIEWER_ENTRIES.find((e) => e.id === id);
  if (!entry) throw new Error(`no viewer setting ${id}`);
  return entry;
}
