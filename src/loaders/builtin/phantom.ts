/**
 * The dungeon's phantom: a hooded robe turned on a lathe (a surface of revolution about object +y),
 * with a ragged hem, a dark opening in the hood facing object +z and two faint eyes in it. Object
 * space: the hem's centre at the origin, y up, facing +z, 62 units (about 1.9 m at Doom's scale) tall.
 * Pure.
 */
import type { Mesh } from '../../scene/types.ts';

/** (height, radius) from the hem to the crown of the hood; the last ring closes at a point. */
const PROFILE: readonly (readonly [number, number])[] = [
  [0, 14],
  [4, 13.4],
  [11, 12],
  [20, 10.6],
  [29, 9.7],
  [36, 10.2],
  [40, 8.4],
  [43, 7],
  [46, 7.8],
  [50, 8.2],
  [54, 7.4],
  [58, 5.2],
  [60.5, 2.2],
  [62, 0],
];

/** Around the axis. */
const SEGMENTS = 16;
/** The hood's opening: rings between these heights, within this angle of +z. */
const FACE_FROM = 44.5, FACE_TO = 56, FACE_HALF_ANGLE = (50 * Math.PI) / 180;

export const PHANTOM_HEIGHT = PROFILE[PROFILE.length - 1]![0];
/** The largest distance of any vertex from the axis: what must clear the walls. */
export const PHANTOM_RADIUS = Math.max(...PROFILE.map(([, r]) => r)) * 1.16;

export interface PhantomMaterials {
  readonly robe: number;
  /** The hood's opening and the robe's inside. */
  readonly shadow: number;
  readonly eyes: number;
}

export function phantomMesh(m: PhantomMaterials): Mesh {
  const positions: number[] = [];
  const indices: number[] = [];
  const materialIds: number[] = [];
  const vertex = (x: number, y: number, z: number): number => {
    positions.push(x, y, z);
    return positions.length / 3 - 1;
  };
  const tri = (a: number, b: number, c: number, material: number) => {
    indices.push(a, b, c);
    materialIds.push(material);
  };

  // Rings (the apex ring is one vertex). The hem is ragged: radius and height vary with the angle.
  const rings: number[][] = PROFILE.map(([y, r], i) => {
    if (r === 0) return [vertex(0, y, 0)];
    const ring: number[] = [];
    for (let j = 0; j < SEGMENTS; j++) {
      const a = (2 * Math.PI * j) / SEGMENTS;
      const hem = i === 0 ? 1 + 0.1 * Math.sin(5 * a) + 0.05 * Math.sin(11 * a + 1) : 1;
      const dy = i === 0 ? 1.5 * Math.sin(7 * a) : 0;
      ring.push(vertex(r * hem * Math.sin(a), y + dy, r * hem * Math.cos(a)));
    }
    return ring;
  });
  const faceAngle = (j: number) => {
    const a = (2 * Math.PI * (j + 0.5)) / SEGMENTS;
    return Math.abs(Math.atan2(Math.sin(a), Math.cos(a)));
  };
  for (let i = 0; i + 1 < rings.length; i++) {
    const lo = rings[i]!, hi = rings[i + 1]!;
    const yMid = (PROFILE[i]![0] + PROFILE[i + 1]![0]) / 2;
    for (let j = 0; j < SEGMENTS; j++) {
      const k = (j + 1) % SEGMENTS;
      const material = yMid > FACE_FROM && yMid < FACE_TO && faceAngle(j) < FACE_HALF_ANGLE ? m.shadow : m.robe;
      // Counter-clockwise seen from outside: the robe emits outward.
      if (hi.length === 1) {
        tri(lo[j]!, lo[k]!, hi[0]!, material);
      } else {
        tri(lo[j]!, lo[k]!, hi[k]!, material);
        tri(lo[j]!, hi[k]!, hi[j]!, material);
      }
    }
  }
  // The hollow under the robe: a cone up into it, facing down and out.
  const inside = vertex(0, 16, 0);
  const hem = rings[0]!;
  for (let j = 0; j < SEGMENTS; j++) tri(hem[(j + 1) % SEGMENTS]!, hem[j]!, inside, m.shadow);

  // Two eyes just in front of the hood's opening, facing +z.
  for (const side of [-1, 1]) {
    const x = side * 2.4, y = 51.5, z = 8.6;
    const a = vertex(x - 0.9, y - 0.45, z), b = vertex(x + 0.9, y - 0.45, z), c = vertex(x + 0.9, y + 0.45, z), d = vertex(x - 0.9, y + 0.45, z);
    tri(a, b, c, m.eyes);
    tri(a, c, d, m.eyes);
  }
  return { name: 'phantom', positions: new Float32Array(positions), indices: new Uint32Array(indices), materialIds: new Uint32Array(materialIds) };
}
