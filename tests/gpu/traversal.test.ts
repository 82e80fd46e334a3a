/**
 * GPU traversal (scene/bvh.wgsl through passes/trace-rays.wgsl) against the CPU oracle
 * (bvh/traverse.ts; bvh/levels.ts traceScene for both levels of a scene with moving instances) for every pixel of small images and for random rays, on several scenes. The GPU
 * computes in f32 and the oracle in f64, so distances agree to a relative tolerance and a different
 * triangle is accepted only where it is a genuine tie: the oracle itself hits the GPU's triangle at
 * the same distance (a shared edge), or the ray grazes an edge (both answers are right).
 */
import { IDENTITY } from '../../src/math/mat4.ts';
import { describe, expect, it } from 'vitest';
import { traceScene } from '../../src/bvh/levels.ts';
import { prepareRay, intersectPrimitive } from '../../src/bvh/ray.ts';
import { quadGrid, randomSoup, soupScene, uvSphere, makeRandom, movingTestScene } from '../../src/bvh/test-scenes.ts';
import { createBufferWithData, readBuffer } from '../../src/gpu/readback.ts';
import { SceneResources } from '../../src/gpu/scene-resources.ts';
import { builtinScene } from '../../src/loaders/builtin/index.ts';
import { packRays, rayBufferStrides, TraceRaysPass, unpackHits } from '../../src/passes/trace-rays-pass.ts';
import { prepareScene, type PreparedScene } from '../../src/renderer/prepare.ts';
import { cameraBasis } from '../../src/gpu/view.ts';
import type { Vec3 } from '../../src/math/vec3.ts';
import type { Scene } from '../../src/scene/types.ts';
import { testGpu } from './gpu-context.ts';

const SIZE = 48;


/**
 * Spheres and capsules among triangles: random small ones, nested and touching ones, long thin
 * capsules, a capsule with a = b, and the huge ground sphere (radius 1000) of the tutorial scenes.
 */
function analyticScene(): Scene {
  const rnd = makeRandom(5);
  const centers: number[] = [], radii: number[] = [], endpoints: number[] = [], capsuleRadii: number[] = [];
  for (let i = 0; i < 60; i++) {
    centers.push(rnd() * 16 - 8, rnd() * 6, rnd() * 16 - 8);
    radii.push(0.1 + rnd() * 0.9);
  }
  centers.push(0, -1000, 0, 2, 1, 2, 2, 1, 2);
  radii.push(1000, 1, 0.5); // the ground, and a sphere inside another
  for (let i = 0; i < 60; i++) {
    const a = [rnd() * 16 - 8, rnd() * 6, rnd() * 16 - 8];
    const len = i % 10 === 0 ? 0 : 0.2 + rnd() * 4;
    const d = [rnd() - 0.5, rnd() - 0.5, rnd() - 0.5];
    const dl = Math.hypot(d[0]!, d[1]!, d[2]!);
    endpoints.push(a[0]!, a[1]!, a[2]!, a[0]! + (d[0]! / dl) * len, a[1]! + (d[1]! / dl) * len, a[2]! + (d[2]! / dl) * len);
    capsuleRadii.push(0.05 + rnd() * 0.4);
  }
  const soup = randomSoup(200, 3, 0.4);
  const nt = soup.length / 9;
  return {
    name: 'analytic',
    meshes: [
      {
        name: 'mixed',
        positions: soup,
        indices: Uint32Array.from({ length: nt * 3 }, (_, i) => i),
        materialIds: new Uint32Array(nt),
        spheres: { centers: new Float32Array(centers), radii: new Float32Array(radii), materialIds: new Uint32Array(radii.length) },
        capsules: { endpoints: new Float32Array(endpoints), radii: new Float32Array(capsuleRadii), materialIds: new Uint32Array(capsuleRadii.length) },
      },
    ],
    instances: [{ id: 0, mesh: 0, worldFromObject: IDENTITY }],
    materials: [{ kind: 'diffuse', name: 'grey', albedo: [0.5, 0.5, 0.5], emission: [0, 0, 0] }],
    camera: { position: [13, 2, 3], forward: [-13, -2, -3], up: [0, 1, 0], vfovDegrees: 60 },
  };
}

const SCENES: [string, () => Scene][] = [
  ['spheres and capsules among triangles', analyticScene],
  ['cornell', () => builtinScene('cornell')],
  ['furnace (inside a closed box)', () => builtinScene('furnace')],
  ['random soup', () => soupScene('soup', randomSoup(3000, 7), { position: [0, 0, -30], forward: [0, 0, 1], up: [0, 1, 0], vfovDegrees: 50 })],
  ['UV sphere', () => soupScene('sphere', uvSphere(24, 48, 2), { position: [0.3, 0.2, -6], forward: [0, 0, 1], up: [0, 1, 0], vfovDegrees: 45 })],
  ['flat quad grid', () => soupScene('grid', quadGrid(16), { position: [8, 8, -12], forward: [0, 0, 1], up: [0, 1, 0], vfovDegrees: 70 })],
  ['moving instances (two levels: shared, rotated, scaled, mirrored meshes and spheres)', movingTestScene],
  ['everything moving (an empty static world: the top level alone)', () => {
    const s = movingTestScene();
    return { ...s, instances: s.instances.map((i) => ({ ...i, moves: true })) };
  }],
];

