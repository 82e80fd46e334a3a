/**
 * The page's URL parameters: which scene, where the camera is and the settings, so that a link
 * restores a view. Pure (URLSearchParams in, plain data out), unit-tested both ways.
 *
 *   scene=cornell                      a built-in scene
 *   wad=<url>[&wad=<url>…]&map=E1M1    a Doom map from WAD files the server offers (IWAD first)
 *   ply=<url>                          a PLY mesh the server offers
 *                                      (the scene parameters: loaders/scene-link.ts, from the registry)
 *   cam=x,y,z,yaw,pitch  fov=deg  mode=walk|fly
 *   spf, bounces, scale, acc=0|1, tonemap, exposure, torch=on|off, torch-color=r,g,b,
 *   torch-intensity, torch-range, debug=<view>, layout=replace|side-by-side|overlay, depth=<d>,
 *   heat-max=<n>|auto, temporal=0|1, denoise=0|1, clamp-k, history-cap=<n>|unlimited, denoise-view
 */
import { DEBUG_LAYOUTS, DEBUG_VIEWS, DENOISE_VIEWS, MAX_HISTORY_CAP, MAX_WIREFRAME_DEPTH, TONE_MAPPERS, type DebugLayout, type DebugView, type DenoiseView, type HistoryCap, type RenderSettings, type ToneMapper } from '../renderer/settings.ts';
import { formatSceneLocation, parseSceneLocation, type SceneLocation } from '../loaders/scene-link.ts';
import { MOVE_MODES, type MoveMode, type Pose } from './camera-controller.ts';

export type { SceneLocation };

/** Everything a link carries besides the scene; absent fields keep their defaults. */
export interface ViewParams {
  readonly scene?: SceneLocation;
  readonly pose?: Pose;
  readonly fovDegrees?: number;
  readonly mode?: MoveMode;
  readonly samplesPerFrame?: number;
  readonly maxBounces?: number;
  readonly scale?: number;
  readonly accumulate?: boolean;
  readonly toneMapper?: ToneMapper;
  readonly exposureStops?: number;
  readonly debugView?: DebugView;
  readonly debugLayout?: DebugLayout;
  readonly wireframeDepth?: number;
  readonly heatMax?: number | 'auto';
  readonly temporal?: boolean;
  readonly denoise?: boolean;
  readonly clampK?: number;
  readonly historyCap?: HistoryCap;
  readonly denoiseView?: DenoiseView;
  readonly torch?: {
    readonly enabled?: boolean;
    readonly color?: readonly [number, number, number];
    readonly intensity?: number;
    readonly range?: number;
  };
}

/** The render settings a link carries under their RenderSettings names (the torch apart). */
export const LINKED_RENDER_SETTINGS = ['maxBounces', 'toneMapper', 'exposureStops', 'debugView', 'debugLayout', 'wireframeDepth', 'heatMax', 'temporal', 'denoise', 'clampK', 'historyCap', 'denoiseView'] as const;

/** The render settings a link asks for (only those it names). */
export function linkedRenderSettings(view: ViewParams): Partial<RenderSettings> {
  const out: Partial<Record<keyof RenderSettings, unknown>> = {};
  for (const key of LINKED_RENDER_SETTINGS) if (view[key] !== undefined) out[key] = view[key];
  return out as Partial<RenderSettings>;
}

/** Values outside these ranges are refused (the parameter is ignored with a note). */
export const LIMITS = {
  samplesPerFrame: [1, 64],
  maxBounces: [0, 64],
  scale: [0.01, 2],
  exposureStops: [-20, 20],
  fovDegrees: [5, 150],
} as const;

const round = (v: number) => Number(v.toFixed(4));

