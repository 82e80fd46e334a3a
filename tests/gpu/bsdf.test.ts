/**
 * The BSDF module (shaders/scene/bsdf.wgsl) on the GPU: white furnaces per kind, chi-square tests of
 * each sampler against its own bsdf_pdf, weight = f·|cos|/pdf, reciprocity, and the transmittance of
 * a smooth glass slab against the Fresnel equations computed here independently.
 */
import { beforeAll, describe, expect, it } from 'vitest';
import { testGpu } from './gpu-context.ts';
import { outputBuffer, runOnce, storageBuffer, testKernel } from './compute.ts';
import { uploadBsdfTables } from '../../src/gpu/scene-resources.ts';
import type { ComputeKernel } from '../../src/gpu/kernel.ts';

const DIFFUSE = 0, METALLIC_ROUGHNESS = 1, DIELECTRIC = 2;
// Bits of the sample's flags (4: transmitted, not read here).
const FLAG_VALID = 1, FLAG_DELTA = 2;
const THREADS_PER_GROUP = 64;
const COS_BINS = 16, PHI_BINS = 32, BINS = COS_BINS * PHI_BINS;
/** Midpoints per bin axis when integrating bsdf_pdf over a bin. */
const PDF_SUBDIVISION = 16;

interface Case {
  kind: number;
  base?: [number, number, number];
  metallic?: number;
  roughness: number;
  ior?: number;
  transmission?: number;
  specular?: number;
  specularColor?: [number, number, number];
  thin?: boolean;
  /** Cosine of wo to +z (negative: from behind/inside); wo lies in the xz plane. */
  cosO: number;
}

/** Four vec4f per case, decoded by `case_params` below. */
function encodeCases(cases: readonly Case[]): Float32Array {
  const a = new Float32Array(cases.length * 16);
  cases.forEach((c, k) => {
    const base = c.base ?? [1, 1, 1];
    const sc = c.specularColor ?? [1, 1, 1];
    const sinO = Math.sqrt(Math.max(0, 1 - c.cosO * c.cosO));
    a.set([c.kind, c.metallic ?? 0, c.roughness, c.ior ?? 1.5], k * 16);
    a.set([...base, c.transmission ?? 0], k * 16 + 4);
    a.set([...sc, c.specular ?? 1], k * 16 + 8);
    a.set([sinO, 0, c.cosO, c.thin ? 1 : 0], k * 16 + 12);
  });
  return a;
}

const COMMON = `
#import lib/random
#import scene/bsdf
@group(3) @binding(0) var<storage, read> cases: array<vec4f>;
@group(3) @binding(1) var<storage, read_write> results: array<vec4f>;

fn case_params(k: u32) -> BsdfParams {
  let c0 = cases[k * 4u];
  let c1 = cases[k * 4u + 1u];
  let c2 = cases[k * 4u + 2u];
  let c3 = cases[k * 4u + 3u];
  return BsdfParams(u32(c0.x), c1.xyz, c0.y, c0.z, c0.w, c1.w, c2.w, c2.xyz, u32(c3.w));
}

fn case_wo(k: u32) -> vec3f {
  return normalize(cases[k * 4u + 3u].xyz);
}
`;

// Per sample three vec4f: (wi, pdf), (weight, flags), (bsdf_eval·|cos|/bsdf_pdf at wi, bsdf_pdf at wi).
const SAMPLE_KERNEL = (samplesPerThread: number) => `${COMMON}
@compute @workgroup_size(${THREADS_PER_GROUP})
fn sample_bsdf(@builtin(global_invocation_id) id: vec3u, @builtin(num_workgroups) groups: vec3u) {
  let k = id.y;
  let p = case_params(k);
  let wo = case_wo(k);
  let threads = groups.x * ${THREADS_PER_GROUP}u;
  var rng = rng_seed(id.x, k, 777u);
  for (var s = 0u; s < ${samplesPerThread}u; s++) {
    let u = vec3f(rng_next_f32(&rng), rng_next_f32(&rng), rng_next_f32(&rng));
    let b = bsdf_sample(p, wo, u);
    let flags = select(0.0, 1.0, b.valid) + select(0.0, 2.0, b.delta) + select(0.0, 4.0, b.transmitted);
    let pdf = bsdf_pdf(p, wo, b.wi);
    let f = bsdf_eval(p, wo, b.wi);
    let index = ((k * threads + id.x) * ${samplesPerThread}u + s) * 3u;
    results[index] = vec4f(b.wi, b.pdf);
    results[index + 1u] = vec4f(b.weight, flags);
    results[index + 2u] = vec4f(f * abs(b.wi.z) / max(pdf, 1e-30), pdf);
  }
}`;

