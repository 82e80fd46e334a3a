/**
 * Thin-lens arithmetic (pbrt-v4 §5.2.3; the camera model of scene/types.ts ThinLens): what a lens's
 * numbers must be, a photographer's f-number and focal length turned into an aperture radius in
 * scene units, and the circle of confusion a point off the plane of focus is spread over. Pure.
 */
import type { Camera, ThinLens } from './types.ts';

/** Height of a full-frame (35 mm) sensor in millimetres: the frame that "35 mm-equivalent" focal lengths refer to. */
export const FULL_FRAME_HEIGHT_MM = 24;

/** What is wrong with a lens, or undefined. An aperture of 0 is a pinhole that keeps its focus distance. */
export function lensProblem(lens: ThinLens): string | undefined {
  const { apertureRadius: a, focusDistance: f } = lens;
  if (!Number.isFinite(a) || a < 0) return `the lens aperture radius ${a} is not a finite number ≥ 0`;
  if (!Number.isFinite(f) || f <= 0) return `the lens focus distance ${f} is not a finite number > 0`;
  return undefined;
}

/**
 * The 35 mm-equivalent focal length (mm) that gives this vertical field of view on a full-frame
 * sensor: the sensor's half-height over tan(vfov/2), f = 12 mm / tan(vfov/2).
 */
export function focalLengthForFov(vfovDegrees: number): number {
  return FULL_FRAME_HEIGHT_MM / 2 / Math.tan((vfovDegrees * Math.PI) / 360);
}

/**
 * The aperture radius in scene units of a lens of f-number N: the entrance pupil's diameter is the
 * focal length over N, f/N millimetres, so the radius is f/(2N) mm, converted with the scene's size of
 * one unit. The focal length defaults to the one matching the camera's field of view on a full-frame
 * sensor (focalLengthForFov); a focal length that disagrees with the field of view (a crop) keeps the
 * field of view and takes the pupil of that focal length.
 */
export function apertureRadiusForFNumber(fNumber: number, metersPerUnit: number, vfovDegrees: number, focalLengthMm = focalLengthForFov(vfovDegrees)): number {
  const pupilDiameterMm = focalLengthMm / fNumber;
  return (pupilDiameterMm / 2 / 1000) / metersPerUnit;
}

/** The inverse of apertureRadiusForFNumber: the f-number of an aperture radius (scene units) at the focal length of the field of view. */
export function fNumberForAperture(apertureRadius: number, metersPerUnit: number, vfovDegrees: number, focalLengthMm = focalLengthForFov(vfovDegrees)): number {
  return focalLengthMm / (2 * apertureRadius * metersPerUnit * 1000);
}

/**
 * Diameter in pixels of the blur disk of a point at depth `depth` (along forward, scene units) seen
 * by `camera` with its lens, in an image `imageHeight` pixels high: on the plane of focus the disk's
 * diameter is 2A·|d − F|/d (similar triangles through the aperture), and one pixel there spans
 * 2F·tan(vfov/2)/H. 0 for a pinhole.
 */
export function blurDiameterPixels(camera: Camera, depth: number, imageHeight: number): number {
  const lens = camera.lens;
  if (!lens || lens.apertureRadius === 0) return 0;
  const onFocusPlane = (2 * lens.apertureRadius * Math.abs(depth - lens.focusDistance)) / depth;
  const pixel = (2 * lens.focusDistance * Math.tan((camera.vfovDegrees * Math.PI) / 360)) / imageHeight;
  return onFocusPlane / pixel;
}
