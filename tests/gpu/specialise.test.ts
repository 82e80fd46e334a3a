/**
 * Scene-specialised kernels (gpu/specialisation.ts): the unrolled traversal finds the BVH's hits,
 * hit for hit (checked against the CPU oracle and the GPU's BVH traversal); specialised images equal
 * generic ones within Monte Carlo error (same seeds); the renderer switches between them without
 * restarting accumulation, and any edit goes back to the generic kernel at once.
 */
import { describe, expect, it } from 'vitest';
import { makeRandom, randomSoup, soupScene, uvSphere } from '../../src/bvh/test-scenes.ts';
import { traverseClosest } from '../../src/bvh/traverse.ts';
import { prepareRay, intersectPrimitive } from '../../src/bvh/ray.ts';
import { createBufferWithData, readBuffer } from '../../src/gpu/readback.ts';
import { SceneResources } from '../../src/gpu/scene-resources.ts';
import { compileSpecialised, specialiseScene } from '../../src/gpu/specialisation.ts';
import { builtinScene } from '../../src/loaders/builtin/index.ts';
import { translation } from '../../src/math/mat4.ts';
import type { Vec3 } from '../../src/math/vec3.ts';
import { packRays, rayBufferStrides, TraceRaysPass, unpackHits } from '../../src/passes/trace-rays-pass.ts';
import { UniformParams } from '../../src/passes/uniform-params.ts';
import { prepareScene, type PreparedScene } from '../../src/renderer/prepare.ts';
import { renderProgressive } from '../../src/renderer/progressive.ts';
import { Renderer, type Accumulation } from '../../src/renderer/renderer.ts';
import type { Scene } from '../../src/scene/types.ts';
import { testGpu } from './gpu-context.ts';
import { lum } from './scene-render.ts';

const NO_TRIANGLE = 0xffffffff;


interface TestRay {
  origin: Vec3;
  direction: Vec3;
}

/** Random rays from inside the scene's bounds (some axis-aligned), rounded to f32 as the GPU sees them. */
function randomRays(prepared: PreparedScene, count: number, seed: number): TestRay[] {
  const b = prepared.bvh.bounds;
  const rnd = makeRandom(seed);
  const rays: TestRay[] = [];
  for (let i = 0; i < count; i++) {
    const o = [0, 1, 2].map((k) => b[k]! + rnd() * (b[k + 3]! - b[k]!));
    let d = [rnd() * 2 - 1, rnd() * 2 - 1, rnd() * 2 - 1];
    if (i % 16 === 0) d = [[1, 0, 0], [0, -1, 0], [0, 0, 1]][i % 3]!;
    rays.push({ origin: o.map(Math.fround) as unknown as Vec3, direction: d.map(Math.fround) as unknown as Vec3 });
  }
  return rays;
}

interface GpuHits {
  t: Float32Array;
  tri: Uint32Array;
}

/** Traces `rays` with passes/trace-rays: the generic (BVH) kernel, or the one specialised to the scene. */
async function trace(device: GPUDevice, prepared: PreparedScene, rays: TestRay[], specialised: boolean): Promise<GpuHits> {
  const module = 'passes/trace-rays';
  const scene = await SceneResources.upload(device, prepared.packed, prepared.scene.name);
  const rayBuffer = createBufferWithData(device, 'test rays', packRays(rays), GPUBufferUsage.STORAGE);
  const hitBuffer = device.createBuffer({ size: rayBufferStrides().hit * rays.length, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC });
  const encoder = device.createCommandEncoder();
  const params = new UniformParams<{ ray_count: number }>(device, module);
  params.write({ ray_count: rays.length });
  let generic: TraceRaysPass | undefined;
  if (specialised) {
    const spec = specialiseScene(prepared.packed, prepared.scene.name, { maxBounces: 1, lightSampling: 1 });
    expect(spec.unrolled, 'the scene is small enough to unroll').toBeDefined();
    const { kernel } = await compileSpecialised(device, { module, entryPoint: 'trace_rays' }, spec);
    const pass = encoder.beginComputePass();
    kernel.dispatch(pass, { 0: kernel.bindGroup(0, scene.bindings), 2: kernel.bindGroup(2, { params: params.buffer, rays: rayBuffer, hits: hitBuffer }) }, Math.ceil(rays.length / 64));
    pass.end();
  } else {
    generic = await TraceRaysPass.create(device);
    generic.encode(encoder, { binding: await generic.bind(scene, rayBuffer, hitBuffer, rays.length) });
  }
  device.queue.submit([encoder.finish()]);
  const hits = unpackHits(await readBuffer(device, hitBuffer), rays.length);
  const out = { t: Float32Array.from(hits, (h) => h.t), tri: Uint32Array.from(hits, (h) => h.triangle) };
  for (const buffer of [rayBuffer, hitBuffer]) buffer.destroy();
  params.destroy();
  generic?.destroy();
  scene.destroy();
  return out;
}

