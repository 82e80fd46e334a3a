/**
 * `--sky elevation,azimuth[,turbidity]` (the Hosek–Wilkie sky with its sun, degrees) and
 * `--env file.hdr|file.exr` (a lat-long HDR map) with `--env-intensity` and `--env-rotation`, or
 * `--env none` (no environment at all, also none of the default sky a model may get): what lights
 * the scene instead of its own environment. Read here because reading the map is file access.
 */
import { basename } from 'node:path';
import type { Command } from 'commander';
import { LanternError } from '../errors.ts';
import { loadEnvironmentImage } from '../loaders/environment-image.ts';
import { skyEnvironment } from '../scene/environment-override.ts';
import type { Environment } from '../scene/environment.ts';
import { numberListOption, numberOption, pathOption } from './options.ts';
import { readUserFile } from './user-files.ts';

/** The --env value that asks for no environment (a file of that name is `./none`). */
const NO_ENVIRONMENT = 'none';

export interface EnvironmentOptions {
  readonly sky?: number[];
  readonly env?: string;
  readonly envIntensity?: number;
  readonly envRotation?: number;
}

export function withEnvironmentOptions(command: Command): Command {
  return command
    .option('--sky <elevation,azimuth[,turbidity]>', 'light the scene with the Hosek–Wilkie sky and its sun: sun elevation and azimuth in degrees (azimuth from +z toward +x), turbidity 1–10 (default 3)', numberListOption('--sky', [2, 3]))
    .option('--env <file.hdr|none>', 'light the scene with an HDR environment map (Radiance .hdr or OpenEXR, lat-long); none: no environment, not even the default sky a model without enough light of its own gets (./none names a file)', pathOption('--env'))
    .option('--env-intensity <x>', 'multiplies the --sky or --env radiance', numberOption('--env-intensity', 0, 1e9))
    .option('--env-rotation <degrees>', 'turns the --env map about the vertical axis', numberOption('--env-rotation', -360, 360));
}

/** The environment the options ask for, or undefined to keep the scene's own. */
export function environmentFromOptions(o: EnvironmentOptions): Environment | undefined {
  if (o.sky && o.env) throw new LanternError('--sky and --env both give the environment', 'Use one of them');
  if (o.env === NO_ENVIRONMENT) {
    if (o.envIntensity !== undefined || o.envRotation !== undefined) throw new LanternError('--env-intensity and --env-rotation have nothing to act on with --env none');
    return { kind: 'none' };
  }
  const intensity = o.envIntensity ?? 1;
  if (o.sky) {
    const [elevation, azimuth, turbidity = 3] = o.sky as [number, number, number?];
    if (!(elevation >= -90 && elevation <= 90)) throw new LanternError(`--sky: the sun's elevation must be from -90 to 90 degrees, not ${elevation}`);
    if (!(turbidity >= 1 && turbidity <= 10)) throw new LanternError(`--sky: turbidity must be from 1 to 10, not ${turbidity}`);
    return skyEnvironment(elevation, azimuth, turbidity, intensity);
  }
  if (o.env) {
    const bytes = readUserFile(o.env, { what: '--env' });
    return { kind: 'map', image: loadEnvironmentImage(bytes, basename(o.env)), rotationDeg: o.envRotation ?? 0, intensity };
  }
  if (o.envIntensity !== undefined || o.envRotation !== undefined) throw new LanternError('--env-intensity and --env-rotation go with --sky or --env');
  return undefined;
}
