/**
 * Instances on the GPU: moving one with Renderer.updateInstances (BVH refit, buffers rewritten in
 * place) renders exactly what a scene built with the instance at its new place renders, for the same
 * seed; a mirrored instance (negative scale in x) renders as its unmirrored twin mirrored, and its
 * emissive front face still emits (the winding is swapped back, scene/triangles.ts).
 */
import { describe, expect, it } from 'vitest';
import { fromTrs, translation, type Mat4 } from '../../src/math/mat4.ts';
import type { Vec3 } from '../../src/math/vec3.ts';
import type { Accumulation } from '../../src/renderer/renderer.ts';
import { floorSquare, uvSphere } from '../../src/scene/shapes.ts';
import { diffuse, type Mesh, type Scene } from '../../src/scene/types.ts';
import { grey, lum, regionStats, renderScene, topDownCamera } from './scene-render.ts';

const SIZE = 16;
const at = (p: Vec3): Mat4 => translation(p);

/** A floor and two instances of one sphere mesh (ids 1 and 2) under a constant sky, seen from above. */
function twoSpheres(second: Mat4): Scene {
  return {
    name: 'two spheres',
    meshes: [floorSquare('floor', 20, 1, 0), uvSphere('sphere', 0.4, 32, 16, 1)],
    instances: [
      { id: 0, mesh: 0, worldFromObject: at([0, 0, 0]) },
      { id: 1, mesh: 1, worldFromObject: at([-0.5, 0.4, -0.5]), moves: true },
      { id: 2, mesh: 1, worldFromObject: second, moves: true },
    ],
    materials: [diffuse('floor', grey(0.3)), diffuse('sphere', [0.9, 0.2, 0.1])],
    camera: topDownCamera([0, 0], 4, 1.2),
    environment: { kind: 'constant', radiance: [1, 1, 1] },
  };
}

/** The pixel whose centre sees the floor point (x, z) from the camera above (for a sphere's top, its centre's pixel). */
function pixelOf(x: number, z: number): number {
  const px = Math.floor(((x + 1.2) / 2.4) * SIZE), py = Math.floor(((z + 1.2) / 2.4) * SIZE);
  return py * SIZE + px;
}

/** Whether a pixel is red sphere (red ≫ blue) rather than grey floor. */
const isSphere = (a: Accumulation, i: number): boolean => a.radiance[i * 3]! > 3 * a.radiance[i * 3 + 2]!;

describe('moving an instance', () => {
  it('updateInstances renders what a scene built with the instance in its new place renders', async () => {
    const from = at([0.5, 0.4, 0.5]), to = at([0.5, 0.4, -0.5]);
    const options = { width: SIZE, height: SIZE, spp: 8, maxBounces: 3, seed: 4 };
    const moved = await renderScene(twoSpheres(from), options, (r) => {
      r.updateInstances(new Map([[2, to]]));
    });
    const direct = await renderScene(twoSpheres(to), options);
    const unmoved = await renderScene(twoSpheres(from), options);

    // At the new place and not at the old.
    expect(isSphere(moved, pixelOf(0.5, -0.5))).toBe(true);
    expect(isSphere(moved, pixelOf(0.5, 0.5))).toBe(false);
    expect(isSphere(unmoved, pixelOf(0.5, 0.5))).toBe(true);
    expect(isSphere(moved, pixelOf(-0.5, -0.5))).toBe(true); // the other instance stays

    // Same seed, same world-space triangles: the same image, whatever the BVH's shape (refit vs build).
    let worst = 0, differing = 0;
    for (let i = 0; i < SIZE * SIZE * 3; i++) {
      const d = Math.abs(moved.radiance[i]! - direct.radiance[i]!);
      worst = Math.max(worst, d);
      if (d > 1e-5) differing++;
    }
    console.log(`moved vs built in place: ${differing} of ${SIZE * SIZE * 3} values differ by > 1e-5, worst ${worst}`);
    expect(worst).toBeLessThan(1e-4);
    // Power: the move changes the image a lot.
    let changed = 0;
    for (let i = 0; i < SIZE * SIZE; i++) if (Math.abs(lum(moved, i) - lum(unmoved, i)) > 0.05) changed++;
    expect(changed).toBeGreaterThan(10);
  });

  it('moving it back restores the original image', async () => {
    const from = at([0.5, 0.4, 0.5]);
    const options = { width: SIZE, height: SIZE, spp: 4, maxBounces: 2, seed: 8 };
    const there = await renderScene(twoSpheres(from), options, (r) => {
      r.updateInstances(new Map([[2, at([0, 2, 0])]]));
      r.updateInstances(new Map([[2, from]]));
    });
    const original = await renderScene(twoSpheres(from), options);
    for (let i = 0; i < SIZE * SIZE * 3; i++) expect(there.radiance[i]).toBeCloseTo(original.radiance[i]!, 4);
  });

  it('an unknown instance id is an error', async () => {
    await expect(renderScene(twoSpheres(at([0, 0, 0])), { width: 4, height: 4, spp: 1, maxBounces: 1 }, (r) => {
      r.updateInstances(new Map([[99, at([0, 0, 0])]]));
    })).rejects.toThrow(/99/);
  });
});

