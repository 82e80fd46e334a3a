/**
 * Deterministic triangle soups for the BVH tests (test-only; nothing in the renderer imports this).
 * Each returns a flat position array, 9 floats per triangle.
 */
import { fromTrs, IDENTITY, translation } from '../math/mat4.ts';
import { seededRandom } from '../math/seeded-random.ts';
import { diffuse, type Mesh, type Scene } from '../scene/types.ts';
import type { Vec3 } from '../math/vec3.ts';
import type { Ray } from './ray.ts';

/** The seeded PRNG the BVH tests share (math/seeded-random.ts). */
export const makeRandom = seededRandom;

/** Random triangles in [-10, 10]³: mostly small, some long slivers, scaled by `scale`. */
export function randomSoup(count: number, seed: number, scale = 1): Float32Array {
  const rnd = makeRandom(seed);
  const out = new Float32Array(count * 9);
  for (let t = 0; t < count; t++) {
    const cx = (rnd() * 20 - 10) * scale, cy = (rnd() * 20 - 10) * scale, cz = (rnd() * 20 - 10) * scale;
    const size = (t % 17 === 0 ? 8 : 0.6) * scale;
    for (let v = 0; v < 3; v++) {
      out[t * 9 + v * 3] = cx + (rnd() - 0.5) * size;
      out[t * 9 + v * 3 + 1] = cy + (rnd() - 0.5) * size;
      out[t * 9 + v * 3 + 2] = cz + (rnd() - 0.5) * size;
    }
  }
  return out;
}

/** An n×n grid of unit quads in the plane z = 0 (two triangles each): every box is flat in z. */
export function quadGrid(n: number): Float32Array {
  const out: number[] = [];
  for (let i = 0; i < n; i++) {
    for (let j = 0; j < n; j++) {
      out.push(i, j, 0, i + 1, j, 0, i + 1, j + 1, 0);
      out.push(i, j, 0, i + 1, j + 1, 0, i, j + 1, 0);
    }
  }
  return new Float32Array(out);
}

/**
 * A UV sphere of radius r: `rings` latitude bands × `segments` longitude steps, two triangles per
 * cell, including the zero-area triangles a naive tessellation leaves at the poles.
 */
export function uvSphere(rings: number, segments: number, r = 1): Float32Array {
  const point = (i: number, j: number): number[] => {
    const theta = (Math.PI * i) / rings, phi = (2 * Math.PI * j) / segments;
    return [r * Math.sin(theta) * Math.cos(phi), r * Math.sin(theta) * Math.sin(phi), r * Math.cos(theta)];
  };
  const out: number[] = [];
  for (let i = 0; i < rings; i++) {
    for (let j = 0; j < segments; j++) {
      out.push(...point(i, j), ...point(i + 1, j), ...point(i + 1, j + 1));
      out.push(...point(i, j), ...point(i + 1, j + 1), ...point(i, j + 1));
    }
  }
  return new Float32Array(out);
}

/**
 * The awkward cases: many exact copies of one triangle (all centroids equal), zero-area points and
 * slivers, and a few ordinary triangles so that not everything is degenerate.
 */
export function degenerateSoup(): Float32Array {
  const out: number[] = [];
  for (let k = 0; k < 300; k++) out.push(0, 0, 0, 1, 0, 0, 0, 1, 0); // coincident
  for (let k = 0; k < 100; k++) out.push(2, 2, 2, 2, 2, 2, 2, 2, 2); // points
  for (let k = 0; k < 100; k++) out.push(k, 0, 5, k + 0.5, 0, 5, k + 1, 0, 5); // collinear slivers
  for (let k = 0; k < 20; k++) out.push(k, 3, -1, k + 1, 3, -1, k, 4, 1); // ordinary
  return new Float32Array(out);
}

/** `count` copies of one zero-area triangle at a single point: the whole scene has no extent. */
export function pointCloud(count: number): Float32Array {
  return new Float32Array(count * 9).fill(1.5);
}

/** A mesh of the triangles in `positions` (9 floats each), one material. */
function meshOf(name: string, positions: Float32Array): Mesh {
  const n = positions.length / 9;
  return { name, positions, indices: Uint32Array.from({ length: n * 3 }, (_, i) => i), materialIds: new Uint32Array(n) };
}

const soupMesh = (name: string, count: number, seed: number, scale: number): Mesh => meshOf(name, randomSoup(count, seed, scale));

/** A one-instance scene of the triangles in `positions`, grey diffuse, seen from `camera`. */
export function soupScene(name: string, positions: Float32Array, camera: Scene['camera']): Scene {
  return { name, meshes: [meshOf(name, positions)], instances: [{ id: 0, mesh: 0, worldFromObject: IDENTITY }], materials: [diffuse('grey', [0.5, 0.5, 0.5])], camera };
}