// Per thread: Σ weight of reflected samples (rgb, count of invalid samples), Σ weight of transmitted ones.
const FURNACE_KERNEL = (samplesPerThread: number) => `${COMMON}
@compute @workgroup_size(${THREADS_PER_GROUP})
fn furnace(@builtin(global_invocation_id) id: vec3u, @builtin(num_workgroups) groups: vec3u) {
  let k = id.y;
  let p = case_params(k);
  let wo = case_wo(k);
  var rng = rng_seed(id.x, k, 31337u);
  var reflected = vec3f(0.0);
  var transmitted = vec3f(0.0);
  var invalid = 0.0;
  for (var s = 0u; s < ${samplesPerThread}u; s++) {
    let u = vec3f(rng_next_f32(&rng), rng_next_f32(&rng), rng_next_f32(&rng));
    let b = bsdf_sample(p, wo, u);
    if (!b.valid) {
      invalid += 1.0;
    } else if (b.transmitted) {
      transmitted += b.weight;
    } else {
      reflected += b.weight;
    }
  }
  let index = (k * groups.x * ${THREADS_PER_GROUP}u + id.x) * 2u;
  results[index] = vec4f(reflected, invalid);
  results[index + 1u] = vec4f(transmitted, 0.0);
}`;

// Per sample one vec4f: (wi, 1 valid non-delta | 2 delta | 0 invalid) — what the chi-square test bins.
const DIRECTION_KERNEL = (samplesPerThread: number) => `${COMMON}
@compute @workgroup_size(${THREADS_PER_GROUP})
fn sample_directions(@builtin(global_invocation_id) id: vec3u, @builtin(num_workgroups) groups: vec3u) {
  let k = id.y;
  let p = case_params(k);
  let wo = case_wo(k);
  var rng = rng_seed(id.x, k, 2024u);
  for (var s = 0u; s < ${samplesPerThread}u; s++) {
    let u = vec3f(rng_next_f32(&rng), rng_next_f32(&rng), rng_next_f32(&rng));
    let b = bsdf_sample(p, wo, u);
    let kind = select(0.0, select(1.0, 2.0, b.delta), b.valid);
    results[(k * groups.x * ${THREADS_PER_GROUP}u + id.x) * ${samplesPerThread}u + s] = vec4f(b.wi, kind);
  }
}`;

// ∫ bsdf_pdf over each (cos θ, φ) bin of the sphere by a midpoint rule; equal steps in cos θ and φ
// are equal solid angles.
const PDF_BIN_KERNEL = `${COMMON}
@compute @workgroup_size(${THREADS_PER_GROUP})
fn integrate_pdf(@builtin(global_invocation_id) id: vec3u) {
  let k = id.y;
  let bin = id.x;
  if (bin >= ${BINS}u) {
    return;
  }
  let p = case_params(k);
  let wo = case_wo(k);
  let ci = bin / ${PHI_BINS}u;
  let pi_ = bin % ${PHI_BINS}u;
  let dc = 2.0 / ${COS_BINS}.0 / ${PDF_SUBDIVISION}.0;
  let dphi = 2.0 * PI / ${PHI_BINS}.0 / ${PDF_SUBDIVISION}.0;
  var sum = 0.0;
  for (var a = 0u; a < ${PDF_SUBDIVISION}u; a++) {
    let c = -1.0 + (f32(ci * ${PDF_SUBDIVISION}u + a) + 0.5) * dc;
    let s = sqrt(max(0.0, 1.0 - c * c));
    for (var b = 0u; b < ${PDF_SUBDIVISION}u; b++) {
      let phi = (f32(pi_ * ${PDF_SUBDIVISION}u + b) + 0.5) * dphi;
      sum += bsdf_pdf(p, wo, vec3f(s * cos(phi), s * sin(phi), c));
    }
  }
  results[k * ${BINS}u + bin] = vec4f(sum * dc * dphi, 0.0, 0.0, 0.0);
}`;

