/**
 * Camera paths for offline animations (`lantern render --path path.json --frames N`): keyframes of
 * position, look-at target and optionally vertical field of view at times in seconds, interpolated
 * linearly; frames are spaced evenly from the first keyframe's time to the last one's.
 *
 *   { "keyframes": [ { "time": 0, "position": [278, 273, -800], "target": [278, 273, 0], "fov": 39.3 },
 *                    { "time": 2, "position": [400, 273, -800], "target": [278, 273, 0] } ] }
 */
import { LanternError } from '../errors.ts';
import { add, length, scale, sub, type Vec3 } from '../math/vec3.ts';
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

const isVec3 = (v: unknown): v is Vec3 => Array.isArray(v) && v.length === 3 && v.every((x) => typeof x === 'number' && Number.isFinite(x));

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
    if (typeof k.time !== 'number' || !Number.isFinite(k.time)) throw new LanternError(`${where}: "time" must be a number of seconds`);
    if (k.time <= previous) throw new LanternError(`${where}: times must increase (${k.time} follows ${previous})`);
    previous = k.time;
    if (!isVec3(k.position)) throw new LanternError(`${where}: "position" must be three numbers`);
    if (!isVec3(k.target)) throw new LanternError(`${where}: "target" must be three numbers`);
    if (!(length(sub(k.target, k.position)) > 0)) throw new LanternError(`${where}: the target is the same point as the position`);
    if (k.fov !== undefined && !(typeof k.fov === 'number' && k.fov > 0 && k.fov < 180)) throw new LanternError(`${where}: "fov" must be degrees between 0 and 180`);
    return { time: k.time, position: k.position, target: k.target, ...(k.fov !== undefined ? { fov: k.fov as number } : {}) };
  });
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
  return { ...base, position, forward: sub(target, position), vfovDegrees: fovA + (fovB - fovA) * t };
}

/** The time of frame `index` of `frames`, evenly spaced over the path (one frame: the start). */
export function frameTime(path: CameraPath, index: number, frames: number): number {
  const start = path.keyframes[0]!.time, end = path.keyframes[path.keyframes.length - 1]!.time;
  return frames > 1 ? start + ((end - start) * index) / (frames - 1) : start;
}
