/**
 * What the static-world accel tests share (grid-traversal, wide-traversal): rays that exercise a
 * scene (pixel rays, random rays from inside a box, some along the axes and some short, rays into
 * each moving instance) and their closest and any hits traced through the scene's kernels as the
 * renderer compiles them.
 */
import type { Grid } from '../../src/bvh/grid.ts';
import { traceScene } from '../../src/bvh/levels.ts';
import { intersectPrimitive, prepareRay } from '../../src/bvh/ray.ts';
import { makeRandom } from '../../src/bvh/test-scenes.ts';
import type { WideBvh } from '../../src/bvh/wide.ts';
import { ComputeKernel, TRAVERSAL_FEATURES } from '../../src/gpu/kernel.ts';
import { featureConstants } from '../../src/gpu/kernel-variants.ts';
import { readBuffer } from '../../src/gpu/readback.ts';
import { SceneResources } from '../../src/gpu/scene-resources.ts';
import { cameraBasis, type CameraBasis } from '../../src/gpu/view.ts';
import { linkWgsl } from '../../src/gpu/wgsl/linker.ts';
import { reflectLinked } from '../../src/gpu/wgsl/reflect.ts';
import type { Vec3 } from '../../src/math/vec3.ts';
import { packRays } from '../../src/passes/trace-rays-pass.ts';
import type { PreparedScene } from '../../src/renderer/prepare.ts';
import { SHADER_MODULES } from '../../src/shaders/index.ts';
import { expect } from 'vitest';
import { builtinScene } from '../../src/loaders/builtin/index.ts';
import type { Renderer } from '../../src/renderer/renderer.ts';
import type { RenderSettings } from '../../src/renderer/settings.ts';
import { outputBuffer, storageBuffer } from './compute.ts';

// Closest and any hit of each ray.
const KERNEL = `
#import scene/bvh

struct AccelTestHit {
  t: f32,
  source: u32,
  u: f32,
  v: f32,
  any: u32,
}

@group(2) @binding(0) var<storage, read> rays: array<Ray>;
@group(2) @binding(1) var<storage, read_write> out: array<AccelTestHit>;

@compute @workgroup_size(64)
fn accel_test(@builtin(global_invocation_id) id: vec3u) {
  let i = id.x;
  if (i >= arrayLength(&rays)) {
    return;
  }
  let hit = trace_closest(rays[i]);
  var source = NO_TRIANGLE;
  if (hit.triangle != NO_TRIANGLE) {
    source = world_shading(hit.instance, hit.triangle).source_index;
  }
  out[i] = AccelTestHit(hit.t, source, hit.u, hit.v, select(0u, 1u, trace_any(rays[i])));
}
`;

export interface TestRay {
  readonly origin: Vec3;
  readonly direction: Vec3;
  readonly tMin: number;
  readonly tMax: number;
}

/** Where random rays start (a box, min and max xyz) and how many: from inside it, and toward each moving instance. */
export interface RaySpread {
  readonly lo: ArrayLike<number>;
  readonly hi: ArrayLike<number>;
  readonly random: number;
  readonly perInstance: number;
}

/** size × size pixel rays from the camera, then the spread's rays; all in f32, as the GPU reads them. */
export function makeRays(prepared: PreparedScene, size: number, spread: RaySpread): TestRay[] {
  const b = cameraBasis(prepared.scene.camera, 1);
  const rays: TestRay[] = [];
  const far = 1e30;
  for (let y = 0; y < size; y++) {
    for (let x = 0; x < size; x++) {
      const nx = (2 * (x + 0.5)) / size - 1, ny = 1 - (2 * (y + 0.5)) / size;
      const d = [0, 1, 2].map((k) => b.forward[k]! + nx * b.right[k]! + ny * b.up[k]!);
      rays.push({ origin: b.position, direction: d as unknown as Vec3, tMin: 0, tMax: far });
    }
  }
  const boxes = prepared.levels?.boxes ?? prepared.bvh.bounds.subarray(0, 6);
  const { lo, hi } = spread;
  const rnd = makeRandom(17);
  const inside = () => [0, 1, 2].map((k) => lo[k]! + rnd() * (hi[k]! - lo[k]!)) as unknown as Vec3;
  for (let i = 0; i < spread.random; i++) {
    let d: Vec3 = [rnd() * 2 - 1, rnd() * 2 - 1, rnd() * 2 - 1];
    if (i % 16 === 0) d = [[1, 0, 0], [0, -1, 0], [0, 0, 1]][i % 3] as unknown as Vec3;
    rays.push({ origin: inside(), direction: d, tMin: 0, tMax: i % 4 === 1 ? rnd() * 3 : far });
  }
  for (let g = 1; prepared.levels && g < boxes.length / 6; g++) {
    for (let i = 0; i < spread.perInstance; i++) {
      const o = inside();
      const target = [0, 1, 2].map((k) => boxes[g * 6 + k]! + rnd() * (boxes[g * 6 + 3 + k]! - boxes[g * 6 + k]!));
      rays.push({ origin: o, direction: [target[0]! - o[0], target[1]! - o[1], target[2]! - o[2]], tMin: 0, tMax: far });
    }
  }
  return rays.map((r) => ({ ...r, origin: r.origin.map(Math.fround) as unknown as Vec3, direction: r.direction.map(Math.fround) as unknown as Vec3, tMax: Math.fround(r.tMax) }));
}

