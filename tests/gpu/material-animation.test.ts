/**
 * Doom's animations on the GPU (world/material-animation.ts played by world/world.ts): the state at
 * two times, applied with Renderer.applySceneUpdate, changes exactly the animated surfaces. A tiny
 * WAD (test-wad.ts animatedRoomWad) seen from its player start: a NUKAGE floor cycling through its
 * frames, a scrolling striped west wall, a CEIL1_2 lamp ceiling in a sector strobing between light
 * 160 and 96. Surfaces are told apart by the CPU oracle's hit for each pixel-centre ray.
 */
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { traverseClosest } from '../../src/bvh/traverse.ts';
import { primaryRay } from '../../src/gpu/view.ts';
import type { Vec3 } from '../../src/math/vec3.ts';
import { loadDoomMap } from '../../src/loaders/doom/load.ts';
import { animatedRoomWad } from '../../src/loaders/doom/test-wad.ts';
import { readWad, WadStack } from '../../src/loaders/doom/wad.ts';
import { editMaterials, prepareScene, type PreparedScene } from '../../src/renderer/prepare.ts';
import { renderProgressive } from '../../src/renderer/progressive.ts';
import { Renderer } from '../../src/renderer/renderer.ts';
import type { Scene } from '../../src/scene/types.ts';
import type { Viewpoint } from '../../src/world/animator.ts';
import { sceneUpdateAt } from '../../src/world/world.ts';
import { testGpu } from './gpu-context.ts';
import { lum } from './scene-render.ts';

const W = 32, H = 24;
const TIC = 1 / 35;

const scene: Scene = loadDoomMap(new WadStack([readWad(animatedRoomWad(), 'animated.wad')]), undefined).scene;
const view: Viewpoint = { position: scene.camera.position, forward: scene.camera.forward };
const animations = scene.dynamics!.materialAnimations!;
const cycleMaterial = animations.cycles![0]!.material;
const scrollMaterial = animations.scrolls![0]!.material;
const lampMaterial = animations.patterns!.find((p) => scene.materials[p.material]!.name.startsWith('CEIL1_2'))!.material;

/** The material each pixel-centre ray hits (CPU oracle), and whether all four neighbours hit the same one. */
function materialsSeen(prepared: PreparedScene): { material: number[]; interior: boolean[] } {
  const material: number[] = [];
  for (let y = 0; y < H; y++) {
    for (let x = 0; x < W; x++) {
      const ray = primaryRay(prepared.scene.camera, W, H, x + 0.5, y + 0.5);
      const f32 = { origin: ray.origin.map(Math.fround) as unknown as Vec3, direction: ray.direction.map(Math.fround) as unknown as Vec3 };
      const hit = traverseClosest(prepared.bvh, prepared.triangles.positions, f32);
      material.push(hit ? prepared.triangles.materialIds[hit.triangle]! : -1);
    }
  }
  const interior = material.map((m, i) => {
    const [x, y] = [i % W, Math.floor(i / W)];
    return [[x - 1, y], [x + 1, y], [x, y - 1], [x, y + 1]].every(([u, v]) => u! < 0 || v! < 0 || u! >= W || v! >= H || material[v! * W + u!] === m);
  });
  return { material, interior };
}

let renderer: Renderer;
let prepared: PreparedScene;
let seen: ReturnType<typeof materialsSeen>;

beforeAll(async () => {
  renderer = await Renderer.create(await testGpu());
  prepared = prepareScene(scene);
  seen = materialsSeen(prepared);
  await renderer.setScene(prepared);
  await renderer.resize(W, H);
});
afterAll(() => renderer.destroy());

async function albedoAt(t: number): Promise<Float32Array> {
  renderer.applySceneUpdate(sceneUpdateAt(scene, t, view));
  renderer.updateSettings({ debugView: 'albedo', debugLayout: 'replace' });
  return new Float32Array(await renderer.readDebugValues());
}