interface TestRay {
  origin: Vec3;
  direction: Vec3;
}

/** A ray per pixel centre from the scene's camera, then random rays from inside the scene bounds. */
function makeRays(prepared: PreparedScene): TestRay[] {
  const b = cameraBasis(prepared.scene.camera, 1);
  const rays: TestRay[] = [];
  for (let y = 0; y < SIZE; y++) {
    for (let x = 0; x < SIZE; x++) {
      const nx = (2 * (x + 0.5)) / SIZE - 1, ny = 1 - (2 * (y + 0.5)) / SIZE;
      const d: Vec3 = [b.forward[0] + nx * b.right[0] + ny * b.up[0], b.forward[1] + nx * b.right[1] + ny * b.up[1], b.forward[2] + nx * b.right[2] + ny * b.up[2]];
      const len = Math.hypot(...d);
      rays.push({ origin: b.position, direction: [d[0] / len, d[1] / len, d[2] / len] });
    }
  }
  // The scene's bounds: the static world's box with every instance's (an empty static world has none).
  const boxes = prepared.levels?.boxes ?? prepared.bvh.bounds.subarray(0, 6);
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < boxes.length; i += 6) {
    if (!(boxes[i]! <= boxes[i + 3]!)) continue;
    for (let k = 0; k < 3; k++) {
      lo[k] = Math.min(lo[k]!, boxes[i + k]!);
      hi[k] = Math.max(hi[k]!, boxes[i + 3 + k]!);
    }
  }
  const rnd = makeRandom(99);
  for (let i = 0; i < 1024; i++) {
    const o: Vec3 = [0, 1, 2].map((k) => lo[k]! + rnd() * (hi[k]! - lo[k]!)) as unknown as Vec3;
    let d: Vec3 = [rnd() * 2 - 1, rnd() * 2 - 1, rnd() * 2 - 1];
    if (i % 16 === 0) d = [[1, 0, 0], [0, -1, 0], [0, 0, 1]][i % 3] as unknown as Vec3; // axis-aligned, exact zeros
    rays.push({ origin: o, direction: d });
  }
  // Rays aimed into the moving instances' boxes, from anywhere in the scene.
  for (let g = 1; prepared.levels && g < boxes.length / 6; g++) {
    for (let i = 0; i < 256; i++) {
      const o: Vec3 = [0, 1, 2].map((k) => lo[k]! + rnd() * (hi[k]! - lo[k]!)) as unknown as Vec3;
      const target = [0, 1, 2].map((k) => boxes[g * 6 + k]! + rnd() * (boxes[g * 6 + 3 + k]! - boxes[g * 6 + k]!));
      rays.push({ origin: o, direction: [target[0]! - o[0], target[1]! - o[1], target[2]! - o[2]] });
    }
  }
  // Round to what the GPU sees, so both sides trace the very same ray.
  return rays.map((r) => ({ origin: r.origin.map(Math.fround) as unknown as Vec3, direction: r.direction.map(Math.fround) as unknown as Vec3 }));
}

async function traceOnGpu(device: GPUDevice, prepared: PreparedScene, rays: TestRay[]): Promise<{ t: Float32Array; tri: Uint32Array; u: Float32Array; v: Float32Array }> {
  const scene = await SceneResources.upload(device, prepared.packed, prepared.scene.name);
  const rayBuffer = createBufferWithData(device, 'test rays', packRays(rays), GPUBufferUsage.STORAGE);
  const hitBuffer = device.createBuffer({ size: rayBufferStrides().hit * rays.length, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC });
  const pass = await TraceRaysPass.create(device);
  const encoder = device.createCommandEncoder();
  pass.encode(encoder, { binding: await pass.bind(scene, rayBuffer, hitBuffer, rays.length) });
  device.queue.submit([encoder.finish()]);
  const hits = unpackHits(await readBuffer(device, hitBuffer), rays.length);
  const out = { t: Float32Array.from(hits, (h) => h.t), tri: Uint32Array.from(hits, (h) => h.triangle), u: Float32Array.from(hits, (h) => h.u), v: Float32Array.from(hits, (h) => h.v) };
  for (const b of [rayBuffer, hitBuffer]) b.destroy();
  scene.destroy();
  pass.destroy();
  return out;
}

const NO_TRIANGLE = 0xffffffff;
const EDGE = 1e-3;

