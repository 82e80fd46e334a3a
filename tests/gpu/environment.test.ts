/**
 * The environment on the GPU (shaders/scene/environment.wgsl with gpu/pack/environment-pack.ts):
 * lat-long orientation, sampling density against its own pdf (chi-square), the pdf's normalisation,
 * radiance/pdf consistency through irradiance, the sun cone against the closed form, and a constant
 * environment's round trip.
 */
import { describe, expect, it } from 'vitest';
import { readBuffer } from '../../src/gpu/readback.ts';
import { packEnvironment, type PackedEnvironment } from '../../src/gpu/pack/environment-pack.ts';
import { uploadEnvironment } from '../../src/gpu/scene-resources.ts';
import type { Environment } from '../../src/scene/environment.ts';
import { directionFromLatLong } from '../../src/scene/environment.ts';
import { SUN_ANGULAR_RADIUS_DEG } from '../../src/scene/sky.ts';
import type { ComputeKernel } from '../../src/gpu/kernel.ts';
import { outputBuffer, storageBuffer, testKernel } from './compute.ts';
import { testGpu } from './gpu-context.ts';

const SAMPLES_PER_THREAD = 16;
const SAMPLE_GROUPS = 256;
const N = SAMPLES_PER_THREAD * SAMPLE_GROUPS * 64;
/** The midpoint grid in (φ, cos θ) over the sphere: equal solid angle 4π / (GRID_PHI · GRID_Z) per cell. */
const GRID_PHI = 512;
const GRID_Z = 256;

const KERNEL = `
#import lib/random
#import scene/environment
@group(3) @binding(0) var<storage, read> directions_in: array<vec4f>;
@group(3) @binding(1) var<storage, read_write> out_a: array<vec4f>;
@group(3) @binding(2) var<storage, read_write> out_b: array<vec4f>;

@compute @workgroup_size(64)
fn sample_env(@builtin(global_invocation_id) id: vec3u) {
  var rng = rng_seed(id.x, 0u, 777u);
  for (var s = 0u; s < ${SAMPLES_PER_THREAD}u; s++) {
    let k = id.x * ${SAMPLES_PER_THREAD}u + s;
    let e = sample_environment(rng_next_2d(&rng));
    out_a[k] = vec4f(e.direction, e.pdf);
    out_b[k] = vec4f(e.radiance, environment_pdf(e.direction));
  }
}

@compute @workgroup_size(64)
fn sample_sun_cone(@builtin(global_invocation_id) id: vec3u) {
  var rng = rng_seed(id.x, 0u, 4242u);
  for (var s = 0u; s < ${SAMPLES_PER_THREAD}u; s++) {
    let k = id.x * ${SAMPLES_PER_THREAD}u + s;
    let e = sample_sun(rng_next_2d(&rng));
    out_a[k] = vec4f(e.direction, e.pdf);
    out_b[k] = vec4f(sun_radiance(e.direction), sun_pdf(e.direction));
  }
}

// Midpoints of the (φ, cos θ) grid: radiance and pdf for numerical integrals over the sphere.
@compute @workgroup_size(64)
fn grid(@builtin(global_invocation_id) id: vec3u) {
  let k = id.x;
  let z = 1.0 - 2.0 * (f32(k / ${GRID_PHI}u) + 0.5) / f32(${GRID_Z});
  let phi = 6.28318530718 * (f32(k % ${GRID_PHI}u) + 0.5) / f32(${GRID_PHI});
  let r = sqrt(max(0.0, 1.0 - z * z));
  let d = vec3f(r * cos(phi), z, r * sin(phi));
  out_a[k] = vec4f(environment_radiance(d), environment_pdf(d));
  out_b[k] = vec4f(d, 0.0);
}

@compute @workgroup_size(64)
fn probe(@builtin(global_invocation_id) id: vec3u) {
  let d = directions_in[id.x].xyz;
  out_a[id.x] = vec4f(environment_radiance(d), environment_pdf(d));
  out_b[id.x] = vec4f(sun_radiance(d), sun_pdf(d));
}
`;