const pixelOf = (v: Float32Array, i: number) => Array.from(v.subarray(i * 4, i * 4 + 3));
const pixelsOf = (m: number) => seen.material.flatMap((k, i) => (k === m && seen.interior[i] ? [i] : []));

describe('Doom animations on the GPU', () => {
  it('the view shows the cycling floor, the scrolling wall and the lamp', () => {
    for (const m of [cycleMaterial, scrollMaterial, lampMaterial]) expect(pixelsOf(m).length, scene.materials[m]!.name).toBeGreaterThan(10);
  });

  it('9 tics apart, the cycling floor shows another frame and every other surface the same albedo', async () => {
    const before = await albedoAt(0);
    const after = await albedoAt(9 * TIC);
    let changed = 0, same = 0;
    for (let i = 0; i < W * H; i++) {
      if (!seen.interior[i]) continue;
      const m = seen.material[i]!;
      // texture_refs are not written by applySceneUpdate yet (the scroll is checked below).
      if (m === scrollMaterial) continue;
      if (m === cycleMaterial) {
        expect(pixelOf(after, i), `pixel ${i}`).not.toEqual(pixelOf(before, i));
        changed++;
      } else {
        expect(pixelOf(after, i), `pixel ${i}`).toEqual(pixelOf(before, i));
        same++;
      }
    }
    expect(changed).toBeGreaterThan(10);
    expect(same).toBeGreaterThan(10);
    // Back at t = 0, the first image again.
    expect(Array.from(await albedoAt(0))).toEqual(Array.from(before));
  });

  it('a scrolled wall, packed by editMaterials and uploaded, shows its stripes moved by 9 texels', async () => {
    const other = await Renderer.create(await testGpu());
    try {
      const albedo = async (t: number) => {
        const edited = editMaterials(prepared, sceneUpdateAt(scene, t, view).materials);
        await other.setScene(edited.prepared);
        await other.resize(W, H);
        other.updateSettings({ debugView: 'albedo', debugLayout: 'replace' });
        return { values: new Float32Array(await other.readDebugValues()), textureRefsChanged: edited.textureRefsChanged };
      };
      const before = await albedo(0);
      const after = await albedo(9 * TIC);
      expect(after.textureRefsChanged).toBe(true);
      const wall = pixelsOf(scrollMaterial);
      // Stripes of period 4 moved by 9 ≡ 1 texel: every wall pixel shows the next stripe.
      for (const i of wall) expect(pixelOf(after.values, i), `pixel ${i}`).not.toEqual(pixelOf(before.values, i));
      for (const i of pixelsOf(lampMaterial)) expect(pixelOf(after.values, i)).toEqual(pixelOf(before.values, i));
    } finally {
      other.destroy();
    }
  });

  it('the strobing lamp emits (96/160)² as much in its dark tics (emitters only, no bounces)', async () => {
    const emitted = async (t: number) => {
      renderer.updateSettings({ debugView: 'none', maxBounces: 0, torch: { enabled: false }, seed: 1 });
      renderer.applySceneUpdate(sceneUpdateAt(scene, t, view));
      await renderProgressive(renderer, { spp: 4 });
      return renderer.readAccumulation();
    };
    const bright = await emitted(0);
    const dark = await emitted(9 * TIC);
    const lamp = pixelsOf(lampMaterial);
    for (const i of lamp) {
      expect(lum(bright, i)).toBeGreaterThan(0);
      expect(lum(dark, i) / lum(bright, i), `pixel ${i}`).toBeCloseTo((96 / 160) ** 2, 4);
    }
    // A surface that does not emit stays black either way.
    const still = seen.material.findIndex((m, i) => seen.interior[i] && m !== lampMaterial && m !== cycleMaterial && !scene.materials[m]!.emission.some((c) => c > 0));
    expect(still).toBeGreaterThanOrEqual(0);
    expect(lum(bright, still)).toBe(0);
    expect(lum(dark, still)).toBe(0);
  });
});