/** Each ray's closest hit (t, source primitive, barycentrics) and whether trace_any finds anything. */
export async function traceOnGpu(device: GPUDevice, prepared: PreparedScene, rays: readonly TestRay[]) {
  const constants: Record<string, number> = {};
  Object.assign(constants, featureConstants(TRAVERSAL_FEATURES, prepared.packed.features));
  const sources = new Map(SHADER_MODULES);
  sources.set('tests/accel-test', KERNEL);
  const kernel = await ComputeKernel.create(device, { module: reflectLinked(linkWgsl('tests/accel-test', sources)), entryPoint: 'accel_test', constants });
  const scene = await SceneResources.upload(device, prepared.packed, prepared.scene.name);
  const rayBuffer = storageBuffer(device, 'accel test rays', packRays(rays));
  const out = outputBuffer(device, 'accel test hits', rays.length * 20);
  const encoder = device.createCommandEncoder();
  const pass = encoder.beginComputePass();
  kernel.dispatch(pass, { 0: kernel.bindGroup(0, scene.bindings), 2: kernel.bindGroup(2, { rays: rayBuffer, out }) }, Math.ceil(rays.length / 64));
  pass.end();
  device.queue.submit([encoder.finish()]);
  const raw = await readBuffer(device, out);
  rayBuffer.destroy();
  out.destroy();
  scene.destroy();
  const f = new Float32Array(raw), u = new Uint32Array(raw);
  return rays.map((_, i) => ({ t: f[i * 5]!, tri: u[i * 5 + 1]!, u: f[i * 5 + 2]!, v: f[i * 5 + 3]!, any: u[i * 5 + 4] === 1 }));
}

const NO_TRIANGLE = 0xffffffff;
/** Barycentric distance from an edge under which a ray is taken to graze it. */
const EDGE = 1e-3;

/**
 * Holds the GPU's hits (traceOnGpu) to the CPU oracle's (bvh/levels.ts traceScene through `accel`):
 * distances to a relative tolerance, a different primitive only where it is a genuine tie or the ray
 * grazes an edge; with moving instances, enough rays hit them. `label` starts the log line.
 */
export function expectHitsMatchOracle(prepared: PreparedScene, rays: readonly TestRay[], gpu: Awaited<ReturnType<typeof traceOnGpu>>, accel: Grid | WideBvh | undefined, label = ''): void {
  const { positions, kinds } = prepared.triangles;
  let exact = 0, ties = 0, grazing = 0, hits = 0;
  const failures: string[] = [];
  rays.forEach((ray, i) => {
    const cpu = traceScene(prepared.scene, prepared.triangles, prepared.bvh, prepared.levels, ray, accel);
    const g = gpu[i]!;
    const onEdge = (u: number, v: number, prim: number) => kinds[prim] !== 0 || Math.min(u, v, 1 - u - v) < EDGE;
    // Any hit is whether the closest hit exists.
    if (g.any !== (g.tri !== NO_TRIANGLE) && !(cpu && onEdge(cpu.u, cpu.v, cpu.triangle))) failures.push(`ray ${i}: any ${g.any}, closest ${g.tri === NO_TRIANGLE ? 'miss' : g.tri}`);
    if (cpu) hits++;
    if (!cpu || g.tri === NO_TRIANGLE) {
      if (!cpu && g.tri === NO_TRIANGLE) exact++;
      else if (cpu && onEdge(cpu.u, cpu.v, cpu.triangle)) grazing++;
      else if (!cpu && onEdge(g.u, g.v, g.tri)) grazing++;
      else failures.push(`ray ${i}: cpu ${cpu ? `hit ${cpu.triangle} at ${cpu.t}` : 'miss'}, gpu ${g.tri === NO_TRIANGLE ? 'miss' : `hit ${g.tri} at ${g.t}`}`);
      return;
    }
    const relative = Math.abs(g.t - cpu.t) / Math.max(cpu.t, 1e-3);
    if (g.tri === cpu.triangle && relative < 1e-4) {
      exact++;
      return;
    }
    const tAlt = intersectPrimitive(positions, kinds, g.tri, prepareRay(ray), 0, 3e38, { u: 0, v: 0 });
    if (Math.abs(tAlt - cpu.t) / Math.max(cpu.t, 1e-3) < 1e-4 || (onEdge(cpu.u, cpu.v, cpu.triangle) && relative < 1e-3)) ties++;
    else failures.push(`ray ${i}: cpu ${cpu.triangle} at ${cpu.t}, gpu ${g.tri} at ${g.t} (oracle has it at ${tAlt})`);
  });
  console.log(`${label}${rays.length} rays: ${hits} hits, ${exact} exact, ${ties} ties, ${grazing} grazing`);
  expect(failures.slice(0, 10)).toEqual([]);
  expect(hits).toBeGreaterThan(rays.length / 6);
  expect(ties + grazing).toBeLessThan(0.01 * rays.length);
  if (prepared.levels) {
    const moving = new Set(prepared.levels.dynamic);
    expect(gpu.filter((g) => g.tri !== NO_TRIANGLE && moving.has(prepared.triangles.instanceIds[g.tri]!)).length).toBeGreaterThan(30);
  }
}

