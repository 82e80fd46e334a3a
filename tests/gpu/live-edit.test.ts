/**
 * Live editing on the GPU: Renderer.pick against the CPU oracle (bvh/traverse.ts) for pixels of the
 * Cornell box; Renderer.updateMaterials renders exactly what a scene prepared from scratch with the
 * edited materials renders (colour, roughness and emission edits, an emitter appearing where there
 * was none); the selection outline changes what present() draws only at and around the selected
 * part, and never the estimate.
 */
import { describe, expect, it } from 'vitest';
import { traverseClosest } from '../../src/bvh/traverse.ts';
import { LanternError } from '../../src/errors.ts';
import { expectLanternError } from '../../src/expect-lantern-error.ts';
import { readTexture4x8 } from '../../src/gpu/readback.ts';
import { primaryRay } from '../../src/gpu/view.ts';
import type { Vec3 } from '../../src/math/vec3.ts';
import { builtinScene } from '../../src/loaders/builtin/index.ts';
import { prepareScene } from '../../src/renderer/prepare.ts';
import { Renderer } from '../../src/renderer/renderer.ts';
import { applyMaterialEdit, type MaterialEdit } from '../../src/scene/material-edit.ts';
import { diffuse, metallicRoughness, type Scene } from '../../src/scene/types.ts';
import { IDENTITY, translation } from '../../src/math/mat4.ts';
import { testGpu } from './gpu-context.ts';
import { renderScene } from './scene-render.ts';

const W = 24, H = 20;

async function cornellRenderer(): Promise<{ renderer: Renderer; scene: Scene }> {
  const renderer = await Renderer.create(await testGpu());
  const scene = builtinScene('cornell');
  await renderer.setScene(scene);
  await renderer.resize(W, H);
  return { renderer, scene };
}

describe('Renderer.pick', () => {
  it('equals the CPU oracle for pixels of the Cornell box', async () => {
    const { renderer } = await cornellRenderer();
    try {
      const prepared = renderer.scene!;
      const camera = prepared.scene.camera;
      const pixels: [number, number][] = [[1, 10], [22, 10], [12, 2], [12, 18], [8, 14], [16, 9], [12, 10], [3, 3], [20, 17], [0, 0]];
      let hits = 0;
      for (const [x, y] of pixels) {
        const ray = primaryRay(camera, W, H, x + 0.5, y + 0.5);
        const f32 = { origin: ray.origin.map(Math.fround) as unknown as Vec3, direction: ray.direction.map(Math.fround) as unknown as Vec3 };
        const cpu = traverseClosest(prepared.bvh, prepared.triangles.positions, f32);
        const gpu = await renderer.pick(x + 0.3, y + 0.8);
        if (!cpu) {
          expect(gpu, `pixel ${x},${y}`).toBeNull();
          continue;
        }
        hits++;
        expect(gpu, `pixel ${x},${y}`).not.toBeNull();
        expect(gpu!.primitive).toBe(cpu.triangle);
        expect(gpu!.distance).toBeCloseTo(cpu.t, 1);
        expect(Math.abs(gpu!.distance - cpu.t) / cpu.t).toBeLessThan(1e-4);
        expect(gpu!.material).toBe(prepared.triangles.materialIds[cpu.triangle]);
        expect(gpu!.instanceIndex).toBe(prepared.triangles.instanceIds[cpu.triangle]);
        expect(gpu!.instanceId).toBe(prepared.scene.instances[gpu!.instanceIndex]!.id);
        // The camera looks along +z: depth is the hit's z minus the camera's.
        expect(gpu!.depth).toBeCloseTo(gpu!.position[2] - camera.position[2], 2);
        for (let k = 0; k < 3; k++) expect(gpu!.position[k]).toBeCloseTo(ray.origin[k]! + cpu.t * ray.direction[k]!, 1);
      }
      expect(hits).toBeGreaterThan(5);
      // The left edge shows the red wall, the right edge the green one (cornell.ts).
      const names = (p: Awaited<ReturnType<Renderer['pick']>>) => prepared.scene.materials[p!.material]!.name;
      expect(names(await renderer.pick(3, 10))).toBe('red');
      expect(names(await renderer.pick(W - 4, 10))).toBe('green');
      await expect(renderer.pick(W, 0)).rejects.toThrow(/outside the 24×20 image/);
      await expect(renderer.pick(-1, 0)).rejects.toBeInstanceOf(LanternError);
    } finally {
      renderer.destroy();
    }
  });
});

