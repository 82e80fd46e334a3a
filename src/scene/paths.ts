/**
 * Instances carried along closed paths (the dungeon's phantom): the curves of the data
 * (`InstancePath`, scene/dynamics-types.ts, the field `paths` of SceneDynamics), checked and compiled
 * into poses by time; world/paths.ts's animator plays them, and loaders pose what they place with
 * them. A path is a closed loop through world-space points, either a polyline or a centripetal
 * Catmull–Rom spline through them (Barry & Goldman's pyramid, "A recursive evaluation algorithm for a
 * class of Catmull-Rom splines", SIGGRAPH 1988; centripetal knots after Yuksel, Schaefer & Keyser
 * 2011, which never form cusps or self-intersections within a segment). The instance moves at a
 * constant speed along the arc, optionally turns its object +z toward the direction of motion
 * (object +y along `up`), and bobs along `up`. The pose is a pure function of time, so
 * `lantern render --time t` and the viewer agree. Pure.
 */
import { LanternError } from '../errors.ts';
import { IDENTITY, multiply, type Mat4 } from '../math/mat4.ts';
import { cross, dot, length, normalize, sub, type Vec3 } from '../math/vec3.ts';
import type { InstancePath } from './dynamics-types.ts';
import type { Scene } from './types.ts';

/**
 * Arc-length samples per segment of the curve: the table that makes the speed constant. Between samples
 * the parameter is interpolated linearly, so the speed is off by about the relative change of the
 * curve's parametric speed over one sample: under 0.5 % at 128 on a right-angle Catmull–Rom turn.
 */
const SAMPLES_PER_SEGMENT = 128;

/** What is wrong with a path in `scene`, or undefined. */
export function pathProblem(scene: Scene, path: InstancePath): string | undefined {
  const inst = scene.instances.find((i) => i.id === path.instance);
  if (!inst) return `carries instance ${path.instance}, which the scene does not have`;
  if (!inst.moves) return `carries instance ${path.instance}, which was not created with moves: true`;
  if (path.points.length < 3) return `has ${path.points.length} points; a closed path needs at least 3`;
  for (const [i, p] of path.points.entries()) {
    if (!p.every(Number.isFinite)) return `point ${i} is not finite`;
    const next = path.points[(i + 1) % path.points.length]!;
    if (length(sub(next, p)) === 0) return `points ${i} and ${(i + 1) % path.points.length} are equal`;
  }
  if (!(path.speed > 0) || !Number.isFinite(path.speed)) return `speed must be a finite number > 0, not ${path.speed}`;
  if (path.offset !== undefined && !Number.isFinite(path.offset)) return `offset must be finite, not ${path.offset}`;
  if (path.up && !(length(path.up) > 0 && path.up.every(Number.isFinite))) return 'up must be a finite, non-zero vector';
  if (path.bob) {
    if (!Number.isFinite(path.bob.amplitude)) return `bob amplitude must be finite, not ${path.bob.amplitude}`;
    if (!(Number.isInteger(path.bob.perLap) && path.bob.perLap >= 1)) return `bob perLap must be a whole number ≥ 1 (a lap must be a period), not ${path.bob.perLap}`;
  }
  return undefined;
}

/** A path ready to play: its arc-length table, and positions and poses by distance or time. */
export class CompiledPath {
  /** Length of the loop, scene units. */
  readonly length: number;
  /** Seconds per lap. */
  readonly lapSeconds: number;
  private readonly up: Vec3;
  /** Cumulative arc length at each sample (SAMPLES_PER_SEGMENT per segment, plus the closing one). */
  private readonly cumulative: Float64Array;

  constructor(readonly path: InstancePath) {
    this.up = normalize(path.up ?? [0, 1, 0]);
    const n = path.points.length * SAMPLES_PER_SEGMENT;
    this.cumulative = new Float64Array(n + 1);
    let previous = this.at(0);
    for (let i = 1; i <= n; i++) {
      const p = this.at(i / SAMPLES_PER_SEGMENT);
      this.cumulative[i] = this.cumulative[i - 1]! + length(sub(p, previous));
      previous = p;
    }
    this.length = this.cumulative[n]!;
    this.lapSeconds = this.length / path.speed;
  }

