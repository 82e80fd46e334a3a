/**
 * Depth of field on the command line: `--aperture <radius>` (scene units) or `--f-number <N>` (with
 * `--focal-length <mm>`, 35 mm-equivalent; by default the focal length a full-frame sensor needs
 * for the camera's field of view), and `--focus-distance <d>`. Without a focus distance the lens
 * focuses on the `--camera` target, else at the scene's own focus distance, else on what lies at
 * the image centre (one CPU ray through the BVH). The arithmetic is scene/lens.ts.
 */
import { InvalidArgumentError, type Command } from 'commander';
import { LanternError } from '../errors.ts';
import { length, sub, type Vec3 } from '../math/vec3.ts';
import { apertureRadiusForFNumber } from '../scene/lens.ts';
import type { Camera, Scene, ThinLens } from '../scene/types.ts';

export interface LensOptions {
  aperture?: number;
  fNumber?: number;
  focalLength?: number;
  focusDistance?: number;
}

/** A finite number with a lower bound, open (> min) or closed (≥ min), with a message naming the option and its meaning. */
function boundedNumber(name: string, min: number, open: boolean, meaning: string): (value: string) => number {
  return (value: string) => {
    const n = Number(value);
    const ok = value.trim() !== '' && Number.isFinite(n) && (open ? n > min : n >= min);
    if (!ok) throw new InvalidArgumentError(`${name} must be a number ${open ? '>' : '≥'} ${min} (${meaning}), not '${value}'.`);
    return n;
  };
}

/** The parser of --aperture (≥ 0) or --focus-distance (> 0), for commands that take only those (`view`). */
export const lensNumber = (name: '--aperture' | '--focus-distance', allowZero: boolean) => boundedNumber(name, 0, !allowZero, allowZero ? 'a radius in scene units' : 'scene units');

export function withLensOptions(command: Command): Command {
  return command
    .option('--aperture <radius>', 'depth of field: the lens aperture radius in scene units (0: a pinhole)', lensNumber('--aperture', true))
    .option('--f-number <N>', 'depth of field: the aperture as an f-number (needs a scene that knows its unit size)', boundedNumber('--f-number', 0, true, 'focal length over aperture diameter'))
    .option('--focal-length <mm>', 'with --f-number: 35 mm-equivalent focal length (default: the one that gives the field of view on a 24 mm-high sensor)', boundedNumber('--focal-length', 0, true, 'millimetres'))
    .option('--focus-distance <d>', 'depth of field: distance to the plane in focus along the view (default: the --camera target, the scene\'s own, or what lies at the image centre)', lensNumber('--focus-distance', false));
}

export interface LensContext {
  readonly scene: Pick<Scene, 'name' | 'metersPerUnit'>;
  /** The --camera look-at target, when given. */
  readonly target?: Vec3;
  /** Depth of the surface at the image centre (renderer/focus.ts), asked only when needed. */
  readonly centreDistance: (camera: Camera) => number | undefined;
}

/**
 * The camera with the lens the options ask for (the camera after --camera and --fov). No lens option:
 * the camera as it is (the scene's own lens, if any). `--aperture 0`: a pinhole.
 */
export function cameraWithLens(camera: Camera, o: LensOptions, context: LensContext): Camera {
  checkLensOptions(o);
  const radius = apertureRadius(camera, o, context.scene);
  if (radius === undefined) {
    if (o.focusDistance === undefined) return camera;
    if (!camera.lens) throw new LanternError(`--focus-distance needs a lens, and the camera of '${context.scene.name}' is a pinhole`, 'Add --aperture <radius> or --f-number <N>');
    return { ...camera, lens: { ...camera.lens, focusDistance: o.focusDistance } };
  }
  if (radius === 0 && o.focusDistance === undefined) {
    const { lens: _, ...pinhole } = camera;
    return pinhole;
  }
  const lens: ThinLens = { apertureRadius: radius, focusDistance: o.focusDistance ?? defaultFocusDistance(camera, context) };
  return { ...camera, lens };
}

/** Refuses lens options that contradict each other; needs no scene, so commands call it before opening one. */
export function checkLensOptions(o: LensOptions): void {
  if (o.aperture !== undefined && o.fNumber !== undefined) throw new LanternError('--aperture and --f-number both give the aperture', 'Give one of them');
  if (o.focalLength !== undefined && o.fNumber === undefined) throw new LanternError('--focal-length sets the aperture only with --f-number', 'Add --f-number <N>, or give the radius with --aperture');
}

/** The aperture radius in scene units the options give, or undefined when they give none. */
function apertureRadius(camera: Camera, o: LensOptions, scene: LensContext['scene']): number | undefined {
  if (o.aperture !== undefined) return o.aperture;
  if (o.fNumber === undefined) return undefined;
  if (!scene.metersPerUnit) {
    throw new LanternError(`--f-number needs the size of the scene's unit, and '${scene.name}' does not say how large its unit is (no metersPerUnit)`, 'Give the aperture radius in scene units with --aperture instead');
  }
  return apertureRadiusForFNumber(o.fNumber, scene.metersPerUnit, camera.vfovDegrees, o.focalLength);
}

/** The --camera target's distance, else the scene's own focus distance, else the depth at the image centre. */
function defaultFocusDistance(camera: Camera, context: LensContext): number {
  if (context.target) return length(sub(context.target, camera.position));
  if (camera.lens) return camera.lens.focusDistance;
  const centre = context.centreDistance(camera);
  if (centre !== undefined && centre > 0) return centre;
  throw new LanternError('the lens has nothing to focus on: no --camera target, no focus distance in the scene, and the ray through the image centre hits nothing', 'Give --focus-distance <d> in scene units');
}
