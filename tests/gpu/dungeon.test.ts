/**
 * The dungeon on the GPU, tiny: lit by its flames and the player's torch the image is not black, and
 * the phantom, moved by the World to where it is at t = 2 s (Renderer.applySceneUpdate), shows where
 * its projection says: a pale blue-white glow in a crop around it, which is darker and warmer when the
 * phantom is moved out of view.
 */
import { describe, expect, it } from 'vitest';
import { dungeonScene, PHANTOM_ID } from '../../src/loaders/builtin/dungeon.ts';
import { transformPoint, translation } from '../../src/math/mat4.ts';
import { cross, dot, normalize, sub, type Vec3 } from '../../src/math/vec3.ts';
import { renderProgressive } from '../../src/renderer/progressive.ts';
import { Renderer, type Accumulation } from '../../src/renderer/renderer.ts';
import { emptySceneUpdate } from '../../src/scene/dynamics.ts';
import { sceneUpdateAt } from '../../src/world/world.ts';
import { testGpu } from './gpu-context.ts';

const W = 48, H = 32;

/** The pixel (column, row) a world point projects to, through the scene camera (view.ts: right = forward × up). */
function project(p: Vec3, camera: { position: Vec3; forward: Vec3; up: Vec3; vfovDegrees: number }): [number, number] {
  const f = normalize(camera.forward);
  const right = normalize(cross(f, camera.up));
  const up = cross(right, f);
  const d = sub(p, camera.position);
  const tanHalf = Math.tan((camera.vfovDegrees * Math.PI) / 360);
  const x = dot(d, right) / dot(d, f) / (tanHalf * (W / H)), y = dot(d, up) / dot(d, f) / tanHalf;
  return [((x + 1) / 2) * W, ((1 - y) / 2) * H];
}

/** Mean linear RGB over pixels [x0, x1) × [y0, y1). */
function cropMean(a: Accumulation, x0: number, y0: number, x1: number, y1: number): Vec3 {
  const sum = [0, 0, 0];
  let n = 0;
  for (let y = Math.max(0, y0); y < Math.min(H, y1); y++) {
    for (let x = Math.max(0, x0); x < Math.min(W, x1); x++) {
      for (let k = 0; k < 3; k++) sum[k]! += a.radiance[(y * W + x) * 3 + k]!;
      n++;
    }
  }
  return [sum[0]! / n, sum[1]! / n, sum[2]! / n];
}

const lum = (c: Vec3) => 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];

describe('dungeon', () => {
  it('renders lit stone, and the phantom glows where the World put it', async () => {
    const scene = dungeonScene();
    const view = { position: scene.camera.position, forward: scene.camera.forward };
    const at2 = sceneUpdateAt(scene, 2, view);
    const pose = at2.instances.get(PHANTOM_ID)!.worldFromObject!;
    const renderer = await Renderer.create(await testGpu());
    try {
      await renderer.setScene(scene);
      await renderer.resize(W, H);
      renderer.updateSettings({ maxBounces: 3, seed: 5 });
      renderer.applySceneUpdate(at2);
      await renderProgressive(renderer, { spp: 8 });
      const withPhantom = await renderer.readAccumulation();
      // Out of sight: under the floor, far off.
      renderer.applySceneUpdate({ ...emptySceneUpdate(), instances: new Map([[PHANTOM_ID, { worldFromObject: translation([-5000, -5000, -5000]) }]]) });
      await renderProgressive(renderer, { spp: 8 });
      const without = await renderer.readAccumulation();

      // Not black: most pixels see lit stone.
      let lit = 0;
      for (let i = 0; i < W * H; i++) if (0.2126 * withPhantom.radiance[i * 3]! + 0.7152 * withPhantom.radiance[i * 3 + 1]! + 0.0722 * withPhantom.radiance[i * 3 + 2]! > 0.01) lit++;
      expect(lit).toBeGreaterThan(0.8 * W * H);

      // The crop around the phantom's projected body (its middle and its crown bound the box).
      const [cx, top] = project(transformPoint(pose, [0, 58, 0]), scene.camera);
      const [, bottom] = project(transformPoint(pose, [0, 8, 0]), scene.camera);
      const [edge] = project(transformPoint(pose, [10, 30, 0]), scene.camera);
      const half = Math.max(1, Math.abs(edge - cx));
      const box = [Math.floor(cx - half), Math.floor(top), Math.ceil(cx + half), Math.ceil(bottom)] as const;
      expect(box[2] - box[0]).toBeGreaterThanOrEqual(2);
      expect(box[3] - box[1]).toBeGreaterThanOrEqual(3);
      const ghost = cropMean(withPhantom, ...box), empty = cropMean(without, ...box);
      console.log(`phantom crop [${box.join(', ')}] of ${W}×${H}: rgb ${ghost.map((v) => v.toFixed(3)).join(' ')} with it, ${empty.map((v) => v.toFixed(3)).join(' ')} without; image lit ${lit}/${W * H}`);
      // Brighter and bluer than the torch-lit corridor behind it.
      expect(lum(ghost)).toBeGreaterThan(1.5 * lum(empty));
      expect(ghost[2] / ghost[0]).toBeGreaterThan(1.1 * (empty[2] / empty[0]));
      expect(ghost[2]).toBeGreaterThan(ghost[0]);
      // Away from it the two images agree roughly (the phantom lights only its surroundings).
      const farLeft = [0, 0, Math.max(1, box[0] - 4), H] as const;
      const a = lum(cropMean(withPhantom, ...farLeft)), b = lum(cropMean(without, ...farLeft));
      expect(Math.abs(a - b)).toBeLessThan(0.5 * Math.max(a, b));
    } finally {
      renderer.destroy();
    }
  }, 600_000);
});