// f(wo, wi) and f(wi, wo) for random pairs in the upper hemisphere.
const RECIPROCITY_KERNEL = `${COMMON}
#import lib/sampling
@compute @workgroup_size(${THREADS_PER_GROUP})
fn reciprocity(@builtin(global_invocation_id) id: vec3u, @builtin(num_workgroups) groups: vec3u) {
  let k = id.y;
  let p = case_params(k);
  var rng = rng_seed(id.x, k, 99u);
  let a = sample_sphere_uniform(rng_next_2d(&rng));
  let b = sample_sphere_uniform(rng_next_2d(&rng));
  // WGSL's sin and cos may be off by 2^-11: normalize, or the pair is not the same pair both ways.
  let wo = normalize(vec3f(a.xy, abs(a.z)));
  let wi = normalize(vec3f(b.xy, abs(b.z)));
  let index = (k * groups.x * ${THREADS_PER_GROUP}u + id.x) * 2u;
  results[index] = vec4f(bsdf_eval(p, wo, wi), 0.0);
  results[index + 1u] = vec4f(bsdf_eval(p, wi, wo), 0.0);
}`;

// bsdf_has_non_delta and bsdf_albedo at wo = case_wo.
const QUERY_KERNEL = `${COMMON}
@compute @workgroup_size(1)
fn query(@builtin(global_invocation_id) id: vec3u) {
  let k = id.y;
  let p = case_params(k);
  results[k] = vec4f(bsdf_albedo(p, case_wo(k)), select(0.0, 1.0, bsdf_has_non_delta(p)));
}`;

// Random walks in a slab between two smooth glass interfaces (top: normal +z, bottom: normal −z,
// outside is air on both). The walk starts above, travelling down along −wo. Each interface is
// sampled in its own local frame (front = outside); the bottom one is the top one mirrored in z.
const MAX_SLAB_BOUNCES = 64;
const SLAB_KERNEL = `${COMMON}
@compute @workgroup_size(${THREADS_PER_GROUP})
fn slab(@builtin(global_invocation_id) id: vec3u, @builtin(num_workgroups) groups: vec3u) {
  let k = id.y;
  let p = case_params(k);
  var d = -case_wo(k);           // travel direction, world frame
  var weight = vec3f(1.0);
  var at_top = true;
  var outcome = 0.0;             // 1: out of the bottom, 2: out of the top, 0: still inside / lost
  var rng = rng_seed(id.x, k, 4242u);
  for (var bounce = 0u; bounce < ${MAX_SLAB_BOUNCES}u; bounce++) {
    let mirror = select(vec3f(1.0, 1.0, -1.0), vec3f(1.0), at_top);
    let wo = -d * mirror;
    let u = vec3f(rng_next_f32(&rng), rng_next_f32(&rng), rng_next_f32(&rng));
    let b = bsdf_sample(p, wo, u);
    if (!b.valid) {
      break;
    }
    weight *= b.weight;
    d = b.wi * mirror;
    // Leaving: through the top going up, or through the bottom going down.
    if (at_top && d.z > 0.0) {
      outcome = 2.0;
      break;
    }
    if (!at_top && d.z < 0.0) {
      outcome = 1.0;
      break;
    }
    at_top = d.z > 0.0;
  }
  results[k * groups.x * ${THREADS_PER_GROUP}u + id.x] = vec4f(weight, outcome);
}`;

/** Upper critical value of χ² with k degrees of freedom at tail probability ~1e-4 (Wilson–Hilferty). */
function chiSquareCritical(k: number): number {
  const z = 3.719;
  const a = 2 / (9 * k);
  return k * (1 - a + z * Math.sqrt(a)) ** 3;
}

/** χ² over bins, pooling bins whose expected count is under 5 into one; returns statistic and dof. */
function chiSquare(observed: readonly number[], expected: readonly number[]): { chi2: number; dof: number } {
  let chi2 = 0, bins = 0, poolO = 0, poolE = 0;
  for (let i = 0; i < observed.length; i++) {
    const o = observed[i]!, e = expected[i]!;
    if (e < 5) {
      poolO += o;
      poolE += e;
      continue;
    }
    chi2 += (o - e) ** 2 / e;
    bins++;
  }
  if (poolE > 0) {
    chi2 += (poolO - poolE) ** 2 / Math.max(poolE, 5);
    bins++;
  }
  return { chi2, dof: bins - 1 };
}

