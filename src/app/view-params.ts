/**
 * The page's URL parameters: which scene, where the camera is and the settings, so that a link
 * restores a view. Pure (URLSearchParams in, plain data out), unit-tested both ways.
 *
 *   scene=cornell                      a built-in scene
 *   wad=<url>[&wad=<url>…]&map=E1M1    a Doom map from WAD files the server offers (IWAD first)
 *   ply=<url>                          a PLY mesh the server offers
 *                                      (the scene parameters: loaders/scene-link.ts, from the registry)
 *   cam=x,y,z,yaw,pitch  mode=walk|fly
 *   and every viewer setting with a `link` name in VIEWER_SETTINGS (viewer-settings.ts): fov=deg,
 *   spf, scale, acc=0|1, anim=0|1, converge=0|1 (converge when still), env-intensity; with
 *   sky=elevation,azimuth[,turbidity] (SKY_LINK): parsed, checked and written from their entries,
 *   so they accept what the panel accepts
 *   aperture=<radius>  focus=<distance>  the camera's thin lens, scene units (aperture 0: a pinhole;
 *                                      a link with only one of them takes the other from the scene's
 *                                      lens, or focuses on what lies at the image centre;
 *                                      renderer/lens-link.ts, which `lantern view` writes too)
 *   and every render setting with a `link` name in RENDER_SETTINGS (renderer/settings.ts): bounces,
 *   tonemap, exposure, torch=on|off, torch-color=r,g,b, torch-intensity, torch-range, debug,
 *   layout, heat-max=<n>|auto, depth, temporal=0|1, denoise=0|1, clamp-k, history-cap=<n>|unlimited,
 *   denoise-view; parsed, checked and written from their schema entries.
 *   mat=1:<index>:<name>:c=r,g,b;r=…   a material edit (one parameter per material; material-link.ts),
 *                                      applied once the scene has loaded
 *   look=doom                          a look (renderer/looks.ts): the settings it sets, under any
 *                                      the link names itself (a link written back names the settings)
 *   sky=elevation,azimuth[,turbidity]  env-intensity=x
 *                                      the Hosek–Wilkie sky instead of the scene's own environment
 *                                      (as the CLI's --sky and --env-intensity; turbidity left off:
 *                                      its default, 3); an HDR map opened from this computer cannot
 *                                      be linked
 */
import { formatSettingText, getAt, mergeSettings, parseSettingText, setAt, type SettingEntry } from '../renderer/settings-schema.ts';
import { isLook, lookSettings, LOOKS } from '../renderer/looks.ts';
import { SETTING_ENTRIES, type RenderSettings, type RenderSettingsPatch } from '../renderer/settings.ts';
import { formatSceneLocation, parseSceneLocation, type SceneLocation } from '../loaders/scene-link.ts';
import { formatLensLink, parseLensLink } from '../renderer/lens-link.ts';
import { MOVE_MODES, type MoveMode, type Pose } from './camera-controller.ts';
import { formatMaterialOverride, MATERIAL_LINK_PARAM, parseMaterialOverride, type MaterialOverride } from './material-link.ts';
import { SKY_LINK, VIEWER_DEFAULTS, VIEWER_ENTRIES } from './viewer-settings.ts';

export type { SceneLocation };

/** The settings that links carry. */
export const LINKED_SETTINGS: readonly SettingEntry[] = SETTING_ENTRIES.filter((e) => e.spec.link !== undefined);

/** The viewer's settings that links carry each under its own name (the sky's three travel together: SKY_LINK). Their paths are ViewParams' fields. */
export const LINKED_VIEWER_SETTINGS: readonly SettingEntry[] = VIEWER_ENTRIES.filter((e) => e.spec.link !== undefined);

/** Everything a link carries besides the scene; absent fields keep their defaults. */
export type ViewParams = RenderSettingsPatch & {
  readonly scene?: SceneLocation;
  readonly pose?: Pose;
  readonly fovDegrees?: number;
  /** The thin lens's aperture radius (scene units, ≥ 0). */
  readonly apertureRadius?: number;
  /** The thin lens's focus distance (scene units, > 0). */
  readonly focusDistance?: number;
  readonly mode?: MoveMode;
  readonly samplesPerFrame?: number;
  readonly scale?: number;
  readonly accumulate?: boolean;
  /** Whether the scene's clock runs (ViewerSettings.animate). */
  readonly animate?: boolean;
  /** Whether a still real-time view converges progressively (ViewerSettings.convergeWhenStill). */
  readonly convergeWhenStill?: boolean;
  /** The sky that replaces the scene's environment: sun elevation and azimuth (degrees), turbidity. */
  readonly sky?: SkyParams;
  /** Multiplies the sky's radiance. */
  readonly envIntensity?: number;
  /** Material edits, applied after the scene loads. */
  readonly materials?: readonly MaterialOverride[];
};