const kernels = new Map<string, Promise<ComputeKernel>>();
async function kernel(device: GPUDevice, entry: string): Promise<ComputeKernel> {
  let k = kernels.get(entry);
  if (!k) kernels.set(entry, (k = testKernel(device, 'test/environment', KERNEL, entry)));
  return k;
}

/** Runs one entry point over `threads` threads with `count` vec4 outputs in out_a and out_b. */
async function run(env: Environment, entry: string, threads: number, count: number, directions?: Float32Array): Promise<{ a: Float32Array; b: Float32Array; packed: PackedEnvironment }> {
  const { device } = await testGpu();
  const k = await kernel(device, entry);
  const packed = packEnvironment(env);
  const up = await uploadEnvironment(device, packed, 'test');
  const outA = outputBuffer(device, 'out_a', count * 16), outB = outputBuffer(device, 'out_b', count * 16);
  const input = storageBuffer(device, 'directions_in', directions ?? new Float32Array(4));
  const encoder = device.createCommandEncoder();
  const pass = encoder.beginComputePass();
  k.dispatch(pass, { 0: k.bindGroup(0, up.bindings), 3: k.bindGroup(3, { directions_in: input, out_a: outA, out_b: outB }) }, Math.ceil(threads / 64));
  pass.end();
  device.queue.submit([encoder.finish()]);
  const a = new Float32Array(await readBuffer(device, outA));
  const b = new Float32Array(await readBuffer(device, outB));
  for (const buffer of [outA, outB, input]) buffer.destroy();
  up.destroy();
  return { a, b, packed };
}

/** Upper critical value of χ² with k degrees of freedom at tail probability ~1e-4 (Wilson–Hilferty). */
function chiSquareCritical(k: number): number {
  const z = 3.719;
  const a = 2 / (9 * k);
  return k * (1 - a + z * Math.sqrt(a)) ** 3;
}

/** A 16×8 map with strong structure: a hot spot 1000× the rest, a black band, a ramp. */
const W = 16, H = 8;
function structuredMap(): Float32Array {
  const rgb = new Float32Array(W * H * 3);
  for (let j = 0; j < H; j++) {
    for (let i = 0; i < W; i++) {
      const o = (j * W + i) * 3;
      const v = j === 6 ? 0 : i === 3 && j === 2 ? 1000 : 0.1 + i * 0.2;
      rgb[o] = v;
      rgb[o + 1] = v * (j % 2 ? 0.5 : 1);
      rgb[o + 2] = v * 0.25;
    }
  }
  return rgb;
}

/**
 * Texel probabilities recomputed here, independently of the packer: weight = the largest luminance in
 * the 3×3 neighbourhood (columns wrap, rows clamp), times the texel's solid angle.
 */
function expectedTexelProbabilities(rgb: Float32Array, w: number, h: number, neighbourhood = true): Float64Array {
  const lum = (i: number, j: number) => {
    const o = (Math.min(h - 1, Math.max(0, j)) * w + ((i + w) % w)) * 3;
    return 0.2126 * rgb[o]! + 0.7152 * rgb[o + 1]! + 0.0722 * rgb[o + 2]!;
  };
  const p = new Float64Array(w * h);
  let total = 0;
  for (let j = 0; j < h; j++) {
    const omega = ((2 * Math.PI) / w) * (Math.cos((j * Math.PI) / h) - Math.cos(((j + 1) * Math.PI) / h));
    for (let i = 0; i < w; i++) {
      let m = 0;
      const reach = neighbourhood ? 1 : 0;
      for (let dj = -reach; dj <= reach; dj++) for (let di = -reach; di <= reach; di++) m = Math.max(m, lum(i + di, j + dj));
      p[j * w + i] = m * omega;
      total += m * omega;
    }
  }
  return p.map((v) => v / total);
}

