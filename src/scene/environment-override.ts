/**
 * Replacing a scene's environment (the CLI's --sky and --env, the page's sky panel and map picker).
 * The analytic sky is in physical units, so a scene switching to or from it has its camera's
 * exposure moved by the daylight exposure (scene/sky.ts DAYLIGHT_EXPOSURE_STOPS), once.
 */
import type { Environment } from './environment.ts';
import { DAYLIGHT_EXPOSURE_STOPS } from './sky.ts';
import type { Scene } from './types.ts';

export function withEnvironment(scene: Scene, environment: Environment): Scene {
  const wasSky = scene.environment?.kind === 'sky';
  const isSky = environment.kind === 'sky';
  const shift = (isSky ? DAYLIGHT_EXPOSURE_STOPS : 0) - (wasSky ? DAYLIGHT_EXPOSURE_STOPS : 0);
  const camera = shift === 0 ? scene.camera : { ...scene.camera, exposureStops: (scene.camera.exposureStops ?? 0) + shift };
  // The note on how the scene's own light was chosen no longer applies (scene/default-light.ts).
  const { lightingNote: _replaced, ...rest } = scene;
  return { ...rest, environment, camera };
}

/** The sky of `--sky elevation,azimuth[,turbidity]` (degrees; turbidity 1–10, default 3). */
export function skyEnvironment(elevationDeg: number, azimuthDeg: number, turbidity = 3, intensity = 1): Environment {
  return { kind: 'sky', sunElevationDeg: elevationDeg, sunAzimuthDeg: azimuthDeg, turbidity, groundAlbedo: 0.3, intensity };
}