/** Unpolarized Fresnel reflectance from air into index n at incidence cosine cosI (independent of the WGSL). */
function fresnelAirTo(n: number, cosI: number): number {
  const sinT = Math.sqrt(1 - cosI * cosI) / n;
  const cosT = Math.sqrt(1 - sinT * sinT);
  const rs = (cosI - n * cosT) / (cosI + n * cosT);
  const rp = (n * cosI - cosT) / (n * cosI + cosT);
  return (rs * rs + rp * rp) / 2;
}

interface Samples {
  readonly data: Float32Array;
  readonly perCase: number;
}

describe('the BSDF module on the GPU', () => {
  let device: GPUDevice;
  let tables: GPUTexture;
  const kernels = new Map<string, ComputeKernel>();

  beforeAll(async () => {
    ({ device } = await testGpu());
    tables = await uploadBsdfTables(device);
  });

  async function kernel(name: string, code: string, entry: string): Promise<ComputeKernel> {
    const key = `${name}:${code.length}`;
    let k = kernels.get(key);
    if (!k) {
      k = await testKernel(device, `test/${name}`, code, entry);
      kernels.set(key, k);
    }
    return k;
  }

  async function run(k: ComputeKernel, cases: readonly Case[], groupsX: number, floatsPerCase: number): Promise<Float32Array> {
    const caseBuffer = storageBuffer(device, 'cases', encodeCases(cases));
    const out = outputBuffer(device, 'results', cases.length * floatsPerCase * 4);
    const groups = { 0: k.bindGroup(0, { bsdf_tables: tables.createView() }), 3: k.bindGroup(3, { cases: caseBuffer, results: out }) };
    const data = new Float32Array(await runOnce(device, k, groups, [groupsX, cases.length], out));
    caseBuffer.destroy();
    out.destroy();
    return data;
  }

  /** Sampled directions (wi, valid) per case, for binning. */
  async function directions(cases: readonly Case[], samplesPerCase: number): Promise<Samples> {
    const samplesPerThread = 64;
    const groupsX = Math.ceil(samplesPerCase / (samplesPerThread * THREADS_PER_GROUP));
    const perCase = groupsX * THREADS_PER_GROUP * samplesPerThread;
    const k = await kernel('bsdf-directions', DIRECTION_KERNEL(samplesPerThread), 'sample_directions');
    return { data: await run(k, cases, groupsX, perCase * 4), perCase };
  }

  async function sample(cases: readonly Case[], samplesPerCase: number): Promise<Samples> {
    const samplesPerThread = 64;
    const groupsX = Math.ceil(samplesPerCase / (samplesPerThread * THREADS_PER_GROUP));
    const perCase = groupsX * THREADS_PER_GROUP * samplesPerThread;
    const k = await kernel('bsdf-sample', SAMPLE_KERNEL(samplesPerThread), 'sample_bsdf');
    return { data: await run(k, cases, groupsX, perCase * 12), perCase };
  }

  /**
   * Mean weight (rgb) of each case, from the furnace kernel; undoRadianceScaling(case) multiplies
   * transmitted weights (to undo the 1/η² of refraction).
   */
  async function furnace(cases: readonly Case[], samplesPerCase: number, undoRadianceScaling: (c: Case) => number = () => 1): Promise<[number, number, number][]> {
    const samplesPerThread = 64;
    const groupsX = Math.ceil(samplesPerCase / (samplesPerThread * THREADS_PER_GROUP));
    const threads = groupsX * THREADS_PER_GROUP;
    const k = await kernel('bsdf-furnace', FURNACE_KERNEL(samplesPerThread), 'furnace');
    const data = await run(k, cases, groupsX, threads * 8);
    return cases.map((c, ci) => {
      const m: [number, number, number] = [0, 0, 0];
      const scale = undoRadianceScaling(c);
      for (let t = 0; t < threads; t++) {
        const o = (ci * threads + t) * 8;
        for (let ch = 0; ch < 3; ch++) m[ch]! += data[o + ch]! + scale * data[o + 4 + ch]!;
      }
      return m.map((x) => x / (threads * samplesPerThread)) as [number, number, number];
    });
  }

  const COS_ANGLES = [1, 0.7, 0.3, 0.1];
  // 0 is the delta limit (mirror spec lobe), 0.05 just above it.
  const ROUGHNESSES = [0, 0.05, 0.25, 0.5, 0.75, 1];
  function grid(make: (cosO: number, roughness: number) => Case): Case[] {
    return ROUGHNESSES.flatMap((r) => COS_ANGLES.map((c) => make(c, r)));
  }

  it('white furnace: diffuse = 1, white metal = 1 (±1 %) at every roughness, white glTF dielectric ≈ 1 and never above', async () => {
    const diffuse = COS_ANGLES.map((c): Case => ({ kind: DIFFUSE, roughness: 1, cosO: c }));
    const metal = grid((c, r): Case => ({ kind: METALLIC_ROUGHNESS, metallic: 1, roughness: r, cosO: c }));
    const plastic = grid((c, r): Case => ({ kind: METALLIC_ROUGHNESS, metallic: 0, roughness: r, cosO: c }));
    const cases = [...diffuse, ...metal, ...plastic];
    const means = await furnace(cases, 16384);
    console.log(cases.map((c, i) => `kind ${c.kind} m ${c.metallic ?? '-'} r ${c.roughness} μ ${c.cosO}: ${means[i]![0].toFixed(4)}`).join('\n'));
    cases.forEach((c, i) => {
      const [r, g, b] = means[i]!;
      expect(Math.abs(r - g)).toBeLessThan(1e-4); // white in, grey out
      expect(Math.abs(r - b)).toBeLessThan(1e-4);
      // Cosine sampling of Lambert: every weight is 1 (but a sample exactly at the horizon is dropped).
      if (c.kind === DIFFUSE) expect(Math.abs(r - 1)).toBeLessThan(1e-3);
      else if (c.metallic === 1) expect(Math.abs(r - 1)).toBeLessThan(0.01);
      else {
        expect(Math.abs(r - 1)).toBeLessThan(0.015);
        expect(r).toBeLessThan(1.01);
      }
    });
  });

  it('white furnace: glass (reflect + transmit, 1/η² undone) = 1 (±1 %) from both sides, smooth and rough; transmissive glTF too', async () => {
    const ior = 1.5;
    const cases: Case[] = [
      ...[0, 0.05, 0.25, 0.5, 1].flatMap((r) => [1, 0.5, 0.1, -1, -0.5, -0.1].map((c): Case => ({ kind: DIELECTRIC, roughness: r, ior, cosO: c }))),
      ...[0.3, 0.8].flatMap((r) => [0.8, -0.8].map((c): Case => ({ kind: METALLIC_ROUGHNESS, transmission: 1, roughness: r, ior, cosO: c }))),
      ...[0.3].flatMap((r) => [0.8, -0.5].map((c): Case => ({ kind: METALLIC_ROUGHNESS, transmission: 1, roughness: r, ior, thin: true, cosO: c }))),
    ];
    // η² with η = n(wi side)/n(wo side) undoes the radiance scaling of a transmitted sample.
    const etaSquared = (c: Case) => (c.thin ? 1 : c.cosO > 0 ? ior * ior : 1 / (ior * ior));
    const means = (await furnace(cases, 32768, etaSquared)).map((m) => m[0]);
    console.log(cases.map((c, i) => `kind ${c.kind} thin ${c.thin ?? false} r ${c.roughness} μ ${c.cosO}: ${means[i]!.toFixed(4)}`).join('\n'));
    means.forEach((r) => expect(Math.abs(r - 1)).toBeLessThan(0.01));
  });

  it('creates no energy: random materials with colours ≤ 1 reflect + transmit at most 1 per channel', async () => {
    let seed = 7;
    const rand = () => ((seed = (Math.imul(seed, 1664525) + 1013904223) >>> 0) / 2 ** 32);
    const cases: Case[] = [];
    for (let i = 0; i < 24; i++) {
      const kind = i % 3;
      cases.push({
        kind,
        base: [rand(), rand(), rand()],
        metallic: rand() < 0.3 ? 1 : rand(),
        roughness: rand(),
        ior: 1.1 + 1.5 * rand(),
        transmission: rand() < 0.5 ? 0 : rand(),
        specular: rand(),
        specularColor: [rand(), rand(), rand()],
        thin: rand() < 0.3,
        cosO: (kind === DIFFUSE ? 1 : rand() < 0.5 ? -1 : 1) * (0.05 + 0.95 * rand()),
      });
    }
    // Opaque kinds are given wo.z ≥ 0 by the caller; keep that contract.
    for (const c of cases) if (c.kind === METALLIC_ROUGHNESS && !c.transmission) c.cosO = Math.abs(c.cosO);
    const etaSquared = (c: Case) => (c.thin ? 1 : c.cosO > 0 ? c.ior! ** 2 : 1 / c.ior! ** 2);
    const means = await furnace(cases, 8192, etaSquared);
    console.log(means.map((m, i) => `${JSON.stringify(cases[i])}: ${m.map((x) => x.toFixed(4)).join(' ')}`).join('\n'));
    for (const m of means) for (const x of m) expect(x).toBeLessThan(1.01);
  });

  it('bsdf_has_non_delta is false exactly for delta-only materials; bsdf_albedo matches the furnace', async () => {
    const cases: [Case, boolean, [number, number, number]][] = [
      [{ kind: DIFFUSE, base: [0.2, 0.4, 0.6], roughness: 0, cosO: 0.5 }, true, [0.2, 0.4, 0.6]],
      [{ kind: METALLIC_ROUGHNESS, metallic: 1, roughness: 0, cosO: 0.5 }, false, [1, 1, 1]],
      [{ kind: METALLIC_ROUGHNESS, metallic: 1, roughness: 0.02, cosO: 0.5 }, false, [1, 1, 1]],
      [{ kind: METALLIC_ROUGHNESS, metallic: 1, roughness: 0.7, cosO: 0.5 }, true, [1, 1, 1]],
      [{ kind: METALLIC_ROUGHNESS, metallic: 0, roughness: 0, cosO: 0.5 }, true, [1, 1, 1]],
      [{ kind: METALLIC_ROUGHNESS, metallic: 0, roughness: 0, transmission: 1, cosO: 0.5 }, false, [1, 1, 1]],
      [{ kind: DIELECTRIC, roughness: 0, cosO: 0.5 }, false, [1, 1, 1]],
      [{ kind: DIELECTRIC, roughness: 0.5, cosO: -0.5 }, true, [1, 1, 1]],
      // Black glTF dielectric: only the 4 % (Schlick at μ = 1) specular layer is left.
      [{ kind: METALLIC_ROUGHNESS, metallic: 0, base: [0, 0, 0], roughness: 0, cosO: 1 }, true, [0.04, 0.04, 0.04]],
    ];
    const k = await kernel('bsdf-query', QUERY_KERNEL, 'query');
    const data = await run(k, cases.map(([c]) => c), 1, 4);
    cases.forEach(([, nonDelta, albedo], i) => {
      expect(data[i * 4 + 3] === 1, `case ${i}`).toBe(nonDelta);
      for (let ch = 0; ch < 3; ch++) expect(Math.abs(data[i * 4 + ch]! - albedo[ch]!), `case ${i}`).toBeLessThan(0.01);
    });
  });

  it('weight equals bsdf_eval·|cos|/bsdf_pdf for every non-delta sample, and delta samples report no density', async () => {
    const cases: Case[] = [
      { kind: DIFFUSE, base: [0.8, 0.5, 0.2], roughness: 1, cosO: 0.6 },
      { kind: METALLIC_ROUGHNESS, metallic: 1, base: [0.9, 0.6, 0.3], roughness: 0.4, cosO: 0.5 },
      { kind: METALLIC_ROUGHNESS, metallic: 0.3, base: [0.2, 0.7, 0.4], roughness: 0.6, specular: 0.7, specularColor: [1, 0.5, 0.8], cosO: 0.8 },
      { kind: DIELECTRIC, roughness: 0.3, ior: 1.5, base: [0.9, 0.8, 1], cosO: 0.7 },
      { kind: DIELECTRIC, roughness: 0.3, ior: 1.5, cosO: -0.7 },
      { kind: METALLIC_ROUGHNESS, transmission: 0.6, roughness: 0.5, ior: 1.4, base: [0.6, 0.9, 0.7], cosO: -0.4 },
    ];
    const s = await sample(cases, 4096);
    // Assert once on the worst cases: one expect per sample would cost seconds.
    let checked = 0, deltas = 0, worstPdf = 0, worstWeight = 0;
    for (let c = 0; c < cases.length; c++) {
      for (let i = 0; i < s.perCase; i++) {
        const o = (c * s.perCase + i) * 12;
        const flags = s.data[o + 7]!;
        if (!(flags & FLAG_VALID)) continue;
        if (flags & FLAG_DELTA) deltas++;
        const pdf = s.data[o + 3]!, pdfAgain = s.data[o + 11]!;
        worstPdf = Math.max(worstPdf, Math.abs(pdf - pdfAgain) / pdf);
        for (let ch = 0; ch < 3; ch++) {
          const w = s.data[o + 4 + ch]!, fromEval = s.data[o + 8 + ch]!;
          worstWeight = Math.max(worstWeight, Math.abs(w - fromEval) / Math.max(w, 1e-6));
        }
        checked++;
      }
    }
    expect(deltas).toBe(0);
    expect(worstPdf).toBeLessThan(1e-3);
    expect(worstWeight).toBeLessThan(1e-3);
    expect(checked).toBeGreaterThan(cases.length * s.perCase * 0.5);
  });

  it('bsdf_eval is reciprocal for the reflection lobes (diffuse, metal, glTF dielectric)', async () => {
    const cases: Case[] = [
      { kind: DIFFUSE, base: [0.5, 0.7, 0.9], roughness: 1, cosO: 1 },
      { kind: METALLIC_ROUGHNESS, metallic: 1, base: [0.9, 0.6, 0.3], roughness: 0.5, cosO: 1 },
      { kind: METALLIC_ROUGHNESS, metallic: 1, roughness: 1, cosO: 1 },
      { kind: METALLIC_ROUGHNESS, metallic: 0, base: [0.3, 0.6, 0.2], roughness: 0.7, specularColor: [1, 0.8, 0.6], cosO: 1 },
      { kind: METALLIC_ROUGHNESS, metallic: 0.5, base: [0.8, 0.8, 0.4], roughness: 0.2, cosO: 1 },
    ];
    const groupsX = 16;
    const k = await kernel('bsdf-reciprocity', RECIPROCITY_KERNEL, 'reciprocity');
    const data = await run(k, cases, groupsX, groupsX * THREADS_PER_GROUP * 8);
    let nonZero = 0, worst = 0;
    for (let i = 0; i < data.length / 8; i++) {
      for (let ch = 0; ch < 3; ch++) {
        const a = data[i * 8 + ch]!, b = data[i * 8 + 4 + ch]!;
        worst = Math.max(worst, Math.abs(a - b) / Math.max(a, b, 1e-6));
        if (a > 0) nonZero++;
      }
    }
    expect(worst).toBeLessThan(1e-3);
    expect(nonZero).toBeGreaterThan(data.length / 4);
  });

  it('a smooth glass slab transmits (1 − R)/(1 + R) of the light, R the Fresnel reflectance', async () => {
    const ior = 1.5;
    const cosines = [1, 0.7, 0.3];
    const cases = cosines.map((c): Case => ({ kind: DIELECTRIC, roughness: 0, ior, cosO: c }));
    const groupsX = 256;
    const walks = groupsX * THREADS_PER_GROUP;
    const k = await kernel('bsdf-slab', SLAB_KERNEL, 'slab');
    const data = await run(k, cases, groupsX, walks * 4);
    cosines.forEach((cosI, c) => {
      let transmitted = 0, reflected = 0, worstWeight = 0;
      for (let i = 0; i < walks; i++) {
        const o = (c * walks + i) * 4;
        // Every delta weight is 1 or the 1/η², η² pair of entering and leaving: a whole walk weighs 1.
        worstWeight = Math.max(worstWeight, Math.abs(s3(data, o) - 1));
        if (data[o + 3] === 1) transmitted++;
        if (data[o + 3] === 2) reflected++;
      }
      expect(worstWeight).toBeLessThan(1e-4);
      const r = fresnelAirTo(ior, cosI);
      const expected = (1 - r) / (1 + r);
      const sigma = Math.sqrt((expected * (1 - expected)) / walks);
      expect(Math.abs(transmitted / walks - expected)).toBeLessThan(4 * sigma);
      expect(transmitted + reflected).toBeGreaterThan(walks * 0.999);
    });
  });

  const CHI_SQUARE_SAMPLES = 65536;
  const chiCases: Case[] = [
    { kind: DIFFUSE, base: [0.7, 0.7, 0.7], roughness: 1, cosO: 0.6 },
    { kind: METALLIC_ROUGHNESS, metallic: 1, base: [0.9, 0.7, 0.5], roughness: 0.3, cosO: 0.6 },
    { kind: METALLIC_ROUGHNESS, metallic: 1, base: [0.9, 0.7, 0.5], roughness: 0.9, cosO: 0.3 },
    { kind: METALLIC_ROUGHNESS, metallic: 0, base: [0.5, 0.5, 0.5], roughness: 0.4, cosO: 0.5 },
    { kind: DIELECTRIC, roughness: 0.4, ior: 1.5, cosO: 0.6 },
    { kind: DIELECTRIC, roughness: 0.4, ior: 1.5, cosO: -0.6 },
    { kind: METALLIC_ROUGHNESS, transmission: 0.7, base: [0.8, 0.8, 0.8], roughness: 0.5, ior: 1.5, cosO: 0.5 },
    { kind: METALLIC_ROUGHNESS, transmission: 1, roughness: 0.4, ior: 1.5, thin: true, cosO: 0.5 },
    // Mixtures of delta and non-delta lobes: smooth layer over diffuse, smooth glass beside it.
    { kind: METALLIC_ROUGHNESS, metallic: 0, base: [0.5, 0.5, 0.5], roughness: 0, cosO: 0.3 },
    { kind: METALLIC_ROUGHNESS, transmission: 0.5, base: [0.8, 0.8, 0.8], roughness: 0, ior: 1.5, cosO: -0.7 },
  ];

  it('each sampler passes a chi-square test against its own bsdf_pdf over the sphere', async () => {
    const s = await directions(chiCases, CHI_SQUARE_SAMPLES);
    const k = await kernel('bsdf-pdf-bins', PDF_BIN_KERNEL, 'integrate_pdf');
    const integrals = await run(k, chiCases, BINS / THREADS_PER_GROUP, BINS * 4);
    const results = chiCases.map((c, ci) => {
      const { observed, expected } = binSamples(s, ci, integrals);
      const r = chiSquare(observed, expected);
      console.log(`case ${ci} (kind ${c.kind} r ${c.roughness} μ ${c.cosO}): χ² ${r.chi2.toFixed(1)} dof ${r.dof} crit ${chiSquareCritical(r.dof).toFixed(1)} pdf mass ${(1 - expected[BINS]! / s.perCase).toFixed(4)} invalid or delta ${(observed[BINS]! / s.perCase).toFixed(4)}`);
      return r;
    });
    for (const { chi2, dof } of results) {
      expect(dof).toBeGreaterThan(20);
      expect(chi2).toBeLessThan(chiSquareCritical(dof));
    }
  });

  it('the chi-square test has power: the metal samples fail against the pdf of another roughness', async () => {
    const s = await directions([chiCases[1]!], CHI_SQUARE_SAMPLES);
    const wrong: Case = { ...chiCases[1]!, roughness: 0.36 };
    const k = await kernel('bsdf-pdf-bins', PDF_BIN_KERNEL, 'integrate_pdf');
    const integrals = await run(k, [wrong], BINS / THREADS_PER_GROUP, BINS * 4);
    const { observed, expected } = binSamples(s, 0, integrals);
    const { chi2, dof } = chiSquare(observed, expected);
    expect(chi2).toBeGreaterThan(chiSquareCritical(dof));
  });

  /**
   * Sample counts per (cos θ, φ) bin plus one bin for the rest (invalid and delta samples, which
   * bsdf_pdf does not describe), and their expected counts.
   */
  function binSamples(s: Samples, c: number, integrals: Float32Array): { observed: number[]; expected: number[] } {
    const observed = new Array<number>(BINS + 1).fill(0);
    for (let i = 0; i < s.perCase; i++) {
      const o = (c * s.perCase + i) * 4;
      if (s.data[o + 3] !== 1) {
        observed[BINS]!++;
        continue;
      }
      const x = s.data[o]!, y = s.data[o + 1]!, z = s.data[o + 2]!;
      const cb = Math.min(COS_BINS - 1, Math.floor(((z + 1) / 2) * COS_BINS));
      const phi = Math.atan2(y, x) + (y < 0 ? 2 * Math.PI : 0);
      const pb = Math.min(PHI_BINS - 1, Math.floor((phi / (2 * Math.PI)) * PHI_BINS));
      observed[cb * PHI_BINS + pb]!++;
    }
    const expected: number[] = [];
    let mass = 0;
    for (let b = 0; b < BINS; b++) {
      const p = integrals[(c * BINS + b) * 4]!;
      mass += p;
      expected.push(p * s.perCase);
    }
    expected.push(Math.max(0, 1 - mass) * s.perCase);
    return { observed, expected };
  }
});

function s3(data: Float32Array, o: number): number {
  return (data[o]! + data[o + 1]! + data[o + 2]!) / 3;
}