  /** The curve at parameter u (segment k runs over u in [k, k + 1], from points[k] to points[k + 1]). */
  at(u: number): Vec3 {
    const pts = this.path.points;
    const n = pts.length;
    const k = Math.min(Math.floor(u), n - 1);
    const f = u - k;
    const p1 = pts[k]!, p2 = pts[(k + 1) % n]!;
    if (this.path.curve === 'polyline') return lerp(p1, p2, f);
    const p0 = pts[(k + n - 1) % n]!, p3 = pts[(k + 2) % n]!;
    // Centripetal knots: t_{i+1} = t_i + |P_{i+1} − P_i|^½.
    const t0 = 0, t1 = t0 + Math.sqrt(length(sub(p1, p0))), t2 = t1 + Math.sqrt(length(sub(p2, p1))), t3 = t2 + Math.sqrt(length(sub(p3, p2)));
    const t = t1 + f * (t2 - t1);
    const a1 = lerp(p0, p1, (t - t0) / (t1 - t0));
    const a2 = lerp(p1, p2, (t - t1) / (t2 - t1));
    const a3 = lerp(p2, p3, (t - t2) / (t3 - t2));
    const b1 = lerp(a1, a2, (t - t0) / (t2 - t0));
    const b2 = lerp(a2, a3, (t - t1) / (t3 - t1));
    return lerp(b1, b2, (t - t1) / (t2 - t1));
  }

  /** The curve parameter at arc length s (any real; wraps around the loop). */
  private parameterAt(s: number): number {
    const c = this.cumulative;
    const d = ((s % this.length) + this.length) % this.length;
    let lo = 0, hi = c.length - 1;
    while (hi - lo > 1) {
      const mid = (lo + hi) >> 1;
      if (c[mid]! <= d) lo = mid;
      else hi = mid;
    }
    const span = c[hi]! - c[lo]!;
    return (lo + (span > 0 ? (d - c[lo]!) / span : 0)) / SAMPLES_PER_SEGMENT;
  }

  /** The point at arc length s along the loop (without the bob). */
  positionAt(s: number): Vec3 {
    return this.at(this.parameterAt(s));
  }

  /** Unit direction of motion at arc length s. */
  directionAt(s: number): Vec3 {
    const h = Math.min(1e-3 * this.length, 0.5 * this.cumulative[1]!);
    return normalize(sub(this.positionAt(s + h), this.positionAt(s - h)));
  }

  /** Distance along the loop at time t (not wrapped). */
  distanceAt(t: number): number {
    return (this.path.offset ?? 0) + this.path.speed * t;
  }

  /** The bob's displacement along up at time t. */
  bobAt(t: number): number {
    const bob = this.path.bob;
    if (!bob) return 0;
    return bob.amplitude * Math.sin((2 * Math.PI * bob.perLap * this.distanceAt(t)) / this.length);
  }

  /** World from object at time t: carried to the curve's point, turned to face the motion, bobbing. */
  poseAt(t: number): Mat4 {
    const s = this.distanceAt(t);
    const p = this.positionAt(s);
    const b = this.bobAt(t);
    const up = this.up;
    const position: Vec3 = [p[0] + up[0] * b, p[1] + up[1] * b, p[2] + up[2] * b];
    let frame: Mat4 = IDENTITY;
    if (this.path.faceMotion ?? true) {
      const d = this.directionAt(s);
      const flat = sub(d, [up[0] * dot(d, up), up[1] * dot(d, up), up[2] * dot(d, up)]);
      // Moving along up itself: keep the object unturned rather than divide by zero.
      if (length(flat) > 1e-9) {
        const z = normalize(flat);
        const x = cross(up, z);
        frame = [x[0], x[1], x[2], 0, up[0], up[1], up[2], 0, z[0], z[1], z[2], 0, 0, 0, 0, 1];
      }
    }
    const placed: Mat4 = [...frame.slice(0, 12), position[0], position[1], position[2], 1];
    return this.path.pathFromObject ? multiply(placed, this.path.pathFromObject) : placed;
  }
}

const lerp = (a: Vec3, b: Vec3, f: number): Vec3 => [a[0] + (b[0] - a[0]) * f, a[1] + (b[1] - a[1]) * f, a[2] + (b[2] - a[2]) * f];

/** The scene's paths, checked and compiled; throws LanternError naming the first bad one. */
export function compilePaths(scene: Scene): CompiledPath[] {
  return (scene.dynamics?.paths ?? []).map((path, i) => {
    const problem = pathProblem(scene, path);
    if (problem) throw new LanternError(`scene '${scene.name}': path ${i} ${problem}`);
    return new CompiledPath(path);
  });
}