/**
 * The same bytes on the GPU give the same image up to the last bits of a few values (SwiftShader
 * compiles each renderer's pipelines anew; the unit test edit-materials.test.ts holds the packed
 * bytes equal exactly).
 */
function expectSameImage(a: Float32Array, b: Float32Array): void {
  let worst = 0;
  for (let i = 0; i < a.length; i++) worst = Math.max(worst, Math.abs(a[i]! - b[i]!) / Math.max(Math.abs(b[i]!), 1e-3));
  expect(worst).toBeLessThan(1e-5);
}

/** A floor (instance 0) and a mesh of one sphere and one capsule placed by a translation (instance 1), each primitive its own material. */
function analyticScene(): Scene {
  return {
    name: 'sphere and capsule',
    meshes: [
      { name: 'floor', positions: new Float32Array([-4, 0, -4, 4, 0, -4, 4, 0, 4, -4, 0, 4]), indices: new Uint32Array([0, 2, 1, 0, 3, 2]), materialIds: new Uint32Array([0, 0]) },
      {
        name: 'shapes',
        positions: new Float32Array(0),
        indices: new Uint32Array(0),
        materialIds: new Uint32Array(0),
        spheres: { centers: new Float32Array([-1, 1, 0]), radii: new Float32Array([0.9]), materialIds: new Uint32Array([1]) },
        capsules: { endpoints: new Float32Array([1, 0.5, -0.5, 1.5, 1.8, 0.5]), radii: new Float32Array([0.4]), materialIds: new Uint32Array([2]) },
      },
    ],
    instances: [
      { id: 10, mesh: 0, worldFromObject: IDENTITY },
      { id: 11, mesh: 1, worldFromObject: translation([0, 0.1, 0]) },
    ],
    materials: [diffuse('floor', [0.5, 0.5, 0.5]), diffuse('sphere', [0.8, 0.2, 0.2]), diffuse('capsule', [0.2, 0.8, 0.2])],
    camera: { position: [0, 2.5, 6], forward: [0, -0.35, -1], up: [0, 1, 0], vfovDegrees: 50 },
    environment: { kind: 'constant', radiance: [1, 1, 1] },
  };
}

describe('Renderer.pick on spheres and capsules', () => {
  it('equals the CPU oracle and names the instance and material of each primitive kind', async () => {
    const renderer = await Renderer.create(await testGpu());
    try {
      await renderer.setScene(analyticScene());
      await renderer.resize(W, H);
      const prepared = renderer.scene!;
      const seen = new Set<string>();
      for (let y = 1; y < H; y += 3) {
        for (let x = 1; x < W; x += 3) {
          const ray = primaryRay(prepared.scene.camera, W, H, x + 0.5, y + 0.5);
          const f32 = { origin: ray.origin.map(Math.fround) as unknown as Vec3, direction: ray.direction.map(Math.fround) as unknown as Vec3 };
          const cpu = traverseClosest(prepared.bvh, prepared.triangles.positions, f32, prepared.triangles.kinds);
          const gpu = await renderer.pick(x, y);
          expect(gpu === null, `pixel ${x},${y}`).toBe(cpu === null);
          if (!cpu || !gpu) continue;
          expect(Math.abs(gpu.distance - cpu.t) / cpu.t, `pixel ${x},${y}`).toBeLessThan(1e-4);
          // The floor's two triangles share a diagonal: a tie there is either.
          if (gpu.primitive !== cpu.triangle) expect(gpu.material).toBe(0);
          else expect(gpu.material).toBe(prepared.triangles.materialIds[cpu.triangle]);
          expect(gpu.instanceId).toBe(gpu.material === 0 ? 10 : 11);
          seen.add(prepared.scene.materials[gpu.material]!.name);
        }
      }
      expect([...seen].sort()).toEqual(['capsule', 'floor', 'sphere']);
    } finally {
      renderer.destroy();
    }
  });
});

