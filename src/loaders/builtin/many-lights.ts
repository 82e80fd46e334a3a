/**
 * A room lit by 40 small ceiling lamps of mixed power (a few bright, most dim, colours varied),
 * with pillars and a low wall casting overlapping shadows: the test scene for many-light sampling
 * (ReSTIR DI, docs/denoise.md). One light sample per bounce from the power-weighted table mostly
 * finds the bright lamps, whether or not they are visible; the dim ones nearby are left noisy. The
 * lamps are placed by a fixed seed, so the scene is always the same. Metres.
 */
import type { Vec3 } from '../../math/vec3.ts';
import { MeshBuilder } from '../../scene/builder.ts';
import { placeEachOnce } from '../../scene/instances.ts';
import { diffuse, type Scene } from '../../scene/types.ts';

export const MANY_LIGHTS_COUNT = 40;
const ROOM = { x: 8, y: 3, z: 8 };
const LAMP_HALF = 0.08;

/** A small deterministic generator (a linear congruential one: the scene only needs variety, not quality). */
function lcg(seed: number): () => number {
  let s = seed >>> 0;
  return () => {
    s = (Math.imul(s, 1664525) + 1013904223) >>> 0;
    return s / 2 ** 32;
  };
}

export function manyLightsScene(): Scene {
  const b = new MeshBuilder('many-lights');
  const white = b.material(diffuse('white', [0.7, 0.7, 0.7]));
  const warm = b.material(diffuse('warm wall', [0.7, 0.55, 0.4]));
  const cool = b.material(diffuse('cool wall', [0.4, 0.5, 0.7]));
  const { x: X, y: Y, z: Z } = ROOM;
  // Floor (facing up), ceiling (facing down), back and side walls facing in; the front is open.
  b.quad(white, [0, 0, 0], [0, 0, Z], [X, 0, Z], [X, 0, 0]);
  b.quad(white, [0, Y, 0], [X, Y, 0], [X, Y, Z], [0, Y, Z]);
  b.quad(white, [0, 0, Z], [0, Y, Z], [X, Y, Z], [X, 0, Z]);
  b.quad(warm, [0, 0, 0], [0, Y, 0], [0, Y, Z], [0, 0, Z]);
  b.quad(cool, [X, 0, 0], [X, 0, Z], [X, Y, Z], [X, Y, 0]);
  // Four pillars and a low wall: most lamps are hidden from most of the floor by something.
  const box = (m: number, lo: Vec3, hi: Vec3) => {
    const [x0, y0, z0] = lo, [x1, y1, z1] = hi;
    b.quad(m, [x0, y0, z0], [x0, y1, z0], [x1, y1, z0], [x1, y0, z0]);
    b.quad(m, [x1, y0, z1], [x1, y1, z1], [x0, y1, z1], [x0, y0, z1]);
    b.quad(m, [x0, y0, z1], [x0, y1, z1], [x0, y1, z0], [x0, y0, z0]);
    b.quad(m, [x1, y0, z0], [x1, y1, z0], [x1, y1, z1], [x1, y0, z1]);
    b.quad(m, [x0, y1, z0], [x0, y1, z1], [x1, y1, z1], [x1, y1, z0]);
  };
  for (const [px, pz] of [[2.5, 3], [5.5, 3], [2.5, 6], [5.5, 6]] as const) box(white, [px - 0.25, 0, pz - 0.25], [px + 0.25, Y, pz + 0.25]);
  box(white, [1, 0, 4.4], [7, 0.9, 4.6]);

  const random = lcg(15);
  for (let i = 0; i < MANY_LIGHTS_COUNT; i++) {
    const cx = 0.4 + random() * (X - 0.8), cz = 0.4 + random() * (Z - 0.8);
    // Power over two decades: every fifth lamp bright, the rest dim.
    const power = i % 5 === 0 ? 200 + 200 * random() : 5 + 20 * random();
    const hue = random();
    const colour: Vec3 = [power * (0.6 + 0.4 * hue), power * 0.8, power * (1 - 0.4 * hue)];
    const lamp = b.material(diffuse(`lamp ${i}`, [0.8, 0.8, 0.8], colour));
    const y = Y - 0.01;
    // Facing down: (v1 − v0) × (v2 − v0) points to −y.
    b.quad(lamp, [cx - LAMP_HALF, y, cz - LAMP_HALF], [cx + LAMP_HALF, y, cz - LAMP_HALF], [cx + LAMP_HALF, y, cz + LAMP_HALF], [cx - LAMP_HALF, y, cz + LAMP_HALF]);
  }

  const meshes = [b.build()];
  return {
    name: 'many-lights',
    meshes,
    instances: placeEachOnce(meshes),
    materials: b.materials,
    camera: { position: [X / 2, 1.6, -3], forward: [0, -0.2, 1], up: [0, 1, 0], vfovDegrees: 55 },
    metersPerUnit: 1,
  };
}