export function parseViewParams(params: URLSearchParams): { view: ViewParams; problems: string[] } {
  const problems: string[] = [];
  const view: { -readonly [K in keyof ViewParams]: ViewParams[K] } = {};
  const numbers = (name: string, count: number): number[] | undefined => {
    const raw = params.get(name);
    if (raw === null) return undefined;
    const values = raw.split(',').map(Number);
    if (values.length !== count || !values.every(Number.isFinite)) {
      problems.push(`${name}=${raw} is not ${count} number${count > 1 ? 's' : ''}`);
      return undefined;
    }
    return values;
  };
  const ranged = (name: string, [lo, hi]: readonly [number, number], integer = false): number | undefined => {
    const v = numbers(name, 1)?.[0];
    if (v === undefined) return undefined;
    if (v < lo || v > hi || (integer && !Number.isInteger(v))) {
      problems.push(`${name}=${v} is outside ${lo}–${hi}${integer ? ' (whole numbers)' : ''}`);
      return undefined;
    }
    return v;
  };
  const scene = parseSceneLocation(params);
  if (scene) view.scene = scene;

  const cam = numbers('cam', 5);
  if (cam) view.pose = { position: [cam[0]!, cam[1]!, cam[2]!], yaw: cam[3]!, pitch: cam[4]! };
  const fov = ranged('fov', LIMITS.fovDegrees);
  if (fov !== undefined) view.fovDegrees = fov;
  const mode = params.get('mode');
  if (mode !== null) {
    if ((MOVE_MODES as readonly string[]).includes(mode)) view.mode = mode as MoveMode;
    else problems.push(`mode=${mode} is not one of ${MOVE_MODES.join(', ')}`);
  }
  const spf = ranged('spf', LIMITS.samplesPerFrame, true);
  if (spf !== undefined) view.samplesPerFrame = spf;
  const bounces = ranged('bounces', LIMITS.maxBounces, true);
  if (bounces !== undefined) view.maxBounces = bounces;
  const scale = ranged('scale', LIMITS.scale);
  if (scale !== undefined) view.scale = scale;
  const acc = params.get('acc');
  if (acc !== null) view.accumulate = acc !== '0';
  const tonemap = params.get('tonemap');
  if (tonemap !== null) {
    if ((TONE_MAPPERS as readonly string[]).includes(tonemap)) view.toneMapper = tonemap as ToneMapper;
    else problems.push(`tonemap=${tonemap} is not one of ${TONE_MAPPERS.join(', ')}`);
  }
  const exposure = ranged('exposure', LIMITS.exposureStops);
  if (exposure !== undefined) view.exposureStops = exposure;
  const oneOf = <T extends string>(name: string, values: readonly T[]): T | undefined => {
    const v = params.get(name);
    if (v === null) return undefined;
    if ((values as readonly string[]).includes(v)) return v as T;
    problems.push(`${name}=${v} is not one of ${values.join(', ')}`);
    return undefined;
  };
  const debugView = oneOf('debug', DEBUG_VIEWS);
  if (debugView) view.debugView = debugView;
  const debugLayout = oneOf('layout', DEBUG_LAYOUTS);
  if (debugLayout) view.debugLayout = debugLayout;
  const depth = ranged('depth', [0, MAX_WIREFRAME_DEPTH], true);
  if (depth !== undefined) view.wireframeDepth = depth;
  if (params.get('heat-max') === 'auto') view.heatMax = 'auto';
  else {
    const heatMax = ranged('heat-max', [1e-6, 1e9]);
    if (heatMax !== undefined) view.heatMax = heatMax;
  }

  const temporal = params.get('temporal');
  if (temporal !== null) view.temporal = temporal !== '0';
  const denoise = params.get('denoise');
  if (denoise !== null) view.denoise = denoise !== '0';
  const clampK = ranged('clamp-k', [0, 16]);
  if (clampK !== undefined) view.clampK = clampK;
  if (params.get('history-cap') === 'unlimited') view.historyCap = 'unlimited';
  else {
    const cap = ranged('history-cap', [1, MAX_HISTORY_CAP], true);
    if (cap !== undefined) view.historyCap = cap;
  }
  const denoiseView = oneOf('denoise-view', DENOISE_VIEWS);
  if (denoiseView) view.denoiseView = denoiseView;

  const torch: { enabled?: boolean; color?: [number, number, number]; intensity?: number; range?: number } = {};
  const on = params.get('torch');
  if (on !== null) torch.enabled = on !== 'off';
  const color = numbers('torch-color', 3);
  if (color && color.every((c) => c >= 0 && c <= 1)) torch.color = [color[0]!, color[1]!, color[2]!];
  else if (color) problems.push('torch-color components must be in 0–1');
  const intensity = ranged('torch-intensity', [0, 1e9]);
  if (intensity !== undefined) torch.intensity = intensity;
  const range = ranged('torch-range', [1e-3, 1e9]);
  if (range !== undefined) torch.range = range;
  if (Object.keys(torch).length > 0) view.torch = torch;
  return { view, problems };
}

export function formatViewParams(view: ViewParams): URLSearchParams {
  const p = new URLSearchParams();
  if (view.scene) formatSceneLocation(view.scene, p);
  if (view.pose) p.set('cam', [...view.pose.position, view.pose.yaw, view.pose.pitch].map(round).join(','));
  if (view.fovDegrees !== undefined) p.set('fov', String(round(view.fovDegrees)));
  if (view.mode) p.set('mode', view.mode);
  if (view.samplesPerFrame !== undefined) p.set('spf', String(view.samplesPerFrame));
  if (view.maxBounces !== undefined) p.set('bounces', String(view.maxBounces));
  if (view.scale !== undefined) p.set('scale', String(round(view.scale)));
  if (view.accumulate !== undefined) p.set('acc', view.accumulate ? '1' : '0');
  if (view.toneMapper) p.set('tonemap', view.toneMapper);
  if (view.exposureStops !== undefined) p.set('exposure', String(round(view.exposureStops)));
  if (view.debugView) p.set('debug', view.debugView);
  if (view.debugLayout) p.set('layout', view.debugLayout);
  if (view.wireframeDepth !== undefined) p.set('depth', String(view.wireframeDepth));
  if (view.heatMax !== undefined) p.set('heat-max', String(view.heatMax));
  if (view.temporal !== undefined) p.set('temporal', view.temporal ? '1' : '0');
  if (view.denoise !== undefined) p.set('denoise', view.denoise ? '1' : '0');
  if (view.clampK !== undefined) p.set('clamp-k', String(round(view.clampK)));
  if (view.historyCap !== undefined) p.set('history-cap', String(view.historyCap));
  if (view.denoiseView) p.set('denoise-view', view.denoiseView);
  const t = view.torch;
  if (t?.enabled !== undefined) p.set('torch', t.enabled ? 'on' : 'off');
  if (t?.color) p.set('torch-color', t.color.map(round).join(','));
  if (t?.intensity !== undefined) p.set('torch-intensity', String(round(t.intensity)));
  if (t?.range !== undefined) p.set('torch-range', String(round(t.range)));
  return p;
}
