/**
 * Textured materials on the GPU against analytic answers: alpha masks let every ray through their
 * holes (closest hit and shadow rays alike); textured albedo and emission decode sRGB and give the
 * furnace's 1/(1 − a); a sky panorama is looked up by viewing direction; the torch delivers I/d².
 */
import { placeEachOnce } from '../../src/scene/instances.ts';
import { IDENTITY } from '../../src/math/mat4.ts';
import { describe, expect, it } from 'vitest';
import { readBuffer } from '../../src/gpu/readback.ts';
import { SceneResources } from '../../src/gpu/scene-resources.ts';
import { StructArray } from '../../src/gpu/pack/struct-array.ts';
import { reflectModule, structLayout } from '../../src/gpu/wgsl/reflect.ts';
import { MeshBuilder } from '../../src/scene/builder.ts';
import { TraceRaysPass } from '../../src/passes/trace-rays-pass.ts';
import { prepareScene } from '../../src/renderer/prepare.ts';
import { Renderer } from '../../src/renderer/renderer.ts';
import type { Vec3 } from '../../src/math/vec3.ts';
import type { Camera, Material, Scene, Texture } from '../../src/scene/types.ts';
import { testGpu } from './gpu-context.ts';
import { outputBuffer, runOnce, storageBuffer, testKernel } from './compute.ts';

const srgbToLinear = (c: number) => {
  const v = c / 255;
  return v <= 0.04045 ? v / 12.92 : ((v + 0.055) / 1.055) ** 2.4;
};

function solid(name: string, width: number, height: number, texel: (x: number, y: number) => [number, number, number, number]): Texture {
  const rgba = new Uint8Array(width * height * 4);
  for (let y = 0; y < height; y++) for (let x = 0; x < width; x++) rgba.set(texel(x, y), (y * width + x) * 4);
  return { name, width, height, rgba, filter: 'nearest' };
}

/** A quad with uvs (0,0) top left .. (1,1) bottom right over corners a (top left), b (top right), c, d. */
function uvQuad(positions: number[], uvs: number[], indices: number[], a: Vec3, b: Vec3, c: Vec3, d: Vec3): void {
  const base = positions.length / 3;
  positions.push(...a, ...b, ...c, ...d);
  uvs.push(0, 0, 1, 0, 1, 1, 0, 1);
  indices.push(base, base + 1, base + 2, base, base + 2, base + 3);
}

function meshScene(name: string, quads: { corners: [Vec3, Vec3, Vec3, Vec3]; material: number }[], materials: Material[], textures: Texture[], camera: Camera): Scene {
  const positions: number[] = [], uvs: number[] = [], indices: number[] = [], materialIds: number[] = [];
  for (const q of quads) {
    uvQuad(positions, uvs, indices, ...q.corners);
    materialIds.push(q.material, q.material);
  }
  return {
    name,
    meshes: [{ name, positions: new Float32Array(positions), indices: new Uint32Array(indices), uvs: new Float32Array(uvs), materialIds: new Uint32Array(materialIds) }],
    instances: [{ id: 0, mesh: 0, worldFromObject: IDENTITY }],
    materials,
    textures,
    camera,
  };
}

const camera: Camera = { position: [0, 0, -5], forward: [0, 0, 1], up: [0, 1, 0], vfovDegrees: 40 };

// A 4×4 checkerboard mask on a quad at z = 0 spanning [-1, 1]², in front of a back wall at z = 1.
const checker = solid('checker', 4, 4, (x, y) => ((x + y) % 2 === 0 ? [200, 100, 50, 255] : [0, 0, 0, 0]));
const maskScene = meshScene(
  'mask',
  [
    { corners: [[-1, 1, 0], [1, 1, 0], [1, -1, 0], [-1, -1, 0]], material: 0 },
    { corners: [[-2, 2, 1], [2, 2, 1], [2, -2, 1], [-2, -2, 1]], material: 1 },
  ],
  [
    { kind: 'diffuse', name: 'mask', albedo: [1, 1, 1], emission: [0, 0, 0], albedoTexture: { texture: 0 }, alphaMode: 'mask' },
    { kind: 'diffuse', name: 'wall', albedo: [0.5, 0.5, 0.5], emission: [0, 0, 0] },
  ],
  [checker],
  camera,
);

/** Rays along +z through the centre of every checker texel. The texel's column x sits at world x = −1 + (x + ½)/2. */
function checkerRays(tMax: number): { origin: Vec3; direction: Vec3; tMax: number; opaque: boolean }[] {
  const rays = [];
  for (let y = 0; y < 4; y++) for (let x = 0; x < 4; x++) rays.push({ origin: [-1 + (x + 0.5) / 2, 1 - (y + 0.5) / 2, -1] as Vec3, direction: [0, 0, 1] as Vec3, tMax, opaque: (x + y) % 2 === 0 });
  return rays;
}

