/**
 * Deterministic triangle soups for the BVH tests (test-only; nothing in the renderer imports this).
 * Each returns a flat position array, 9 floats per triangle.
 */
import { seededRandom } from '../math/seeded-random.ts';

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
