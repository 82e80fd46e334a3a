/**
 * The panel's Environment folder as plain data: which environment lights the scene (its own, the
 * sky, an HDR map, none) and the parameters of each, turned into the scene model's Environment and
 * back, and into the link's `sky` and `env-intensity`. Pure, unit-tested; panel.ts binds it.
 */
import { skyEnvironment } from '../scene/environment-override.ts';
import type { Environment, EnvironmentImage } from '../scene/environment.ts';
import type { Scene } from '../scene/types.ts';
import type { ViewParams } from './view-params.ts';
import { VIEWER_DEFAULTS } from './viewer-settings.ts';

export const ENVIRONMENT_CHOICES = ['scene', 'sky', 'map', 'none'] as const;
export type EnvironmentChoiceKind = (typeof ENVIRONMENT_CHOICES)[number];

export interface EnvironmentChoice {
  kind: EnvironmentChoiceKind;
  /** The sun, degrees above the horizon. */
  elevation: number;
  /** The sun, degrees about +y from +z toward +x. */
  azimuth: number;
  turbidity: number;
  skyIntensity: number;
  mapIntensity: number;
  /** The map turned about +y, degrees. */
  rotation: number;
}

/** A sun high in the afternoon: what the sky shows the first time it is picked (the sky's defaults in VIEWER_SETTINGS). */
export const DEFAULT_ENVIRONMENT_CHOICE: Readonly<EnvironmentChoice> = Object.freeze({
  kind: 'scene',
  ...VIEWER_DEFAULTS.sky,
  skyIntensity: VIEWER_DEFAULTS.envIntensity,
  mapIntensity: 1,
  rotation: 0,
});

/**
 * The environment a choice asks for: undefined for the scene's own; for a map without an image
 * yet, undefined too (the scene keeps what it has until a file is opened).
 */
export function environmentOfChoice(choice: EnvironmentChoice, map: EnvironmentImage | undefined): Environment | undefined {
  switch (choice.kind) {
    case 'scene':
      return undefined;
    case 'none':
      return { kind: 'none' };
    case 'sky':
      return skyEnvironment(choice.elevation, choice.azimuth, choice.turbidity, choice.skyIntensity);
    case 'map':
      return map ? { kind: 'map', image: map, rotationDeg: choice.rotation, intensity: choice.mapIntensity } : undefined;
  }
}

/** The choice that shows an override environment (from a link, or set before), keeping the other kinds' parameters. */
export function choiceOfEnvironment(environment: Environment | undefined, previous: Readonly<EnvironmentChoice>): EnvironmentChoice {
  if (!environment) return { ...previous, kind: 'scene' };
  switch (environment.kind) {
    case 'sky':
      return { ...previous, kind: 'sky', elevation: environment.sunElevationDeg, azimuth: environment.sunAzimuthDeg, turbidity: environment.turbidity, skyIntensity: environment.intensity };
    case 'map':
      return { ...previous, kind: 'map', rotation: environment.rotationDeg, mapIntensity: environment.intensity };
    case 'none':
      return { ...previous, kind: 'none' };
    case 'constant':
    case 'gradient':
      // Not offered by the panel: shown as the scene's own, which is what such an override comes from.
      return { ...previous, kind: 'scene' };
  }
}

/** The sky a link asks for, or undefined (the scene's own); env-intensity alone has nothing to multiply. */
export function environmentOfLink(view: Pick<ViewParams, 'sky' | 'envIntensity'>): Environment | undefined {
  return view.sky ? skyEnvironment(view.sky.elevation, view.sky.azimuth, view.sky.turbidity, view.envIntensity ?? 1) : undefined;
}

/** What a link carries of an environment: the sky; an HDR map opened from this computer cannot travel in a link. */
export function linkOfEnvironment(environment: Environment | undefined): Pick<ViewParams, 'sky' | 'envIntensity'> {
  if (environment?.kind !== 'sky') return {};
  return { sky: { elevation: environment.sunElevationDeg, azimuth: environment.sunAzimuthDeg, turbidity: environment.turbidity }, ...(environment.intensity !== 1 ? { envIntensity: environment.intensity } : {}) };
}

/**
 * What the page says of how a loaded scene is lit (scene/default-light.ts: a default sky, or its own
 * emitters), as information; undefined when the panel or a link gives the environment instead, as
 * the note is then about light that is not shown.
 */
export function lightingNoteOf(scene: Pick<Scene, 'name' | 'lightingNote'>, override: Environment | undefined): string | undefined {
  return override === undefined && scene.lightingNote ? `${scene.name}: ${scene.lightingNote}` : undefined;
}