/** What an oracle counts along one ray: nodes (or cells) visited and primitives tested. */
export interface TraversalCounts {
  readonly nodesVisited: number;
  readonly trianglesTested: number;
}

/** The view's basis for an image of the given aspect as the GPU holds it (f32). */
export function f32Basis(prepared: PreparedScene, aspect: number): CameraBasis {
  const b = cameraBasis(prepared.scene.camera, aspect);
  const r = (v: Vec3): Vec3 => v.map(Math.fround) as unknown as Vec3;
  return { position: r(b.position), right: r(b.right), up: r(b.up), forward: r(b.forward) };
}

/** view/bindings.wgsl camera_ray through a point (pixels) of a width × height image, in f64, turned by (dx, dy) in ndc. */
export function cameraRay(b: CameraBasis, width: number, height: number, px: number, py: number, dx = 0, dy = 0): { origin: Vec3; direction: Vec3 } {
  const nx = (2 * px) / width - 1 + dx, ny = (2 * py) / height - 1 + dy;
  const d = [0, 1, 2].map((k) => b.forward[k]! + nx * b.right[k]! - ny * b.up[k]!);
  const len = Math.hypot(...d);
  return { origin: b.position, direction: d.map((v) => Math.fround(v / len)) as unknown as Vec3 };
}

/**
 * Checks each pixel's GPU counts (`gpu(i)`: "nodes,triangles" of pixel i) against `oracle`'s for
 * the pixel-centre ray, turned a little in ndc: where the turns change the oracle's counts the ray
 * grazes a box face, a cell boundary or an edge and either count is right, in fewer than
 * `unstableShare` of the pixels.
 */
export function expectCountsMatchOracle(
  width: number,
  height: number,
  gpu: (i: number) => string,
  oracle: (px: number, py: number, dx: number, dy: number) => TraversalCounts,
  unstableShare: number,
): void {
  let exact = 0, unstable = 0;
  const failures: string[] = [];
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const key = gpu(y * width + x);
      const counts = [0, 1e-6, -1e-6, 1e-5, -1e-5, 3e-4, -3e-4].flatMap((t) => [[t, 0], [0, t]]).map(([dx, dy]) => {
        const c = oracle(x + 0.5, y + 0.5, dx!, dy!);
        return `${c.nodesVisited},${c.trianglesTested}`;
      });
      if (counts.every((c) => c === counts[0])) {
        if (key === counts[0]) exact++;
        else failures.push(`pixel (${x}, ${y}): gpu ${key}, cpu ${counts[0]}`);
      } else {
        unstable++;
        if (!counts.includes(key)) failures.push(`pixel (${x}, ${y}): gpu ${key}, cpu ${counts.join(' | ')}`);
      }
    }
  }
  expect(failures.slice(0, 10)).toEqual([]);
  expect(unstable).toBeLessThan(unstableShare * width * height);
  expect(exact + unstable).toBe(width * height);
}

/**
 * Renders the bvh-teaching scene's heat-nodes view through `accel` at width × height and checks every
 * pixel's counts against `oracle` tracing the same pixel-centre ray on the CPU (expectCountsMatchOracle,
 * fewer than 5 % of the pixels grazing). The heat map must show more than `distinct` levels.
 */
export async function expectHeatMatchesOracle(
  renderer: Renderer,
  accel: RenderSettings['accel'],
  width: number,
  height: number,
  oracle: (prepared: PreparedScene, ray: { origin: Vec3; direction: Vec3 }) => TraversalCounts,
  distinct: number,
): Promise<PreparedScene> {
  renderer.updateSettings({ accel });
  const prepared = await renderer.setScene(builtinScene('bvh-teaching'));
  await renderer.resize(width, height);
  renderer.updateSettings({ debugLayout: 'replace', debugView: 'heat-nodes' });
  const heat = await renderer.readDebugValues();
  const b = f32Basis(prepared, width / height);
  expectCountsMatchOracle(
    width,
    height,
    (i) => `${heat[i * 4]},${heat[i * 4 + 1]}`,
    (px, py, dx, dy) => oracle(prepared, cameraRay(b, width, height, px, py, dx, dy)),
    0.05,
  );
  expect(new Set(Array.from({ length: width * height }, (_, i) => heat[i * 4]!)).size).toBeGreaterThan(distinct);
  return prepared;
}
