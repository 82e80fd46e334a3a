/**
 * `--camera px,py,pz,tx,ty,tz` (position and look-at target in scene coordinates) and `--fov`,
 * applied over the scene's own camera. For Doom maps, scene coordinates are (x, height, −y) of the
 * map's (x, y, height).
 */
import type { Command } from 'commander';
import { LanternError } from '../errors.ts';
import { numberListOption, numberOption } from './options.ts';
import { sub, length, type Vec3 } from '../math/vec3.ts';
import { MAX_CAMERA_COORDINATE, uprightFor } from '../scene/camera-path.ts';
import type { Camera } from '../scene/types.ts';

export function cameraFromOptions(base: Camera, look?: number[], fov?: number): Camera {
  let camera = base;
  if (look) {
    const position: Vec3 = [look[0]!, look[1]!, look[2]!];
    const target: Vec3 = [look[3]!, look[4]!, look[5]!];
    const forward = sub(target, position);
    if (!(length(forward) > 0)) throw new LanternError('--camera: the target is the same point as the position');
    camera = { ...camera, position, forward, up: uprightFor(forward) };
  }
  if (fov !== undefined) camera = { ...camera, vfovDegrees: fov };
  return camera;
}

/** `--camera` and `--fov`, as render and bench take them. */
export function withCameraOptions(command: Command): Command {
  return command
    .option('--camera <px,py,pz,tx,ty,tz>', 'camera position and look-at target in scene coordinates (Doom maps: x, height, -y)', numberListOption('--camera', [6], MAX_CAMERA_COORDINATE))
    .option('--fov <degrees>', 'vertical field of view', numberOption('--fov', 1, 179));
}
