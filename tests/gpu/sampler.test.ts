/**
 * The Sobol sampler of lib/random.wgsl (sampler_seed with SAMPLER_SOBOL) drawn through the call-site
 * API (rng_next_2d), against the properties it claims: each pixel's aligned blocks of 2^k samples
 * are (0,k,2)-nets in every dimension pair, so are the pixels of an aligned 2^a × 2^a tile at one
 * sample, the values are uniform over dimensions 0–7, distinct pixels' sequences differ and are
 * uncorrelated on the whole, and the PCG stream ('random') is still what rng_seed gives.
 */
import { describe, expect, it } from 'vitest';
import { testGpu } from './gpu-context.ts';
import { outputBuffer, runOnce, testKernel } from './compute.ts';

const W = 32, H = 32;
const SAMPLES = 256;
const PAIRS = 4;

const drawn = new Map<string, Promise<Float32Array>>();

/** Points [pixel][sample][pair] of a W × H image, samples first..first+SAMPLES-1, as (x, y) floats. */
function draw(sampler: number, first: number, seed: number, size = { width: W, height: H, samples: SAMPLES }): Promise<Float32Array> {
  const key = JSON.stringify([sampler, first, seed, size]);
  let points = drawn.get(key);
  if (!points) drawn.set(key, (points = drawPoints(sampler, first, seed, size)));
  return points;
}

/** `compiled`: lib/random.wgsl's SAMPLER constant for the kernel (default: chosen per stream, by `sampler`). */
async function drawPoints(sampler: number, first: number, seed: number, size = { width: W, height: H, samples: SAMPLES }, compiled?: number): Promise<Float32Array> {
  const { width, height, samples } = size;
  const { device } = await testGpu();
  const code = `
#import lib/random
@group(3) @binding(0) var<storage, read_write> points: array<vec2f>;
@compute @workgroup_size(64)
fn draw(@builtin(global_invocation_id) id: vec3u) {
  let pixel_index = id.x / ${samples}u;
  let s = id.x % ${samples}u;
  let pixel = vec2u(pixel_index % ${width}u, pixel_index / ${width}u);
  var rng = sampler_seed(${sampler}u, pixel, vec2u(${width}u, ${height}u), ${first}u + s, ${seed}u);
  for (var d = 0u; d < ${PAIRS}u; d++) {
    // rng_next_f32 draws a whole pair too: mix both calls so that the test sees the pairs stay aligned.
    if (d == 2u) {
      points[id.x * ${PAIRS}u + d] = vec2f(rng_next_f32(&rng), 0.0);
    } else {
      points[id.x * ${PAIRS}u + d] = rng_next_2d(&rng);
    }
  }
}`;
  const kernel = await testKernel(device, `test/sampler-${sampler}-${first}-${seed}-${width}x${height}x${samples}`, code, 'draw', compiled === undefined ? undefined : { SAMPLER: compiled });
  const n = width * height * samples;
  const out = outputBuffer(device, 'points', n * PAIRS * 8);
  const data = new Float32Array(await runOnce(device, kernel, { 3: kernel.bindGroup(3, { points: out }) }, [n / 64], out));
  out.destroy();
  return data;
}

const at = (p: Float32Array, pixel: number, s: number, d: number): [number, number] => {
  const i = ((pixel * SAMPLES + s) * PAIRS + d) * 2;
  return [p[i]!, p[i + 1]!];
};

/** Whether these 2^m points hold one point in every elementary interval of every shape 2^-a × 2^-(m-a). */
function isNet(points: readonly (readonly [number, number])[]): boolean {
  const m = Math.log2(points.length);
  for (let a = 0; a <= m; a++) {
    const seen = new Set<number>();
    for (const [x, y] of points) seen.add(Math.floor(x * 2 ** a) * 2 ** (m - a) + Math.floor(y * 2 ** (m - a)));
    if (seen.size !== points.length) return false;
  }
  return true;
}

/** Upper critical value of χ² with k degrees of freedom at tail probability ~1e-4 (Wilson–Hilferty). */
function chiSquareCritical(k: number): number {
  const a = 2 / (9 * k);
  return k * (1 - a + 3.719 * Math.sqrt(a)) ** 3;
}