/** Texel and sub-texel bin (2 × 2, halves in φ and in cos θ) of a map-space direction. */
function texelOf(d: [number, number, number], w: number, h: number): { i: number; j: number; sub: number } {
  let u = 0.5 + Math.atan2(d[0], -d[2]) / (2 * Math.PI);
  u -= Math.floor(u);
  const theta = Math.acos(Math.min(1, Math.max(-1, d[1])));
  const i = Math.min(w - 1, Math.floor(u * w));
  const j = Math.min(h - 1, Math.floor((theta / Math.PI) * h));
  const fu = u * w - i;
  const zTop = Math.cos((j * Math.PI) / h), zBottom = Math.cos(((j + 1) * Math.PI) / h);
  const fz = (zTop - d[1]) / (zTop - zBottom);
  return { i, j, sub: (fu < 0.5 ? 0 : 1) + (fz < 0.5 ? 0 : 2) };
}

describe('environment on the GPU', () => {
  it('lat-long orientation: image centre = -z, u = 0.75 = +x, top row = +y; rotation turns +z toward +x', async () => {
    // 4×2 map, a distinct colour per texel: texel (i, j) has radiance (i + 1, j + 1, 0).
    const rgb = new Float32Array(4 * 2 * 3);
    for (let j = 0; j < 2; j++) for (let i = 0; i < 4; i++) rgb.set([i + 1, j + 1, 0], (j * 4 + i) * 3);
    const image = { name: 'quadrants', width: 4, height: 2, rgb };
    // Texel centres: u = (i + 0.5) / 4, v = 0.25 (upper row) — look exactly at them so bilinear returns the texel.
    const dirs = new Float32Array(4 * 4);
    for (let i = 0; i < 4; i++) dirs.set([...directionFromLatLong((i + 0.5) / 4, 0.25), 0], i * 4);
    const plain = await run({ kind: 'map', image, rotationDeg: 0, intensity: 2 }, 'probe', 4, 4, dirs);
    for (let i = 0; i < 4; i++) {
      expect(plain.a[i * 4]).toBeCloseTo(2 * (i + 1), 3);
      expect(plain.a[i * 4 + 1]).toBeCloseTo(2 * 1, 3);
    }
    // The convention itself: u = 0.5 looks down -z, u = 0.75 toward +x, v < 0.5 is above the horizon.
    const centre = directionFromLatLong(0.5, 0.5), right = directionFromLatLong(0.75, 0.5);
    expect(centre[2]).toBeCloseTo(-1, 12);
    expect(right[0]).toBeCloseTo(1, 12);
    expect(directionFromLatLong(0.3, 0.25)[1]).toBeGreaterThan(0);
    // Rotated by 90°: what the map has at direction d appears at world direction R_y(90°) d, (x, z) → (z, -x).
    const rotated = await run({ kind: 'map', image, rotationDeg: 90, intensity: 2 }, 'probe', 4, 4,
      dirs.map((v, k) => (k % 4 === 0 ? dirs[k + 2]! : k % 4 === 2 ? -dirs[k - 2]! : v)));
    for (let i = 0; i < 4; i++) expect(rotated.a[i * 4]).toBeCloseTo(2 * (i + 1), 3);
  });

  it('sample_environment passes chi-square against the texel probabilities; its pdf is environment_pdf and w/Σ', async () => {
    const rgb = structuredMap();
    const { a, b } = await run({ kind: 'map', image: { name: 'structured', width: W, height: H, rgb }, rotationDeg: 0, intensity: 1 }, 'sample_env', SAMPLE_GROUPS * 64, N);
    const p = expectedTexelProbabilities(rgb, W, H);
    const counts = new Float64Array(W * H * 4);
    let pdfMismatch = 0, analyticMismatch = 0;
    for (let k = 0; k < N; k++) {
      const d: [number, number, number] = [a[k * 4]!, a[k * 4 + 1]!, a[k * 4 + 2]!];
      const pdf = a[k * 4 + 3]!;
      const { i, j, sub } = texelOf(d, W, H);
      counts[(j * W + i) * 4 + sub]!++;
      if (Math.abs(b[k * 4 + 3]! - pdf) > 1e-3 * pdf) pdfMismatch++;
      const omega = ((2 * Math.PI) / W) * (Math.cos((j * Math.PI) / H) - Math.cos(((j + 1) * Math.PI) / H));
      if (Math.abs(pdf - p[j * W + i]! / omega) > 2e-3 * pdf) analyticMismatch++;
    }
    // Directions on a texel's edge may round into the neighbour: a handful, not a pattern.
    expect(pdfMismatch).toBeLessThan(N * 1e-4);
    expect(analyticMismatch).toBeLessThan(N * 1e-4);
    // Chi-square over sub-texel bins (each ¼ of its texel's probability); bins expecting < 5 pooled.
    let chi2 = 0, bins = 0, pooledObserved = 0, pooledExpected = 0;
    for (let t = 0; t < W * H; t++) {
      for (let s = 0; s < 4; s++) {
        const expected = (N * p[t]!) / 4;
        const observed = counts[t * 4 + s]!;
        if (expected === 0) expect(observed).toBe(0);
        else if (expected < 5) {
          pooledObserved += observed;
          pooledExpected += expected;
        } else {
          chi2 += (observed - expected) ** 2 / expected;
          bins++;
        }
      }
    }
    if (pooledExpected > 0) {
      chi2 += (pooledObserved - pooledExpected) ** 2 / pooledExpected;
      bins++;
    }
    expect(bins).toBeGreaterThan(100);
    expect(chi2).toBeLessThan(chiSquareCritical(bins - 1));

    // The test has the power to fail: the same counts against texel probabilities without the 3×3
    // maximum (plain luminance × Ω) are rejected.
    const plainP = expectedTexelProbabilities(rgb, W, H, false);
    let wrong = 0;
    for (let t = 0; t < W * H; t++) {
      const expected = N * plainP[t]!;
      const observed = counts[t * 4]! + counts[t * 4 + 1]! + counts[t * 4 + 2]! + counts[t * 4 + 3]!;
      if (expected >= 5) wrong += (observed - expected) ** 2 / expected;
    }
    expect(wrong).toBeGreaterThan(chiSquareCritical(W * H - 1));
  });

  it('environment_pdf integrates to 1 over the sphere, and the MC irradiance equals the numerical integral', async () => {
    // A smooth map with a bright lobe, rotated and scaled: sample, radiance and pdf must agree on both.
    const w = 64, h = 32;
    const rgb = new Float32Array(w * h * 3);
    for (let j = 0; j < h; j++) {
      for (let i = 0; i < w; i++) {
        const d = directionFromLatLong((i + 0.5) / w, (j + 0.5) / h);
        const lobe = 50 * Math.max(0, d[0] * 0.6 + d[1] * 0.8) ** 16;
        rgb.set([0.2 + lobe, 0.3 + 0.5 * lobe, 0.4 + (j < h / 2 ? 0.3 : 0)], (j * w + i) * 3);
      }
    }
    const env: Environment = { kind: 'map', image: { name: 'lobe', width: w, height: h, rgb }, rotationDeg: 30, intensity: 1.5 };
    const grid = await run(env, 'grid', GRID_PHI * GRID_Z, GRID_PHI * GRID_Z);
    const cell = (4 * Math.PI) / (GRID_PHI * GRID_Z);
    const normals: [number, number, number][] = [[0, 1, 0], [0.6, 0.8, 0], [0, -0.6, 0.8]];
    let pdfIntegral = 0;
    const direct = normals.map(() => 0);
    for (let k = 0; k < GRID_PHI * GRID_Z; k++) {
      pdfIntegral += grid.a[k * 4 + 3]! * cell;
      const l = 0.2126 * grid.a[k * 4]! + 0.7152 * grid.a[k * 4 + 1]! + 0.0722 * grid.a[k * 4 + 2]!;
      normals.forEach((n, m) => {
        const c = n[0] * grid.b[k * 4]! + n[1] * grid.b[k * 4 + 1]! + n[2] * grid.b[k * 4 + 2]!;
        direct[m]! += l * Math.max(0, c) * cell;
      });
    }
    expect(pdfIntegral).toBeGreaterThan(0.999);
    expect(pdfIntegral).toBeLessThan(1.001);

    const samples = await run(env, 'sample_env', SAMPLE_GROUPS * 64, N);
    normals.forEach((n, m) => {
      let sum = 0, sum2 = 0;
      for (let k = 0; k < N; k++) {
        const s = samples.a, r = samples.b;
        const c = Math.max(0, n[0] * s[k * 4]! + n[1] * s[k * 4 + 1]! + n[2] * s[k * 4 + 2]!);
        const l = 0.2126 * r[k * 4]! + 0.7152 * r[k * 4 + 1]! + 0.0722 * r[k * 4 + 2]!;
        const f = (l * c) / s[k * 4 + 3]!;
        sum += f;
        sum2 += f * f;
      }
      const mean = sum / N;
      const sigma = Math.sqrt((sum2 / N - mean * mean) / N);
      expect(Math.abs(mean - direct[m]!)).toBeLessThan(5 * sigma + 2e-3 * direct[m]!);
    });
  });

  it('sun: E = mean(L cos / pdf) on a horizontal plane equals L_sun π sin²r sin(elevation)', async () => {
    const elevation = 35;
    const env: Environment = { kind: 'sky', sunElevationDeg: elevation, sunAzimuthDeg: 120, turbidity: 3, groundAlbedo: 0.2, intensity: 1e-4 };
    const { a, b, packed } = await run(env, 'sample_sun_cone', SAMPLE_GROUPS * 64, N);
    expect(packed.hasSun).toBe(true);
    let sum = 0, outside = 0, pdfMismatch = 0, lSun = 0;
    for (let k = 0; k < N; k++) {
      const radiance = b[k * 4 + 1]!; // green
      if (radiance === 0) outside++;
      lSun = Math.max(lSun, radiance);
      if (b[k * 4 + 3]! !== a[k * 4 + 3]!) pdfMismatch++;
      sum += (radiance * Math.max(0, a[k * 4 + 1]!)) / a[k * 4 + 3]!;
    }
    expect(outside).toBe(0);
    expect(lSun).toBeGreaterThan(0);
    expect(pdfMismatch).toBe(0);
    const r = (SUN_ANGULAR_RADIUS_DEG * Math.PI) / 180;
    const closedForm = lSun * Math.PI * Math.sin(r) ** 2 * Math.sin((elevation * Math.PI) / 180);
    expect(sum / N / closedForm).toBeGreaterThan(0.999);
    expect(sum / N / closedForm).toBeLessThan(1.001);
  });

  it('constant: radiance is the constant everywhere, pdf 1/4π for lookups and samples; no sun', async () => {
    const env: Environment = { kind: 'constant', radiance: [0.25, 0.5, 2] };
    const { a, b } = await run(env, 'sample_env', SAMPLE_GROUPS * 64, N);
    const quarterPi = 1 / (4 * Math.PI);
    let worstPdf = 0, worstRadiance = 0;
    const mean = [0, 0, 0];
    for (let k = 0; k < N; k++) {
      worstPdf = Math.max(worstPdf, Math.abs(a[k * 4 + 3]! / quarterPi - 1), Math.abs(b[k * 4 + 3]! / quarterPi - 1));
      worstRadiance = Math.max(worstRadiance, Math.abs(b[k * 4]! - 0.25), Math.abs(b[k * 4 + 1]! - 0.5), Math.abs(b[k * 4 + 2]! - 2));
      for (let c = 0; c < 3; c++) mean[c]! += a[k * 4 + c]! / N;
    }
    expect(worstPdf).toBeLessThan(1e-4);
    expect(worstRadiance).toBeLessThan(1e-6);
    // Uniform on the sphere: the mean direction is 0 (σ per component = 1/√(3N)).
    for (const m of mean) expect(Math.abs(m)).toBeLessThan(5 / Math.sqrt(3 * N));
    const probe = await run(env, 'probe', 1, 1, new Float32Array([0, 1, 0, 0]));
    expect(Array.from(probe.b)).toEqual([0, 0, 0, 0]);
  });
});