/** Triangles of a small soup with spheres and capsules among them (every primitive kind, each through intersect_primitive). */
function mixedScene(): Scene {
  const soup = soupScene('mixed', randomSoup(24, 5), { position: [0, 0, -30], forward: [0, 0, 1], up: [0, 1, 0], vfovDegrees: 50 });
  const mesh = soup.meshes[0]!;
  const spheres: [Vec3, number][] = [[[0, 0, 0], 3], [[6, -2, 4], 1.5], [[-5, 4, -3], 2]];
  const capsules: [Vec3, Vec3, number][] = [[[-6, -6, 0], [6, -6, 2], 1], [[2, 5, -5], [2, 8, 5], 0.7]];
  return {
    ...soup,
    meshes: [
      {
        ...mesh,
        spheres: { centers: new Float32Array(spheres.flatMap(([c]) => c)), radii: new Float32Array(spheres.map(([, r]) => r)), materialIds: new Uint32Array(spheres.length) },
        capsules: { endpoints: new Float32Array(capsules.flatMap(([a, b]) => [...a, ...b])), radii: new Float32Array(capsules.map(([, , r]) => r)), materialIds: new Uint32Array(capsules.length) },
      },
    ],
    environment: { kind: 'constant', radiance: [1, 1, 1] },
  };
}

/** Scenes small enough to unroll, with the fraction of random rays from inside their bounds that must hit. */
const SMALL_SCENES: [string, () => Scene, number][] = [
  ['cornell', () => builtinScene('cornell'), 0.5],
  ['furnace', () => builtinScene('furnace'), 0.5],
  ['random soup of 60', () => soupScene('soup', randomSoup(60, 3), { position: [0, 0, -30], forward: [0, 0, 1], up: [0, 1, 0], vfovDegrees: 50 }), 0.01],
  ['coarse UV sphere', () => soupScene('sphere', uvSphere(4, 8, 2), { position: [0.3, 0.2, -6], forward: [0, 0, 1], up: [0, 1, 0], vfovDegrees: 45 }), 0.5],
  ['triangles, spheres and capsules', mixedScene, 0.1],
];

describe('the unrolled traversal finds the BVH traversal’s hits', () => {
  it.each(SMALL_SCENES)('%s', async (_, make, hitFraction) => {
    const { device } = await testGpu();
    const prepared = prepareScene(make());
    const rays = randomRays(prepared, 2048, 17);
    const [unrolled, bvh] = await Promise.all([trace(device, prepared, rays, true), trace(device, prepared, rays, false)]);
    const { positions, kinds } = prepared.triangles;
    const failures: string[] = [];
    let hits = 0, ties = 0;
    rays.forEach((ray, i) => {
      const cpu = traverseClosest(prepared.bvh, positions, ray, kinds);
      const u = unrolled.tri[i]!, b = bvh.tri[i]!;
      if (u === b && (u === NO_TRIANGLE || Math.abs(unrolled.t[i]! - bvh.t[i]!) <= 1e-5 * bvh.t[i]!)) {
        if (u !== NO_TRIANGLE) hits++;
      } else if (u !== NO_TRIANGLE && b !== NO_TRIANGLE && Math.abs(unrolled.t[i]! - bvh.t[i]!) <= 1e-5 * bvh.t[i]!) {
        ties++; // two triangles at the same distance (a shared edge): either answer is right
      } else {
        failures.push(`ray ${i}: unrolled ${u} at ${unrolled.t[i]}, BVH ${b} at ${bvh.t[i]}`);
      }
      // And against the CPU oracle (f64): the same triangle, or one the oracle hits at the same distance.
      if ((cpu === null) !== (u === NO_TRIANGLE)) failures.push(`ray ${i}: oracle ${cpu ? `hit ${cpu.triangle}` : 'miss'}, unrolled ${u === NO_TRIANGLE ? 'miss' : `hit ${u}`}`);
      else if (cpu && u !== cpu.triangle) {
        const tAlt = intersectPrimitive(positions, kinds, u, prepareRay(ray), 0, 3e38, { u: 0, v: 0 });
        if (Math.abs(tAlt - cpu.t) > 1e-4 * cpu.t) failures.push(`ray ${i}: oracle ${cpu.triangle} at ${cpu.t}, unrolled ${u} (oracle has it at ${tAlt})`);
      }
    });
    expect(failures.slice(0, 10)).toEqual([]);
    expect(hits).toBeGreaterThan(hitFraction * rays.length);
    expect(ties).toBeLessThan(0.01 * rays.length);
  });
});