function rayBytes(rays: { origin: Vec3; direction: Vec3; tMax: number }[]): ArrayBuffer {
  const a = new StructArray(structLayout(reflectModule('passes/trace-rays').defs, 'Ray'), rays.length);
  const o = a.vec3('origin'), d = a.vec3('direction'), tmax = a.f32Field('t_max');
  rays.forEach((r, i) => {
    o(i, ...r.origin);
    d(i, ...r.direction);
    tmax(i, r.tMax);
  });
  return a.bytes;
}

describe('alpha masks', () => {
  it('closest hits pass through transparent texels to the wall behind', async () => {
    const { device } = await testGpu();
    const prepared = prepareScene(maskScene);
    const scene = await SceneResources.upload(device, prepared.packed, 'mask');
    const rays = checkerRays(100);
    const rayBuffer = storageBuffer(device, 'rays', rayBytes(rays));
    const hitLayout = structLayout(reflectModule('passes/trace-rays').defs, 'HitRecord');
    const hits = outputBuffer(device, 'hits', hitLayout.stride * rays.length);
    const pass = await TraceRaysPass.create(device);
    const encoder = device.createCommandEncoder();
    pass.encode(encoder, { binding: await pass.bind(scene, rayBuffer, hits, rays.length) });
    device.queue.submit([encoder.finish()]);
    const out = new Float32Array(await readBuffer(device, hits));
    rays.forEach((r, i) => {
      const t = out[i * hitLayout.strideWords + hitLayout.word('t')]!;
      expect(t).toBeCloseTo(r.opaque ? 1 : 2, 4);
    });
    scene.destroy();
  });

  it('shadow rays (any hit) pass through the holes too', async () => {
    const { device } = await testGpu();
    const prepared = prepareScene(maskScene);
    const scene = await SceneResources.upload(device, prepared.packed, 'mask');
    // Shadow rays that end between the mask (t = 1) and the wall (t = 2).
    const rays = checkerRays(1.5);
    const code = `
#import scene/bvh
@group(3) @binding(0) var<storage, read> test_rays: array<Ray>;
@group(3) @binding(1) var<storage, read_write> occluded: array<u32>;
@compute @workgroup_size(16) fn any_hit(@builtin(global_invocation_id) id: vec3u) {
  occluded[id.x] = select(0u, 1u, trace_any(test_rays[id.x]));
}`;
    const kernel = await testKernel(device, 'test/any-hit', code, 'any_hit');
    const out = outputBuffer(device, 'occluded', rays.length * 4);
    const result = new Uint32Array(
      await runOnce(device, kernel, { 0: kernel.bindGroup(0, scene.bindings), 3: kernel.bindGroup(3, { test_rays: storageBuffer(device, 'rays', rayBytes(rays)), occluded: out }) }, [1], out),
    );
    expect([...result]).toEqual(rays.map((r) => (r.opaque ? 1 : 0)));
    scene.destroy();
  });
});

/** Radiance of the centre pixel (and its standard error) of a small render. */
async function renderCentre(scene: Scene, spp: number, settings: Parameters<Renderer['updateSettings']>[0] = {}) {
  const renderer = await Renderer.create(await testGpu());
  await renderer.setScene(scene);
  await renderer.resize(5, 5);
  renderer.updateSettings(settings);
  for (let done = 0; done < spp; done += 64) renderer.accumulate(Math.min(64, spp - done));
  const acc = await renderer.readAccumulation();
  renderer.destroy();
  const i = 12;
  return { rgb: [acc.radiance[i * 3]!, acc.radiance[i * 3 + 1]!, acc.radiance[i * 3 + 2]!], se: Math.sqrt(acc.luminanceVariance[i]! / acc.samples), all: acc };
}

/** A closed unit cube seen from inside, every face wound to face inward, all of one material. */
function insideCube(material: Material, textures: Texture[], cam: Camera): Scene {
  const b = new MeshBuilder('cube');
  const m = b.material(material);
  const p = (x: number, y: number, z: number): Vec3 => [x, y, z];
  b.quad(m, p(-1, -1, -1), p(-1, -1, 1), p(1, -1, 1), p(1, -1, -1));
  b.quad(m, p(-1, 1, -1), p(1, 1, -1), p(1, 1, 1), p(-1, 1, 1));
  b.quad(m, p(-1, -1, -1), p(-1, 1, -1), p(-1, 1, 1), p(-1, -1, 1));
  b.quad(m, p(1, -1, -1), p(1, -1, 1), p(1, 1, 1), p(1, 1, -1));
  b.quad(m, p(-1, -1, -1), p(1, -1, -1), p(1, 1, -1), p(-1, 1, -1));
  b.quad(m, p(-1, -1, 1), p(-1, 1, 1), p(1, 1, 1), p(1, -1, 1));
  const mesh = b.build();
  // uvs anywhere: the textures are constant.
  return { name: 'cube', meshes: [{ ...mesh, uvs: new Float32Array((mesh.positions.length / 3) * 2).fill(0.3) }], instances: placeEachOnce([mesh]), materials: b.materials, textures, camera: cam };
}