function chiSquare(counts: ArrayLike<number>, total: number): number {
  const expected = total / counts.length;
  let chi2 = 0;
  for (let i = 0; i < counts.length; i++) chi2 += (counts[i]! - expected) ** 2 / expected;
  return chi2;
}

const SOBOL = 1, RANDOM = 0;

/** permute4's Fisher–Yates shuffle of (0 1 2 3) with p's factorial-base digits as the choices: entry `digit` of permutation p. */
function shuffled(p: number, digit: number): number {
  const items = [0, 1, 2, 3];
  let r = p;
  for (let i = 3; i > 0; i--) {
    const j = r % (i + 1);
    r = Math.floor(r / (i + 1));
    [items[i], items[j]] = [items[j]!, items[i]!];
  }
  return items[digit]!;
}

describe('the Sobol sampler (lib/random.wgsl)', () => {
  it('computes the second Sobol dimension as the direction-number loop does, for every index tried', async () => {
    const { device } = await testGpu();
    const n = 4096;
    // Small indices, then 32-bit ones from a fixed LCG (the scrambled indices the sampler uses are full words).
    const indices = new Uint32Array(n);
    let state = 12345;
    for (let k = 0; k < n; k++) {
      state = (Math.imul(state, 1664525) + 1013904223) >>> 0;
      indices[k] = k < 1024 ? k : state;
    }
    const code = `
#import lib/random
@group(3) @binding(0) var<storage, read_write> values: array<vec2u>;
@compute @workgroup_size(64)
fn sobol(@builtin(global_invocation_id) id: vec3u) {
  values[id.x] = sobol_2d(values[id.x].x);
}`;
    const kernel = await testKernel(device, 'test/sobol-2d', code, 'sobol');
    const buffer = device.createBuffer({ label: 'values', size: n * 8, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC | GPUBufferUsage.COPY_DST });
    const input = new Uint32Array(2 * n);
    for (let k = 0; k < n; k++) input[2 * k] = indices[k]!;
    device.queue.writeBuffer(buffer, 0, input);
    const out = new Uint32Array(await runOnce(device, kernel, { 3: kernel.bindGroup(3, { values: buffer }) }, [n / 64], buffer));
    buffer.destroy();
    const reverse = (x: number) => parseInt(x.toString(2).padStart(32, '0').split('').reverse().join(''), 2);
    for (let k = 0; k < n; k++) {
      let y = 0, v = 0x80000000, bits = indices[k]!;
      for (; bits !== 0; bits >>>= 1, v = (v ^ (v >>> 1)) >>> 0) if (bits & 1) y = (y ^ v) >>> 0;
      expect([out[2 * k], out[2 * k + 1]]).toEqual([reverse(indices[k]!), y]);
    }
  });

  it('tabulates the 24 permutations of the quadtree children as the Fisher–Yates shuffle makes them, all distinct', async () => {
    const { device } = await testGpu();
    const code = `
#import lib/random
@group(3) @binding(0) var<storage, read_write> values: array<u32>;
@compute @workgroup_size(96)
fn permutations(@builtin(local_invocation_index) i: u32) {
  values[i] = permute4(i % 4u, i / 4u);
}`;
    const kernel = await testKernel(device, 'test/permute4', code, 'permutations');
    const out = outputBuffer(device, 'values', 96 * 4);
    const values = new Uint32Array(await runOnce(device, kernel, { 3: kernel.bindGroup(3, { values: out }) }, [1], out));
    out.destroy();
    const expected = Array.from({ length: 96 }, (_, i) => shuffled(Math.floor(i / 4), i % 4));
    expect(Array.from(values)).toEqual(expected);
    expect(new Set(Array.from({ length: 24 }, (_, p) => Array.from(values.subarray(4 * p, 4 * p + 4)).join())).size).toBe(24);
  });

  it('draws what the stream asks for where a kernel chooses per stream, and the compiled-in sampler where it is compiled for one', async () => {
    const size = { width: 8, height: 8, samples: 64 };
    const [perStreamSobol, perStreamRandom, compiledSobol, compiledRandom] = await Promise.all([
      drawPoints(SOBOL, 64, 5, size), drawPoints(RANDOM, 64, 5, size),
      // The stream asks for the other sampler: the kernel's own wins.
      drawPoints(RANDOM, 64, 5, size, SOBOL), drawPoints(SOBOL, 64, 5, size, RANDOM),
    ]);
    expect(Array.from(compiledSobol)).toEqual(Array.from(perStreamSobol));
    expect(Array.from(compiledRandom)).toEqual(Array.from(perStreamRandom));
    expect(Array.from(perStreamSobol)).not.toEqual(Array.from(perStreamRandom));
  });

  it("stratifies each pixel's samples: aligned blocks of 2^k are (0,k,2)-nets in every pair, across frames' indices too", async () => {
    // first = 5120: the blocks are aligned in the index, not to the start of the draw.
    const first = 1024 * 5;
    const p = await draw(SOBOL, first, 7);
    for (const pixel of [0, 1, W + 1, 17 * W + 9, W * H - 1]) {
      for (let d = 0; d < PAIRS; d++) {
        if (d === 2) continue; // rng_next_f32 keeps x only
        for (const k of [1, 2, 4, 6, 8]) {
          for (let start = 0; start + 2 ** k <= SAMPLES; start += 2 ** k) {
            const block = Array.from({ length: 2 ** k }, (_, s) => at(p, pixel, start + s, d));
            expect(isNet(block), `pixel ${pixel}, pair ${d}, samples [${start}, ${start + 2 ** k})`).toBe(true);
          }
        }
      }
    }
    // The net test has the power to fail: PCG points are almost never a (0,6,2)-net.
    const white = await draw(RANDOM, first, 7);
    const block = Array.from({ length: 64 }, (_, s) => at(white, 0, s, 0));
    expect(isNet(block)).toBe(false);
  });

  it("stratifies neighbouring pixels at one sample: an aligned 2^a × 2^a tile is a (0,2a,2)-net in every pair", async () => {
    const p = await draw(SOBOL, 0, 3);
    for (const s of [0, 1, 5, 100]) {
      for (let d = 0; d < PAIRS; d++) {
        if (d === 2) continue;
        for (const a of [1, 2, 3]) {
          const t = 2 ** a;
          for (let ty = 0; ty < H; ty += t) {
            for (let tx = 0; tx < W; tx += t) {
              const tile: [number, number][] = [];
              for (let y = 0; y < t; y++) for (let x = 0; x < t; x++) tile.push(at(p, (ty + y) * W + tx + x, s, d));
              expect(isNet(tile), `sample ${s}, pair ${d}, ${t}×${t} tile at (${tx}, ${ty})`).toBe(true);
            }
          }
        }
      }
    }
  });

  it('is uniform over dimensions 0–7: χ² per dimension over the screen, and per pixel over pairs of dimensions from different pairs', async () => {
    const p = await draw(SOBOL, 0, 3);
    const n = W * H * SAMPLES;
    const B = 64;
    const oneD = Array.from({ length: PAIRS * 2 }, () => new Float64Array(B));
    let outside = 0;
    for (let i = 0; i < n * PAIRS * 2; i++) {
      const x = p[i]!;
      if (!(x >= 0 && x < 1)) outside++;
      else oneD[i % (PAIRS * 2)]![Math.floor(x * B)]!++;
    }
    expect(outside).toBe(0);
    // Dimension 5 (y of pair 2) is not drawn (rng_next_f32 keeps x): it is 0 there.
    oneD.forEach((counts, d) => {
      if (d !== 5) expect(chiSquare(counts, n), `dimension ${d}`).toBeLessThan(chiSquareCritical(B - 1));
    });

    // One pixel's 4096 samples: dimensions of different pairs are independent (16 × 16 bins). Over the
    // screen they are not, by design: a frame's pattern is the previous frame's up to a digital shift.
    const samples = 4096;
    const q = await draw(SOBOL, 0, 11, { width: 2, height: 2, samples });
    const K = 16;
    for (const pixel of [0, 3]) {
      for (const [a, b] of [[0, 2], [1, 6], [3, 7], [0, 7], [4, 6], [1, 3]] as const) {
        const counts = new Float64Array(K * K);
        for (let s = 0; s < samples; s++) {
          const i = (pixel * samples + s) * PAIRS * 2;
          counts[Math.floor(q[i + a]! * K) * K + Math.floor(q[i + b]! * K)]!++;
        }
        expect(chiSquare(counts, samples), `pixel ${pixel}, dimensions ${a} and ${b}`).toBeLessThan(chiSquareCritical(K * K - 1));
      }
    }
  });

  it("gives distinct pixels distinct sequences, uncorrelated over the screen", async () => {
    const p = await draw(SOBOL, 0, 3);
    // No two pixels share their first 16 points in pair 0.
    const keys = new Set<string>();
    for (let pixel = 0; pixel < W * H; pixel++) keys.add(Array.from({ length: 16 }, (_, s) => at(p, pixel, s, 0)[0]).join());
    expect(keys.size).toBe(W * H);
    // The correlation of pixel p's and pixel q's value over their samples, averaged over many pairs of
    // pixels in different 8 × 8 tiles, is zero to within its standard error (each pair's is a Pearson
    // correlation of 256 samples; a shared sequence or a shared shift would push the mean away).
    let sum = 0, sumSq = 0, count = 0;
    for (let pixel = 0; pixel < W * H; pixel += 7) {
      const q = (pixel * 131 + 517) % (W * H);
      if (Math.floor(pixel / W / 8) === Math.floor(q / W / 8) && Math.floor((pixel % W) / 8) === Math.floor((q % W) / 8)) continue;
      for (const d of [0, 1]) {
        for (const c of [0, 1]) {
          let sp = 0, sq = 0, spq = 0, spp = 0, sqq = 0;
          for (let s = 0; s < SAMPLES; s++) {
            const a = at(p, pixel, s, d)[c]!, b = at(p, q, s, d)[c]!;
            sp += a; sq += b; spq += a * b; spp += a * a; sqq += b * b;
          }
          const cov = spq / SAMPLES - (sp / SAMPLES) * (sq / SAMPLES);
          const r = cov / Math.sqrt((spp / SAMPLES - (sp / SAMPLES) ** 2) * (sqq / SAMPLES - (sq / SAMPLES) ** 2));
          sum += r; sumSq += r * r; count++;
        }
      }
    }
    const mean = sum / count;
    const se = Math.sqrt((sumSq / count - mean * mean) / count);
    expect(count).toBeGreaterThan(400);
    expect(Math.abs(mean)).toBeLessThan(4 * se + 0.01);
  });

  it("makes a 1-spp error image blue: 4 × 4 block means of the error keep far less energy than white noise's", async () => {
    // Each pixel estimates ∫ f over the unit square from its sample of pair d at one sample index: a
    // shadow edge across a gradient (what a light sample or a jittered edge looks like). For white
    // noise the 4 × 4 block means keep 1/16 of the error's energy; for blue noise much less.
    const f = (x: number, y: number) => (x + 0.3 * y < 0.6 ? 1 + y : 0);
    let exact = 0;
    const G = 1000;
    for (let i = 0; i < G; i++) for (let j = 0; j < G; j++) exact += f((i + 0.5) / G, (j + 0.5) / G);
    exact /= G * G;
    const lowFraction = (p: Float32Array, s: number, d: number): number => {
      let total = 0, low = 0;
      for (let by = 0; by < H; by += 4) {
        for (let bx = 0; bx < W; bx += 4) {
          let block = 0;
          for (let y = 0; y < 4; y++) {
            for (let x = 0; x < 4; x++) {
              const [u, v] = at(p, (by + y) * W + bx + x, s, d);
              const e = f(u, v) - exact;
              total += e * e;
              block += e;
            }
          }
          low += 16 * (block / 16) ** 2;
        }
      }
      return low / total;
    };
    const sobol = await draw(SOBOL, 0, 3);
    const white = await draw(RANDOM, 0, 3);
    let sobolFraction = 0, whiteFraction = 0, n = 0;
    for (const s of [0, 1, 2, 3, 50, 255]) {
      for (const d of [0, 1, 3]) {
        sobolFraction += lowFraction(sobol, s, d);
        whiteFraction += lowFraction(white, s, d);
        n++;
      }
    }
    sobolFraction /= n;
    whiteFraction /= n;
    // White: 1/16 = 0.0625 within its sampling error; blue: measured 0.003 to 0.006.
    expect(whiteFraction).toBeGreaterThan(0.045);
    expect(whiteFraction).toBeLessThan(0.08);
    expect(sobolFraction).toBeLessThan(whiteFraction / 5);
  });
});
