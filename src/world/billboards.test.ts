/** world/billboards.ts: the animator poses what the view changed, and plays frame cycles from the clock. */
import { describe, expect, it } from 'vitest';
import { determinant3 } from '../math/mat4.ts';
import type { Vec3 } from '../math/vec3.ts';
import { frameAt } from '../scene/billboards.ts';
import type { Billboard } from '../scene/dynamics-types.ts';
import type { Viewpoint } from './animator.ts';
import { World } from './world.ts';
import { billboardImage as image, twoBillboardScene } from '../../tests/fixtures/billboard-scene.ts';

const DEG = Math.PI / 180;
/** A viewer `d` units from `at` in the direction of map angle `deg` (0 east, 90 north = −z). */
const around = (at: Vec3, deg: number, d = 100): Vec3 => [at[0] + d * Math.cos(deg * DEG), at[1], at[2] - d * Math.sin(deg * DEG)];


describe('the billboard animator', () => {
  const { scene } = twoBillboardScene();
  // East of the first thing, looking west at it: it faces the viewer (rotation 1).
  const view: Viewpoint = { position: [200, 41, 0], forward: [-1, 0, 0] };

  it('poses every billboard on the first step, with the material of the rotation seen', () => {
    const world = World.of(scene)!;
    const u = world.advance(0, view)!;
    expect([...u.instances.keys()].sort()).toEqual([10, 11]);
    expect(u.instances.get(10)!.material).toBe(0);
    expect(u.instances.get(11)!.material).toBe(9);
  });

  it('writes nothing when the view does not change a pose, and only what changed when it does', () => {
    const world = World.of(scene)!;
    world.advance(0, view);
    expect(world.advance(1 / 35, view)).toBeUndefined();
    // A small step sideways: no rotation boundary crossed, no turn.
    expect(world.advance(1 / 35, { ...view, position: [200, 41, 0.5] })).toBeUndefined();
    // Walking round to the thing's north-west (135°): its rotation changes to 4 (index 3); the
    // second thing keeps its single image and its yaw.
    const u = world.advance(1 / 35, { position: around([0, 41, 0], 135, 200), forward: [-1, 0, 0] })!;
    expect([...u.instances.keys()]).toEqual([10]);
    expect(u.instances.get(10)!.material).toBe(3);
    // Behind and to the right of it (−135°): rotation 6 is rotation 4 mirrored (index 5, material 5).
    const v = world.advance(1 / 35, { position: around([0, 41, 0], -135, 200), forward: [-1, 0, 0] })!;
    expect(v.instances.get(10)!.material).toBe(5);
    expect(determinant3(v.instances.get(10)!.worldFromObject!)).toBeLessThan(0);
    // Turning the view turns every quad, but the materials stay.
    const w = world.advance(1 / 35, { position: around([0, 41, 0], -135, 200), forward: [0, 0, -1] })!;
    expect([...w.instances.keys()].sort()).toEqual([10, 11]);
    expect(w.instances.get(10)!.material).toBeUndefined();
    expect(w.instances.get(11)!.material).toBeUndefined();
  });

  it('plays a cycle of frames from the clock, from its phase, writing only when a frame changes', () => {
    // A torch: frames A–D (materials 0–3) of 4 tics each, 2.5 tics into frame A at time 0.
    const tic = 1 / 35;
    const torch: Billboard = { instance: 10, position: [0, 0, 0], facing: 0, phase: 2.5 * tic, frames: [0, 1, 2, 3].map((m) => ({ duration: 4 * tic, images: [image({ material: m })] })) };
    expect([0, 1, 2, 3, 4, 5, 6, 13, 14, 15, 16].map((t) => frameAt(torch, t * tic))).toEqual([0, 0, 1, 1, 1, 1, 2, 3, 0, 0, 0]);
    const world = World.of({ ...scene, dynamics: { billboards: [torch] } })!;
    const materials: (number | undefined)[] = [];
    materials.push(world.advance(0, view)!.instances.get(10)!.material);
    for (let i = 0; i < 16; i++) materials.push(world.advance(tic, view)?.instances.get(10)?.material);
    // Frame B at tics 2..5, C at 6..9, D at 10..13, A again at 14.
    expect(materials).toEqual([0, undefined, 1, undefined, undefined, undefined, 2, undefined, undefined, undefined, 3, undefined, undefined, undefined, 0, undefined, undefined]);
  });

  it('makes no world for a scene without billboards', () => {
    expect(World.of({ ...scene, dynamics: { billboards: [] } })).toBeUndefined();
  });
});
