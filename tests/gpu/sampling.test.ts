/**
 * The GPU samplers themselves (lib/sampling.wgsl, lib/random.wgsl) against their target
 * distributions, with a chi-square goodness-of-fit test over equal-probability bins.
 */
import { describe, expect, it } from 'vitest';
import { testGpu } from './gpu-context.ts';
import { outputBuffer, runOnce, testKernel } from './compute.ts';

const SAMPLES_PER_THREAD = 64;
const THREADS = 64 * 256;
const N = SAMPLES_PER_THREAD * THREADS;

/** Upper critical value of χ² with k degrees of freedom at tail probability ~1e-4 (Wilson–Hilferty). */
function chiSquareCritical(k: number): number {
  const z = 3.719; // standard normal quantile for 1e-4
  const a = 2 / (9 * k);
  return k * (1 - a + z * Math.sqrt(a)) ** 3;
}

// Samples directions around a normal n (one of several, per workgroup) and writes them in n's frame
// (z along n) as computed from the world-space result, so the test sees what the renderer uses:
// orthonormal_basis(n) * sample_cosine_hemisphere(u).
const COSINE_KERNEL = `
#import lib/random
#import lib/sampling
@group(3) @binding(0) var<storage, read_write> directions: array<vec4f>;
@compute @workgroup_size(64)
fn sample_directions(@builtin(global_invocation_id) id: vec3u, @builtin(workgroup_id) group: vec3u) {
  let normals = array<vec3f, 4>(vec3f(0.0, 0.0, 1.0), normalize(vec3f(1.0, -2.0, 0.5)), vec3f(0.0, 0.0, -1.0), normalize(vec3f(-0.3, 0.9, -0.1)));
  let n = normals[group.x % 4u];
  let basis = orthonormal_basis(n);
  var rng = rng_seed(id.x, 0u, 12345u);
  for (var s = 0u; s < ${SAMPLES_PER_THREAD}u; s++) {
    let w = basis * sample_cosine_hemisphere(rng_next_2d(&rng));
    // Back into n's frame with the transpose (basis is orthonormal).
    let local = vec3f(dot(w, basis[0]), dot(w, basis[1]), dot(w, basis[2]));
    directions[id.x * ${SAMPLES_PER_THREAD}u + s] = vec4f(local, dot(w, n));
  }
}`;

describe('cosine-weighted hemisphere sampling on the GPU', () => {
  it('passes a chi-square test over equal-probability (cos²θ, φ) bins, around several normals', async () => {
    const { device } = await testGpu();
    const kernel = await testKernel(device, 'test/cosine', COSINE_KERNEL, 'sample_directions');
    const out = outputBuffer(device, 'directions', N * 16);
    const data = new Float32Array(await runOnce(device, kernel, { 3: kernel.bindGroup(3, { directions: out }) }, [THREADS / 64], out));
    out.destroy();

    // With density cos θ / π, cos²θ is uniform on [0, 1] and φ uniform on [0, 2π): K×M equal bins.
    const K = 16, M = 16;
    const counts = new Float64Array(K * M);
    let worstLength = 0;
    let below = 0;
    for (let i = 0; i < N; i++) {
      const x = data[i * 4]!, y = data[i * 4 + 1]!, z = data[i * 4 + 2]!, cosN = data[i * 4 + 3]!;
      worstLength = Math.max(worstLength, Math.abs(Math.hypot(x, y, z) - 1));
      // Directions at the horizon may round to a hair below it; anything clearly below is a bug.
      if (cosN < -1e-6 || z < -1e-6) below++;
      const k = Math.min(K - 1, Math.floor(Math.max(0, z) ** 2 * K));
      const phi = Math.atan2(y, x) + Math.PI;
      const m = Math.min(M - 1, Math.floor((phi / (2 * Math.PI)) * M));
      counts[k * M + m]!++;
    }
    expect(below).toBe(0);
    // WGSL allows sin and cos an absolute error of 2^-11: unit length to that order.
    expect(worstLength).toBeLessThan(1e-3);
    const expected = N / (K * M);
    let chi2 = 0;
    for (const c of counts) chi2 += (c - expected) ** 2 / expected;
    expect(chi2).toBeLessThan(chiSquareCritical(K * M - 1));
  });

  it('the chi-square test rejects a uniform hemisphere (it has the power to fail)', () => {
    // Same binning applied to uniformly distributed directions (cos θ uniform): must fail clearly.
    let seed = 1;
    const rand = () => ((seed = (Math.imul(seed, 1664525) + 1013904223) >>> 0) / 2 ** 32);
    const K = 16, M = 16, n = 200_000;
    const counts = new Float64Array(K * M);
    for (let i = 0; i < n; i++) {
      const z = rand();
      const k = Math.min(K - 1, Math.floor(z * z * K));
      const m = Math.min(M - 1, Math.floor(rand() * M));
      counts[k * M + m]!++;
    }
    const expected = n / (K * M);
    let chi2 = 0;
    for (const c of counts) chi2 += (c - expected) ** 2 / expected;
    expect(chi2).toBeGreaterThan(chiSquareCritical(K * M - 1));
  });
});