describe('GPU traversal equals the CPU oracle', () => {
  it.each(SCENES)('%s', async (_, make) => {
    const { device } = await testGpu();
    const prepared = prepareScene(make());
    const rays = makeRays(prepared);
    const gpu = await traceOnGpu(device, prepared, rays);
    const { positions, kinds } = prepared.triangles;
    let exact = 0, ties = 0, grazing = 0;
    const failures: string[] = [];
    rays.forEach((ray, i) => {
      const cpu = traceScene(prepared.scene, prepared.triangles, prepared.bvh, prepared.levels, ray);
      const gpuTri = gpu.tri[i]!;
      // A triangle's edge; for a sphere or capsule, the hit uv says nothing of grazing, so a ray
      // that the other side misses is checked for a near-tangent approach instead.
      const onEdge = (u: number, v: number, prim = cpu?.triangle ?? gpuTri) =>
        kinds[prim] === 0 ? Math.min(u, v, 1 - u - v) < EDGE : grazesAnalytic(positions, kinds, prim, ray);
      if (!cpu || gpuTri === NO_TRIANGLE) {
        if (!cpu && gpuTri === NO_TRIANGLE) exact++;
        else if (cpu && onEdge(cpu.u, cpu.v)) grazing++;
        else if (!cpu && onEdge(gpu.u[i]!, gpu.v[i]!)) grazing++;
        else failures.push(`ray ${i}: cpu ${cpu ? `hit ${cpu.triangle} at ${cpu.t}` : 'miss'}, gpu ${gpuTri === NO_TRIANGLE ? 'miss' : `hit ${gpuTri} at ${gpu.t[i]}`}`);
        return;
      }
      const relative = Math.abs(gpu.t[i]! - cpu.t) / Math.max(cpu.t, 1e-3);
      if (gpuTri === cpu.triangle && relative < 1e-4) {
        exact++;
        return;
      }
      // A different triangle: the oracle must hit it at (nearly) the same distance.
      const bary = { u: 0, v: 0 };
      const tAlt = intersectPrimitive(positions, kinds, gpuTri, prepareRay(ray), 0, 3e38, bary);
      if (Math.abs(tAlt - cpu.t) / Math.max(cpu.t, 1e-3) < 1e-4 || (onEdge(cpu.u, cpu.v) && Math.abs(gpu.t[i]! - cpu.t) / cpu.t < 1e-3)) ties++;
      else failures.push(`ray ${i}: cpu triangle ${cpu.triangle} at ${cpu.t}, gpu triangle ${gpuTri} at ${gpu.t[i]} (oracle has it at ${tAlt})`);
    });
    expect(failures.slice(0, 10)).toEqual([]);
    // With moving instances, enough rays end on them for the two-level path to be tested.
    const moving = new Set(prepared.levels?.dynamic ?? []);
    const onMoving = [...gpu.tri].filter((t) => t !== NO_TRIANGLE && moving.has(prepared.triangles.instanceIds[t]!)).length;
    if (prepared.levels) expect(onMoving).toBeGreaterThan(60);
    // Ties and grazing rays are rare; a systematic traversal bug would not be.
    expect(ties + grazing).toBeLessThan(0.01 * rays.length);
    expect(exact + ties + grazing).toBe(rays.length);
  });
});

/**
 * Whether the ray passes a sphere's or capsule's surface nearly tangentially: the distance from the
 * ray's line to the centre (sphere) or to the axis segment (capsule) is within 2e-3 of the radius.
 */
function grazesAnalytic(positions: Float32Array, kinds: Uint8Array, prim: number, ray: TestRay): boolean {
  const o = prim * 9;
  const len = Math.hypot(...ray.direction);
  const u = ray.direction.map((x) => x / len);
  // Distance from point c to the line.
  const lineDistance = (c: readonly number[]) => {
    const f = [0, 1, 2].map((k) => ray.origin[k]! - c[k]!);
    const b = f[0]! * u[0]! + f[1]! * u[1]! + f[2]! * u[2]!;
    return Math.hypot(f[0]! - b * u[0]!, f[1]! - b * u[1]!, f[2]! - b * u[2]!);
  };
  const a = [positions[o]!, positions[o + 1]!, positions[o + 2]!];
  if (kinds[prim] === 1) return Math.abs(lineDistance(a) - positions[o + 3]!) < 2e-3 * positions[o + 3]!;
  const b = [positions[o + 3]!, positions[o + 4]!, positions[o + 5]!], r = positions[o + 6]!;
  // The line-to-segment distance, by dense sampling along the segment (a test, not a hot path).
  let nearest = Infinity;
  for (let i = 0; i <= 2000; i++) nearest = Math.min(nearest, lineDistance(a.map((x, k) => x + (i / 2000) * (b[k]! - x))));
  return Math.abs(nearest - r) < 2e-3 * r + 2e-3 * Math.hypot(b[0]! - a[0]!, b[1]! - a[1]!, b[2]! - a[2]!) / 2000;
}