describe('Renderer.updateMaterials', () => {
  const o = { width: 16, height: 16, spp: 4, maxBounces: 3, seed: 5 };
  const edited = (scene: Scene, edits: Map<number, MaterialEdit>): Scene => ({ ...scene, materials: scene.materials.map((m, i) => (edits.has(i) ? applyMaterialEdit(m, edits.get(i)!) : m)) });

  it.each([
    ['a colour', new Map<number, MaterialEdit>([[1, { color: [0.1, 0.2, 0.9] }]])],
    ['the light\'s emission', new Map<number, MaterialEdit>([[3, { emission: [30, 10, 2] }]])],
    ['a wall that starts to glow (the light table grows)', new Map<number, MaterialEdit>([[2, { emission: [2, 4, 2] }]])],
  ])('%s renders what a scene prepared with it renders', async (_, edits) => {
    const scene = builtinScene('cornell');
    const live = await renderScene(scene, o, (r) => {
      r.updateMaterials(edits);
    });
    const fresh = await renderScene(prepareScene(edited(scene, edits)), o);
    const before = await renderScene(scene, o);
    expectSameImage(live.radiance, fresh.radiance);
    // And the edit did change the image.
    let changed = 0;
    for (let i = 0; i < before.radiance.length; i++) if (before.radiance[i] !== live.radiance[i]) changed++;
    expect(changed).toBeGreaterThan(before.radiance.length / 10);
  });

  it('edits roughness, metallic, IOR and transmission of a glTF material, as a fresh preparation does', async () => {
    const base = builtinScene('cornell');
    const scene: Scene = { ...base, materials: base.materials.map((m, i) => (i === 0 ? metallicRoughness('floor', { baseColor: [0.8, 0.8, 0.8], roughness: 0.6, metallic: 0 }) : m)) };
    const edits = new Map<number, MaterialEdit>([[0, { roughness: 0.15, metallic: 0.7, ior: 1.8, transmission: 0.2, color: [0.9, 0.6, 0.3] }]]);
    const live = await renderScene(scene, o, (r) => {
      r.updateMaterials(edits);
    });
    const fresh = await renderScene(prepareScene(edited(scene, edits)), o);
    expectSameImage(live.radiance, fresh.radiance);
  });

  it('refuses a field the kind lacks, naming it', async () => {
    await renderScene(builtinScene('cornell'), o, (r) => {
      expectLanternError(() => r.updateMaterials(new Map([[1, { roughness: 0.5 }]])), /diffuse material has no roughness/);
    });
  });
});

describe('the selection outline', () => {
  it('changes what present() draws only on and next to the selected part, and not the estimate', async () => {
    const { renderer } = await cornellRenderer();
    const device = renderer.device;
    const target = device.createTexture({ size: [W, H], format: 'rgba8unorm', usage: GPUTextureUsage.RENDER_ATTACHMENT | GPUTextureUsage.COPY_SRC });
    try {
      renderer.updateSettings({ maxBounces: 2, seed: 3 });
      await renderer.setPresentationFormat('rgba8unorm');
      renderer.accumulate(2);
      const drawn = async () => {
        renderer.present(target);
        return readTexture4x8(device, target);
      };
      const plain = await drawn();
      const estimate = await renderer.readImage();
      const red = (await renderer.pick(3, 10))!;
      await renderer.setSelection({ instanceIndex: red.instanceIndex, material: red.material });
      const outlined = await drawn();
      expect(await renderer.readImage()).toEqual(estimate);
      // Which pixels see the red wall, by the oracle's picks.
      const prepared = renderer.scene!;
      const onRed: boolean[] = [];
      for (let y = 0; y < H; y++) {
        for (let x = 0; x < W; x++) {
          const r = primaryRay(prepared.scene.camera, W, H, x + 0.5, y + 0.5);
          const hit = traverseClosest(prepared.bvh, prepared.triangles.positions, r);
          onRed.push(hit !== null && prepared.triangles.materialIds[hit.triangle] === red.material);
        }
      }
      const near = (x: number, y: number) => [-1, 0, 1].some((dy) => [-1, 0, 1].some((dx) => onRed[(y + dy) * W + x + dx] === true && x + dx >= 0 && x + dx < W));
      let changed = 0;
      for (let y = 0; y < H; y++) {
        for (let x = 0; x < W; x++) {
          const i = (y * W + x) * 4;
          const differs = [0, 1, 2].some((c) => plain[i + c] !== outlined[i + c]);
          if (differs) {
            changed++;
            expect(near(x, y), `pixel ${x},${y} changed far from the selection`).toBe(true);
          }
        }
      }
      expect(changed).toBeGreaterThan(onRed.filter(Boolean).length);
      await renderer.setSelection(undefined);
      expect(await drawn()).toEqual(plain);
    } finally {
      target.destroy();
      renderer.destroy();
    }
  });
});
