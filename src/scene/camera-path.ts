/**
 * Camera paths for offline animations (`lantern render --path path.json --frames N`): keyframes of
 * position, look-at target and optionally vertical field of view at times in seconds, interpolated
 * linearly; frames are spaced evenly from the first keyframe's time to the last one's.
 *
 *   { "keyframes": [ { "time": 0, "position": [278, 273, -800], "target": [278, 273, 0], "fov": 39.3 },
 *                    { "time": 2, "position": [400, 273, -800], "target": [278, 273, 0] } ] }
 */
import { LanternError } from '../errors.ts';
import { add, cross, dot, length, scale, sub, type Vec3 } from '../math/vec3.ts';
import type { Camera } from './types.ts';

export interface CameraKeyframe {
  readonly time: number;
  readonly position: Vec3;
  readonly target: Vec3;
  /** Vertical field of view in degrees; absent: the base camera's. */
  readonly fov?: number;
}

export interface CameraPath {
  readonly keyframes: readonly CameraKeyframe[];
}

/**
 * The largest coordinate a camera may have (here and in `--camera`): float32 positions that far out
 * are already coarse, and 1e308 is finite while the difference of two such is not.
 */
export const MAX_CAMERA_COORDINATE = 1e7;

/**
 * The largest keyframe time, in seconds either way (`--time` takes the same range): frames are
 * spaced over end − start, which for times of ±1e308 is infinite, and every frame time NaN.
 */
export const MAX_PATH_SECONDS = 1e6;

const isVec3 = (v: unknown): v is Vec3 =>
  Array.isArray(v) && v.length === 3 && v.every((x) => typeof x === 'number' && Number.isFinite(x) && Math.abs(x) <= MAX_CAMERA_COORDINATE);

/**
 * An up vector for a camera looking along `forward`: `preferred` unless the camera looks (nearly)
 * along it, where it would not fix the image's rotation; then +y, or −z when +y is the one it looks
 * along (straight up or down), as `--camera` has always done.
 */
export function uprightFor(forward: Vec3, preferred: Vec3 = [0, 1, 0]): Vec3 {
  const parallel = (up: Vec3) => !(length(cross(forward, up)) > 1e-9 * length(forward) * length(up));
  if (!parallel(preferred)) return preferred;
  return parallel([0, 1, 0]) ? [0, 0, -1] : [0, 1, 0];
}

/** Whether the camera of a segment from keyframe a to b passes through its target (target − position reaches 0). */
function passesThroughTarget(a: CameraKeyframe, b: CameraKeyframe): boolean {
  const da = sub(a.target, a.position), db = sub(b.target, b.position);
  // d(t) = da + t (db − da) is 0 for some t in [0, 1] only when da and db point opposite ways along one line.
  return dot(da, db) < 0 && length(cross(da, db)) <= 1e-9 * length(da) * length(db);
}

/** Checks a parsed JSON value and returns it as a path; every mistake is a LanternError naming the keyframe. */
export function parseCameraPath(json: unknown, name = 'camera path'): CameraPath {
  const keyframes = (json as { keyframes?: unknown } | null)?.keyframes;
  if (!Array.isArray(keyframes) || keyframes.length === 0) {
    throw new LanternError(`${name}: expected an object with a non-empty "keyframes" array`, 'See "Camera paths" in the README for the format.');
  }
  let previous = -Infinity;
  const out = keyframes.map((k: Record<string, unknown>, i): CameraKeyframe => {
    const where = `${name}: keyframe ${i}`;
    if (typeof k !== 'object' || k === null) throw new LanternError(`${where} is not an object`);
    if (typeof k.time !== 'number' || !(Math.abs(k.time) <= MAX_PATH_SECONDS)) throw new LanternError(`${where}: "time" must be a number of seconds from -${MAX_PATH_SECONDS} to ${MAX_PATH_SECONDS}`);
    if (k.time <= previous) throw new LanternError(`${where}: times must increase (${k.time} follows ${previous})`);
    previous = k.time;
    if (!isVec3(k.position)) throw new LanternError(`${where}: "position" must be three numbers from -${MAX_CAMERA_COORDINATE} to ${MAX_CAMERA_COORDINATE}`);
    if (!isVec3(k.target)) throw new LanternError(`${where}: "target" must be three numbers from -${MAX_CAMERA_COORDINATE} to ${MAX_CAMERA_COORDINATE}`);
    if (!(length(sub(k.target, k.position)) > 0)) throw new LanternError(`${where}: the target is the same point as the position`);
    if (k.fov !== undefined && !(typeof k.fov === 'number' && k.fov > 0 && k.fov < 180)) throw new LanternError(`${where}: "fov" must be degrees between 0 and 180`);
    return { time: k.time, position: k.position, target: k.target, ...(k.fov !== undefined ? { fov: k.fov as number } : {}) };
  });
  for (let i = 0; i + 1 < out.length; i++) {
    if (passesThroughTarget(out[i]!, out[i + 1]!)) throw new LanternError(`${name}: between keyframes ${i} and ${i + 1} the camera passes through its target`, 'Move the target so that it stays in front of the camera');
  }
  return { keyframes: out };
}

const lerp = (a: Vec3, b: Vec3, t: number): Vec3 => add(a, scale(sub(b, a), t));

/** The camera at `time` (clamped to the path's span), over `base` for what the path leaves out (up, exposure). */
export function cameraAt(path: CameraPath, time: number, base: Camera): Camera {
  const ks = path.keyframes;
  let i = 0;
  while (i < ks.length - 2 && time > ks[i + 1]!.time) i++;
  const a = ks[i]!, b = ks[Math.min(i + 1, ks.length - 1)]!;
  const t = b.time > a.time ? Math.min(Math.max((time - a.time) / (b.time - a.time), 0), 1) : 0;
  const position = lerp(a.position, b.position, t);
  const target = lerp(a.target, b.target, t);
  const fovA = a.fov ?? base.vfovDegrees, fovB = b.fov ?? base.vfovDegrees;
  const forward = sub(target, position);
  // A keyframe may look straight up or down: keep the base camera's up unless it looks along it.
  return { ...base, position, forward, up: uprightFor(forward, base.up), vfovDegrees: fovA + (fovB - fovA) * t };
}

/** The time of frame `index` of `frames`, evenly spaced over the path (one frame: the start). */
export function frameTime(path: CameraPath, index: number, frames: number): number {
  const start = path.keyframes[0]!.time, end = path.keyframes[path.keyframes.length - 1]!.time;
  return frames > 1 ? start + ((end - start) * index) / (frames - 1) : start;
}