describe('textured materials', () => {
  it('a textured furnace converges to e / (1 − a) with a and e decoded from sRGB', async () => {
    const albedo = solid('grey', 2, 2, () => [188, 188, 188, 255]);
    const glow = solid('glow', 2, 2, () => [128, 128, 128, 255]);
    const a = srgbToLinear(188), e = 2 * srgbToLinear(128);
    const scene = insideCube({ kind: 'diffuse', name: 'textured', albedo: [1, 1, 1], emission: [2, 2, 2], albedoTexture: { texture: 0 }, emissionTexture: { texture: 1 } }, [albedo, glow], { position: [0.1, 0.2, -0.3], forward: [0.2, 0.1, 1], up: [0, 1, 0], vfovDegrees: 60 });
    const { all } = await renderCentre(scene, 512, { maxBounces: 256 });
    const mean = all.radiance.reduce((s, v) => s + v, 0) / all.radiance.length;
    expect(Math.abs(mean - e / (1 - a)) / (e / (1 - a))).toBeLessThan(0.01);
  });

  it('a sky panorama is looked up by viewing direction: a quarter turn per texture column', async () => {
    // Four columns, repeats = 1: azimuth 45°, 135°, 225°, 315° (counter-clockwise from +x seen from
    // above, north = −z) land in the middle of columns 0, 1, 2, 3.
    const colors: [number, number, number, number][] = [[255, 0, 0, 255], [0, 255, 0, 255], [0, 0, 255, 255], [255, 255, 0, 255]];
    const sky = solid('sky', 4, 1, (x) => colors[x]!);
    const expected = colors.map((c) => c.slice(0, 3).map(srgbToLinear));
    for (let k = 0; k < 4; k++) {
      const azimuth = ((45 + 90 * k) * Math.PI) / 180;
      const forward: Vec3 = [Math.cos(azimuth), 0, -Math.sin(azimuth)];
      const scene = insideCube(
        { kind: 'diffuse', name: 'sky', albedo: [0, 0, 0], emission: [1, 1, 1], emissionTexture: { texture: 0 }, emissionMapping: { kind: 'panorama', repeats: 1, horizonV: 0.5, vPerRadian: 0.3 } },
        [sky],
        { position: [0, 0, 0], forward, up: [0, 1, 0], vfovDegrees: 10 },
      );
      const { rgb } = await renderCentre(scene, 4, { maxBounces: 0 });
      rgb.forEach((c, i) => expect(c).toBeCloseTo(expected[k]![i]!, 3));
    }
  });

  it('the torch lights a wall at distance d with E = I/d² (times its range window)', async () => {
    // A grey wall at z = d facing the camera; the torch (radius r ≪ d) sits at the camera. The wall
    // point straight ahead then has radiance ρ/π · I/d² · (1 − (d/range)⁴)².
    const d = 4, range = 10, intensity = 50, rho = 0.5;
    const scene = meshScene(
      'torch',
      [{ corners: [[-50, 50, d], [50, 50, d], [50, -50, d], [-50, -50, d]], material: 0 }],
      [{ kind: 'diffuse', name: 'wall', albedo: [rho, rho, rho], emission: [0, 0, 0] }],
      [],
      { position: [0, 0, 0], forward: [0, 0, 1], up: [0, 1, 0], vfovDegrees: 1 },
    );
    const { rgb, se } = await renderCentre({ ...scene, torch: { color: [1, 1, 1], intensity, range, radius: 0.05 } }, 256, { maxBounces: 1 });
    const window = (1 - (d / range) ** 4) ** 2;
    const expected = (rho / Math.PI) * (intensity / (d * d)) * window;
    expect(Math.abs(rgb[1]! - expected)).toBeLessThan(Math.max(5 * se, 2e-3 * expected));
    // Off: no light at all in this scene.
    const off = await renderCentre({ ...scene, torch: { color: [1, 1, 1], intensity, range, radius: 0.05 } }, 8, { maxBounces: 1, torch: { enabled: false } });
    expect(off.rgb).toEqual([0, 0, 0]);
  });
});
