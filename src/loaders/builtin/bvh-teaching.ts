/**
 * The BVH teaching scene: a room whose left half holds a few well separated cubes, whose right half
 * holds a dense cluster of small cubes, and across which runs a long diagonal slab whose bounding box
 * overlaps everything. Seen through the debug views it shows what a BVH is good at (separated
 * objects: few boxes per ray), what costs more (a dense cluster: many small boxes before the hit) and
 * what defeats it (one long, thin, diagonal object: its box, and every box that holds it, covers the
 * whole room, so rays everywhere descend into it). Lit by a ceiling area light; units are metres.
 */
import { add, cross, normalize, scale, sub, type Vec3 } from '../../math/vec3.ts';
import { MeshBuilder } from '../../scene/builder.ts';
import { placeEachOnce } from '../../scene/instances.ts';
import { diffuse, type Scene } from '../../scene/types.ts';

/** Material names of the three groups of objects, so tests and teaching material can find them. */
export const BVH_TEACHING_GROUPS = ['separated', 'cluster', 'slab'] as const;

const ROOM_MIN: Vec3 = [-10, 0, -10];
const ROOM_MAX: Vec3 = [10, 8, 10];
/** Cluster: CLUSTER_N × CLUSTER_N columns, CLUSTER_LAYERS high, of cubes of side CLUSTER_SIDE. */
const CLUSTER_N = 7;
const CLUSTER_LAYERS = 4;
const CLUSTER_SIDE = 0.35;
const CLUSTER_PITCH = 0.45;
const CLUSTER_CENTER: [number, number] = [5, -2.5];
const SLAB_HALF_WIDTH = 1.5;
const SLAB_HALF_THICKNESS = 0.08;
/** Lengthwise strips of each broad face of the slab. */
const SLAB_STRIPS = 16;

/** An axis-aligned box as six quads wound outward. */
function box(b: MeshBuilder, m: number, lo: Vec3, hi: Vec3): void {
  // Corner i: bit 0 picks the +x side, bit 1 +y, bit 2 +z.
  const c = (i: number): Vec3 => [i & 1 ? hi[0] : lo[0], i & 2 ? hi[1] : lo[1], i & 4 ? hi[2] : lo[2]];
  const q = (i: number, j: number, k: number, l: number) => b.quad(m, c(i), c(j), c(k), c(l));
  q(0, 2, 3, 1); // -z
  q(4, 5, 7, 6); // +z
  q(0, 4, 6, 2); // -x
  q(1, 3, 7, 5); // +x
  q(0, 1, 5, 4); // -y
  q(2, 6, 7, 3); // +y
}



export function bvhTeaching(): Scene {
  const b = new MeshBuilder('bvh-teaching');
  const wall = b.material(diffuse('wall', [0.75, 0.75, 0.72], [0, 0, 0]));
  const separated = b.material(diffuse('separated', [0.15, 0.35, 0.8], [0, 0, 0]));
  const cluster = b.material(diffuse('cluster', [0.85, 0.45, 0.1], [0, 0, 0]));
  const slab = b.material(diffuse('slab', [0.2, 0.7, 0.3], [0, 0, 0]));
  const light = b.material(diffuse('light', [0.8, 0.8, 0.8], [12, 11, 9.5]));

  // The room, open towards the camera (-z): floor, ceiling, back, left and right walls.
  const [x0, y0, z0] = ROOM_MIN, [x1, y1, z1] = ROOM_MAX;
  b.quad(wall, [x0, y0, z0], [x0, y0, z1], [x1, y0, z1], [x1, y0, z0]);
  b.quad(wall, [x0, y1, z0], [x1, y1, z0], [x1, y1, z1], [x0, y1, z1]);
  b.quad(wall, [x0, y0, z1], [x0, y1, z1], [x1, y1, z1], [x1, y0, z1]);
  b.quad(wall, [x0, y0, z0], [x0, y1, z0], [x0, y1, z1], [x0, y0, z1]);
  b.quad(wall, [x1, y0, z0], [x1, y0, z1], [x1, y1, z1], [x1, y1, z0]);
  // Ceiling light, 0.01 below the ceiling, emitting downward ((v1 − v0) × (v2 − v0) points to −y).
  const ly = y1 - 0.01;
  b.quad(light, [2.5, ly, -2.5], [2.5, ly, 2.5], [-2.5, ly, 2.5], [-2.5, ly, -2.5]);

  // Left: six cubes of side 1.2, three metres apart.
  for (const x of [-7.5, -3.5]) {
    for (const z of [-6.5, -3, 0.5]) box(b, separated, [x - 0.6, 0, z - 0.6], [x + 0.6, 1.2, z + 0.6]);
  }

  // Right: a dense cluster of small cubes, a gap of 0.1 between neighbours.
  const half = ((CLUSTER_N - 1) * CLUSTER_PITCH) / 2;
  for (let i = 0; i < CLUSTER_N; i++) {
    for (let k = 0; k < CLUSTER_N; k++) {
      for (let j = 0; j < CLUSTER_LAYERS; j++) {
        const cx = CLUSTER_CENTER[0] - half + i * CLUSTER_PITCH, cz = CLUSTER_CENTER[1] - half + k * CLUSTER_PITCH;
        const y = j * CLUSTER_PITCH;
        const h = CLUSTER_SIDE / 2;
        box(b, cluster, [cx - h, y, cz - h], [cx + h, y + CLUSTER_SIDE, cz + h]);
      }
    }
  }

  // The slab: 3 m wide, 0.16 m thick, rising from the front-left corner to the back-right one above
  // everything else. Its broad faces are cut lengthwise into long slivers, as meshes of long
  // diagonal things often are: every sliver's box spans the room, so no split separates them and
  // rays that reach the slab test many of them.
  const a: Vec3 = [-9.5, 0.3, 3.5], e: Vec3 = [9.5, 7.7, 8.5];
  const across = scale(normalize(cross(sub(e, a), [0, 0, 1])), SLAB_HALF_WIDTH);
  const thick = scale(normalize(cross(sub(e, a), across)), SLAB_HALF_THICKNESS);
  const point = (end: Vec3, s: number, side: number): Vec3 => add(add(end, scale(across, s)), scale(thick, side));
  for (const side of [-1, 1]) {
    for (let i = 0; i < SLAB_STRIPS; i++) {
      const s0 = -1 + (2 * i) / SLAB_STRIPS, s1 = -1 + (2 * (i + 1)) / SLAB_STRIPS;
      b.quad(slab, point(a, s0, side), point(a, s1, side), point(e, s1, side), point(e, s0, side));
    }
  }
  // The two long edges and the two ends.
  for (const s of [-1, 1]) b.quad(slab, point(a, s, -1), point(e, s, -1), point(e, s, 1), point(a, s, 1));
  for (const end of [a, e]) b.quad(slab, point(end, -1, -1), point(end, 1, -1), point(end, 1, 1), point(end, -1, 1));

  const meshes = [b.build()];
  return {
    name: 'bvh-teaching',
    meshes,
    instances: placeEachOnce(meshes),
    materials: b.materials,
    // From the open side, above the floor, so both halves and the whole slab are in view.
    camera: { position: [0, 7, -19], forward: normalize([0, -0.33, 1]), up: [0, 1, 0], vfovDegrees: 55 },
    metersPerUnit: 1,
  };
}