describe.each([
  ['in the static world', false],
  ['moving (two-level BVH: the panel in object space, sampled as a light through its instance)', true],
])('a mirrored instance %s', (_, moves) => {
  /** An L-shaped emissive panel (asymmetric in x and z) in the y = 0 plane, front face down: (v1 − v0) × (v2 − v0) = −y. */
  const panel: Mesh = {
    name: 'L panel',
    positions: new Float32Array([0.1, 0, -0.4, 0.7, 0, -0.4, 0.7, 0, -0.1, 0.1, 0, -0.1, 0.1, 0, 0.4, 0.4, 0, 0.4, 0.4, 0, -0.1]),
    // Two quads: the bar along x (z in [−0.4, −0.1]) and the leg along z (x in [0.1, 0.4]).
    indices: new Uint32Array([0, 1, 2, 0, 2, 3, 3, 6, 5, 3, 5, 4]),
    materialIds: new Uint32Array([1, 1, 1, 1]),
  };

  function scene(scaleX: number): Scene {
    return {
      name: `L panel, scale x ${scaleX}`,
      meshes: [floorSquare('floor', 20, 1, 0), panel],
      instances: [
        { id: 0, mesh: 0, worldFromObject: at([0, 0, 0]) },
        { id: 1, mesh: 1, worldFromObject: fromTrs([0, 0.5, 0], [0, 0, 0, 1], [scaleX, 1, 1]), moves },
      ],
      materials: [diffuse('floor', grey(0.5)), { kind: 'emissive', name: 'panel', emission: [3, 3, 3] }],
      // The camera sits below the panel (height 0.45), looking down at the floor it lights.
      camera: topDownCamera([0, 0], 0.45, 1),
    };
  }

  it('lights the floor as its twin mirrored (x → −x), its front face still emitting', async () => {
    // Check the winding claim of the panel: (v1 − v0) × (v2 − v0) of each triangle points down.
    for (let t = 0; t < 4; t++) {
      const [a, b, c] = [0, 1, 2].map((k) => panel.indices[t * 3 + k]!);
      const p = (v: number) => [panel.positions[v * 3]!, panel.positions[v * 3 + 1]!, panel.positions[v * 3 + 2]!];
      const [v0, v1, v2] = [p(a!), p(b!), p(c!)];
      const e1 = [v1![0]! - v0![0]!, v1![2]! - v0![2]!], e2 = [v2![0]! - v0![0]!, v2![2]! - v0![2]!];
      // y of e1 × e2 = z1·x2 − x1·z2.
      expect(e1[1]! * e2[0]! - e1[0]! * e2[1]!).toBeLessThan(0);
    }
    const options = { width: SIZE, height: SIZE, spp: 64, maxBounces: 1 };
    const plain = await renderScene(scene(1), { ...options, seed: 31 });
    const mirrored = await renderScene(scene(-1), { ...options, seed: 32 });
    const all = [...Array(SIZE * SIZE).keys()];
    const p = regionStats(plain, all), m = regionStats(mirrored, all);
    console.log(`floor under the panel: plain ${p.mean.toFixed(4)} ± ${p.se.toFixed(4)}, mirrored ${m.mean.toFixed(4)} ± ${m.se.toFixed(4)}`);
    // Both light the floor (a back-facing, non-emitting mirrored panel would leave it black).
    expect(p.mean).toBeGreaterThan(0.05);
    expect(m.mean).toBeGreaterThan(0.05);
    expect(Math.abs(p.mean - m.mean)).toBeLessThan(4 * Math.hypot(p.se, m.se));
    // Per 4×4 block, the mirrored image equals the plain one flipped left–right (screen right = +x).
    let asymmetry = 0;
    for (let by = 0; by < SIZE; by += 4) {
      for (let bx = 0; bx < SIZE; bx += 4) {
        const px: number[] = [], flipped: number[] = [];
        for (let y = by; y < by + 4; y++) {
          for (let x = bx; x < bx + 4; x++) {
            px.push(y * SIZE + x);
            flipped.push(y * SIZE + (SIZE - 1 - x));
          }
        }
        const a = regionStats(plain, px), b = regionStats(mirrored, flipped), unflipped = regionStats(mirrored, px);
        const sigma = Math.hypot(a.se, b.se);
        expect(Math.abs(a.mean - b.mean), `block (${bx}, ${by}): ${a.mean} vs ${b.mean} ± ${sigma}`).toBeLessThan(4.5 * sigma + 1e-4);
        asymmetry = Math.max(asymmetry, Math.abs(a.mean - unflipped.mean) / Math.hypot(a.se, unflipped.se));
      }
    }
    // Power: the panel is asymmetric, so the mirrored image without the flip differs by many σ somewhere.
    expect(asymmetry).toBeGreaterThan(10);
  });
});