interface ImageRun {
  readonly image: Accumulation;
  readonly kernel: string;
}

async function renderWith(scene: PreparedScene, kernel: 'generic' | 'specialised', o: { size: number; spp: number; maxBounces: number }): Promise<ImageRun> {
  const renderer = await Renderer.create(await testGpu());
  try {
    await renderer.setScene(scene);
    await renderer.resize(o.size, o.size);
    renderer.updateSettings({ maxBounces: o.maxBounces, lightSampling: 'mis', seed: 5, torch: { enabled: false } });
    if (kernel === 'specialised') expect(await renderer.requestSpecialisation()).toBeDefined();
    await renderProgressive(renderer, { spp: o.spp });
    return { image: await renderer.readAccumulation(), kernel: renderer.kernel };
  } finally {
    renderer.destroy();
  }
}

/**
 * The images agree within Monte Carlo error: over 4×4-pixel blocks (and the whole image) the mean
 * luminances differ by less than 4 standard errors of the difference (the two estimates share seeds,
 * so they are correlated and usually agree far more closely).
 */
function expectSameEstimate(a: Accumulation, b: Accumulation): void {
  const block = 4;
  const bad: string[] = [];
  let totalA = 0, totalB = 0, totalVar = 0;
  for (let by = 0; by < a.height; by += block) {
    for (let bx = 0; bx < a.width; bx += block) {
      let sa = 0, sb = 0, v = 0, n = 0;
      for (let y = by; y < Math.min(by + block, a.height); y++) {
        for (let x = bx; x < Math.min(bx + block, a.width); x++) {
          const i = y * a.width + x;
          sa += lum(a, i);
          sb += lum(b, i);
          v += a.luminanceVariance[i]! / a.samples + b.luminanceVariance[i]! / b.samples;
          n++;
        }
      }
      totalA += sa;
      totalB += sb;
      totalVar += v;
      const diff = Math.abs(sa - sb) / n, se = Math.sqrt(v) / n;
      if (diff > 4 * se + 1e-6) bad.push(`block (${bx}, ${by}): ${(sa / n).toFixed(5)} vs ${(sb / n).toFixed(5)} (se ${se.toExponential(2)})`);
    }
  }
  expect(bad).toEqual([]);
  expect(totalA).toBeGreaterThan(0);
  expect(Math.abs(totalA - totalB)).toBeLessThan(4 * Math.sqrt(totalVar) + 1e-6);
}

/**
 * The paired check: with the same seeds every path draws the same numbers, so a kernel computing the
 * same estimator gives the same pixel values, up to rounding where folded constants change the
 * arithmetic (a path that meets an edge may then diverge). The fraction of pixels that agree to 0.1 %.
 */
function pairedAgreement(a: Accumulation, b: Accumulation): number {
  let same = 0;
  const n = a.width * a.height;
  for (let i = 0; i < n; i++) {
    const la = lum(a, i), lb = lum(b, i);
    if (Math.abs(la - lb) <= 1e-3 * Math.max(la, lb) + 1e-7) same++;
  }
  return same / n;
}