/** A static soup, and moving instances of two meshes: shared, rotated, non-uniformly scaled, mirrored; plus spheres. */
export function movingTestScene(): Scene {
  const rock = soupMesh('rock', 60, 3, 0.1);
  const ball: Mesh = { name: 'balls', positions: new Float32Array(), indices: new Uint32Array(), materialIds: new Uint32Array(), spheres: { centers: new Float32Array([0, 0, 0, 0.5, 0.2, 0]), radii: new Float32Array([0.3, 0.15]), materialIds: new Uint32Array([0, 0]) } };
  const q = (x: number, y: number, z: number) => {
    const w = Math.sqrt(Math.max(0, 1 - x * x - y * y - z * z));
    return [x, y, z, w] as const;
  };
  return {
    name: 'moving test',
    meshes: [soupMesh('world', 400, 1, 1), rock, ball],
    instances: [
      { id: 10, mesh: 0, worldFromObject: translation([0, 0, 0]) },
      { id: 11, mesh: 1, worldFromObject: fromTrs([2, 1, 0], q(0.3, 0.1, 0.2), [1, 2, 0.5]), moves: true },
      { id: 12, mesh: 1, worldFromObject: fromTrs([-3, 0, 2], q(0, 0.6, 0), [-1.5, 1.5, 1.5]), moves: true },
      { id: 13, mesh: 2, worldFromObject: fromTrs([0, -2, -3], q(0.1, 0, 0.3), [2, 2, 2]), moves: true },
      { id: 14, mesh: 1, worldFromObject: translation([5, 5, 5]) },
    ],
    materials: [diffuse('grey', [0.5, 0.5, 0.5])],
    camera: { position: [0, 0, 20], forward: [0, 0, -1], up: [0, 1, 0], vfovDegrees: 60 },
  };
}

/**
 * Rays for traversal oracles over a triangle soup (9 floats a triangle): origins in the scene's box
 * grown by `margin` times its largest side on every side (some inside, some outside, off the plane
 * of a flat scene). By default of every kind: axis-aligned (exact zero components, -0 included),
 * random, and aimed at a point strictly inside a random triangle (so that many hit), some of those
 * scaled by 1e-3 (t in other units), and every seventh with a short (tMin, tMax). `aimed`: aimed rays
 * only, no interval.
 */
export function testRays(positions: Float32Array, count: number, seed: number, options: { readonly aimed?: boolean; readonly margin?: number } = {}): Ray[] {
  const rnd = makeRandom(seed);
  const n = positions.length / 9;
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < positions.length; i++) {
    lo[i % 3] = Math.min(lo[i % 3]!, positions[i]!);
    hi[i % 3] = Math.max(hi[i % 3]!, positions[i]!);
  }
  const margin = Math.max(hi[0]! - lo[0]!, hi[1]! - lo[1]!, hi[2]! - lo[2]!) * (options.margin ?? 0.5);
  const rays: Ray[] = [];
  for (let k = 0; k < count; k++) {
    const origin = [0, 1, 2].map((a) => lo[a]! - margin + (hi[a]! - lo[a]! + 2 * margin) * rnd()) as unknown as Vec3;
    const kind = options.aimed ? 2 : k % 4;
    let direction: Vec3;
    if (kind === 0) {
      const axis = Math.floor(rnd() * 3), sign = rnd() < 0.5 ? -1 : 1;
      const d = [rnd() < 0.5 ? 0 : -0, rnd() < 0.5 ? 0 : -0, rnd() < 0.5 ? 0 : -0];
      d[axis] = sign;
      direction = d as unknown as Vec3;
    } else if (kind === 1) {
      direction = [rnd() - 0.5, rnd() - 0.5, rnd() - 0.5];
    } else {
      const t = Math.floor(rnd() * n) * 9;
      let u = rnd(), v = rnd();
      if (u + v > 1) [u, v] = [1 - u, 1 - v];
      const target = [0, 1, 2].map((a) => positions[t + a]! * (1 - u - v) + positions[t + 3 + a]! * u + positions[t + 6 + a]! * v);
      direction = [target[0]! - origin[0], target[1]! - origin[1], target[2]! - origin[2]];
      if (kind === 3) direction = [direction[0] * 1e-3, direction[1] * 1e-3, direction[2] * 1e-3];
    }
    rays.push(!options.aimed && k % 7 === 0 ? { origin, direction, tMin: rnd() * 0.5, tMax: 0.5 + rnd() * 2 } : { origin, direction });
  }
  return rays;
}