export interface SkyParams {
  readonly elevation: number;
  readonly azimuth: number;
  readonly turbidity: number;
}

/** The sky's default turbidity when a link gives only elevation and azimuth (the CLI's --sky too). */
export const DEFAULT_TURBIDITY = VIEWER_DEFAULTS.sky.turbidity;

/** The top-level render settings a link carries under their RenderSettings names (the torch, a group, apart: its parts wait for the scene). */
export const LINKED_RENDER_SETTINGS: readonly (keyof RenderSettings)[] = LINKED_SETTINGS.filter((e) => e.path.length === 1).map((e) => e.path[0] as keyof RenderSettings);

/** The render settings a link asks for (only those it names). */
export function linkedRenderSettings(view: ViewParams): Partial<RenderSettings> {
  const out: Partial<Record<keyof RenderSettings, unknown>> = {};
  for (const key of LINKED_RENDER_SETTINGS) if (view[key] !== undefined) out[key] = view[key];
  return out as Partial<RenderSettings>;
}

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
  /** A setting's value from its parameter, or a note of why not (the same words for render and viewer settings). */
  const setting = (spec: SettingEntry['spec']): unknown => {
    const name = spec.link!;
    const raw = params.get(name);
    if (raw === null) return undefined;
    const parsed = parseSettingText(spec, raw);
    if (parsed.ok) return parsed.value;
    problems.push(`${name}=${raw} ${parsed.problem.replace(/^must be/, 'is not')}`);
    return undefined;
  };
  const scene = parseSceneLocation(params);
  if (scene) view.scene = scene;

  const cam = numbers('cam', 5);
  if (cam) view.pose = { position: [cam[0]!, cam[1]!, cam[2]!], yaw: cam[3]!, pitch: cam[4]! };
  Object.assign(view, parseLensLink(params, problems));
  const mode = params.get('mode');
  if (mode !== null) {
    if ((MOVE_MODES as readonly string[]).includes(mode)) view.mode = mode as MoveMode;
    else problems.push(`mode=${mode} is not one of ${MOVE_MODES.join(', ')}`);
  }
  // The viewer's settings, each by its entry (fov, spf, scale, acc, anim, converge, env-intensity).
  for (const { path, spec } of LINKED_VIEWER_SETTINGS) {
    const value = setting(spec);
    if (value !== undefined) setAt(view as Record<string, unknown>, path, value);
  }
  const sky = setting(SKY_LINK) as readonly number[] | undefined;
  if (sky) view.sky = { elevation: sky[0]!, azimuth: sky[1]!, turbidity: sky[2] ?? DEFAULT_TURBIDITY };

  const materials: MaterialOverride[] = [];
  for (const raw of params.getAll(MATERIAL_LINK_PARAM)) {
    const parsed = parseMaterialOverride(raw);
    if (!parsed.ok) problems.push(parsed.problem);
    else if (materials.some((m) => m.index === parsed.value.index)) problems.push(`${MATERIAL_LINK_PARAM}=${raw}: material ${parsed.value.index} is edited twice`);
    else materials.push(parsed.value);
  }
  if (materials.length > 0) view.materials = materials;

  // A look first: the settings the link names go over it.
  const look = params.get('look');
  if (look !== null) {
    if (isLook(look)) Object.assign(view, mergeSettings(view as RenderSettingsPatch, lookSettings(look) as never));
    else problems.push(`look=${look} is not one of ${LOOKS.join(', ')}`);
  }
  for (const { path, spec } of LINKED_SETTINGS) {
    const value = setting(spec);
    if (value !== undefined) setAt(view as Record<string, unknown>, path, value);
  }
  return { view, problems };
}

export function formatViewParams(view: ViewParams): URLSearchParams {
  const p = new URLSearchParams();
  if (view.scene) formatSceneLocation(view.scene, p);
  if (view.pose) p.set('cam', [...view.pose.position, view.pose.yaw, view.pose.pitch].map(round).join(','));
  formatLensLink(view, p);
  if (view.mode) p.set('mode', view.mode);
  for (const { path, spec } of LINKED_VIEWER_SETTINGS) {
    const value = getAt(view, path);
    if (value !== undefined) p.set(spec.link!, formatSettingText(spec, value));
  }
  if (view.sky) p.set(SKY_LINK.link!, formatSettingText(SKY_LINK, [view.sky.elevation, view.sky.azimuth, view.sky.turbidity]));
  for (const m of view.materials ?? []) p.append(MATERIAL_LINK_PARAM, formatMaterialOverride(m));
  for (const { path, spec } of LINKED_SETTINGS) {
    const value = getAt(view, path);
    if (value !== undefined) p.set(spec.link!, formatSettingText(spec, value));
  }
  return p;
}