describe('specialised images equal generic ones within Monte Carlo error', () => {
  const cases: [string, () => Scene, { size: number; spp: number; maxBounces: number }, boolean][] = [
    // The furnace's unrolled image is checked by the frame-switching test below, and unrolled soups
    // by the hit-for-hit tests above: these three cover the kinds (diffuse triangles; metal and glass
    // through the BVH; analytic primitives under a sky) without compiling more kernels than that.
    ['cornell (unrolled)', () => builtinScene('cornell'), { size: 24, spp: 16, maxBounces: 4 }, true],
    ['materials (BVH, metal + glass)', () => builtinScene('materials'), { size: 16, spp: 8, maxBounces: 4 }, false],
    ['triangles, spheres and capsules under a white sky (unrolled)', mixedScene, { size: 16, spp: 8, maxBounces: 3 }, true],
  ];
  it.each(cases)('%s', async (_, make, o, unrolled) => {
    const prepared = prepareScene(make());
    const spec = specialiseScene(prepared.packed, 'check', { maxBounces: o.maxBounces, lightSampling: 1 });
    expect(spec.unrolled !== undefined).toBe(unrolled);
    const generic = await renderWith(prepared, 'generic', o);
    const specialised = await renderWith(prepared, 'specialised', o);
    expect(generic.kernel).toBe('generic');
    expect(specialised.kernel).toBe('specialised');
    expectSameEstimate(generic.image, specialised.image);
    // SwiftShader gives 1 (every pixel equal) on all four; a kernel that changed the estimator (one bounce fewer) gave 0.29.
    expect(pairedAgreement(generic.image, specialised.image)).toBeGreaterThan(0.95);
  });
});

describe('the renderer’s switch between generic and specialised kernels', () => {
  it('switches between frames without restarting accumulation, and any edit goes back to generic', async () => {
    const renderer = await Renderer.create(await testGpu());
    try {
      // The furnace: 12 primitives, the quickest unrolled kernel to compile on SwiftShader.
      await renderer.setScene(builtinScene('furnace'));
      await renderer.resize(8, 8);
      expect(renderer.kernel).toBe('generic');
      renderer.accumulate(2);
      const epoch = renderer.accumulationEpoch;
      const report = await renderer.requestSpecialisation();
      expect(report?.unrolled).toBe(true);
      expect(report?.compileMs).toBeGreaterThan(0);
      expect(renderer.kernel).toBe('specialised');
      renderer.accumulate(2);
      await renderer.finish();
      expect(renderer.accumulationEpoch).toBe(epoch);
      expect(renderer.sampleCount).toBe(4);

      // Camera moves and display settings keep it; an estimate setting is an edit.
      renderer.setCamera({ ...renderer.camera!, vfovDegrees: renderer.camera!.vfovDegrees * 0.9 });
      renderer.updateSettings({ exposureStops: 1 });
      expect(renderer.kernel).toBe('specialised');
      const maxBounces = renderer.settings.maxBounces;
      renderer.updateSettings({ maxBounces: maxBounces + 1 });
      expect(renderer.kernel).toBe('generic');
      // Setting it back is an edit too (no kernel is kept for the old settings), and the request
      // below then asks for the kernel already compiled: it completes sooner than a new one would,
      // but still after the edit that overtakes it, without a third unrolled compile (20 s here).
      renderer.updateSettings({ maxBounces });
      expect(renderer.kernel).toBe('generic');

      // A compile overtaken by an edit is dropped.
      const overtaken = renderer.requestSpecialisation();
      renderer.updateInstances(new Map([[0, translation([0, 0.01, 0])]]));
      expect(await overtaken).toBeUndefined();
      expect(renderer.kernel).toBe('generic');

      // The idle policy: specialise after the delay without edits; an edit restarts the delay.
      renderer.setIdleSpecialisation(30);
      await waitFor(() => renderer.kernel === 'specialised', 120_000);
      renderer.invalidateSpecialisation();
      expect(renderer.kernel).toBe('generic');
      await waitFor(() => renderer.kernel === 'specialised', 120_000);
      expect(renderer.specialisationError).toBeUndefined();
      renderer.accumulate(1);
      await renderer.finish();

      // A material edit is an edit too.
      renderer.setIdleSpecialisation(undefined);
      renderer.updateMaterials(new Map([[0, { color: [0.4, 0.4, 0.4] }]]));
      expect(renderer.kernel).toBe('generic');
    } finally {
      renderer.destroy();
    }
  });
});

async function waitFor(condition: () => boolean, ms: number): Promise<void> {
  const end = performance.now() + ms;
  while (!condition()) {
    if (performance.now() > end) throw new Error('timed out waiting for the specialised kernel');
    await new Promise((r) => setTimeout(r, 20));
  }
}
