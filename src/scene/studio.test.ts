import { describe, expect, it } from 'vitest';
import { LanternError } from '../errors.ts';
import { boundsOfPositions, type Aabb } from '../math/aabb.ts';
import { add, cross, dot, length, normalize, scale, sub, type Vec3 } from '../math/vec3.ts';
import { inView } from './framing.ts';
import { meshBounds, studioScene } from './studio.ts';
import type { Material, Mesh } from './types.ts';
import { baseColorOf } from './types.ts';
import { validateScene } from './validate.ts';

const white: Material = { kind: 'diffuse', name: 'white', albedo: [0.8, 0.8, 0.8], emission: [0, 0, 0] };

/** A box mesh (12 triangles) spanning min..max. */
function box(min: Vec3, max: Vec3): Mesh {
  const positions: number[] = [];
  for (let i = 0; i < 8; i++) positions.push(i & 1 ? max[0] : min[0], i & 2 ? max[1] : min[1], i & 4 ? max[2] : min[2]);
  const quads = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
  return {
    name: 'box',
    positions: new Float32Array(positions),
    indices: new Uint32Array(quads.flatMap(([a, b, c, d]) => [a!, b!, c!, a!, c!, d!])),
    materialIds: new Uint32Array(12),
  };
}

const vertex = (m: Mesh, i: number): Vec3 => [m.positions[3 * i]!, m.positions[3 * i + 1]!, m.positions[3 * i + 2]!];
const vertices = (m: Mesh): Vec3[] => Array.from({ length: m.positions.length / 3 }, (_, i) => vertex(m, i));
const centroid = (m: Mesh): Vec3 => scale(vertices(m).reduce(add), 1 / (m.positions.length / 3));
/** Geometric normals (v1-v0)×(v2-v0) of every triangle, the emitting side. */
const triangleNormals = (m: Mesh): Vec3[] =>
  Array.from({ length: m.indices.length / 3 }, (_, t) => {
    const [a, b, c] = [0, 1, 2].map((k) => vertex(m, m.indices[3 * t + k]!)) as [Vec3, Vec3, Vec3];
    return normalize(cross(sub(b, a), sub(c, a)));
  });
const corners = (b: Aabb): Vec3[] =>
  Array.from({ length: 8 }, (_, i) => [i & 1 ? b.max[0] : b.min[0], i & 2 ? b.max[1] : b.min[1], i & 4 ? b.max[2] : b.min[2]] as Vec3);


const CASES: [string, Mesh][] = [
  ['a unit cube at the origin', box([-0.5, -0.5, -0.5], [0.5, 0.5, 0.5])],
  ['a long, thin, off-centre bar in millimetres', box([100, 2000, -30], [900, 2040, 10])],
  ['a tall tower', box([-1, 0, -1], [1, 50, 1])],
  ['a flat sheet', box([-3, 1, -2], [3, 1, 2])],
];

describe('studioScene', () => {
  it.each(CASES)('frames and lights %s', (_, mesh) => {
    const scene = studioScene('test', [mesh], [white]);
    validateScene(scene);
    const bounds = boundsOfPositions(mesh.positions);
    const centre = scale(add(bounds.min, bounds.max), 0.5);
    const [object, floor, key, fill] = scene.meshes as [Mesh, Mesh, Mesh, Mesh];
    expect(object).toBe(mesh);
    expect(scene.meshes).toHaveLength(4);

    // Materials: the caller's first, unchanged; then floor, key and fill.
    expect(scene.materials[0]).toBe(white);
    const material = (m: Mesh) => scene.materials[m.materialIds[0]!]!;
    expect(material(floor).emission).toEqual([0, 0, 0]);
    expect(baseColorOf(material(floor))[0]).toBeCloseTo(0.7);
    expect(material(key).emission[0]).toBeGreaterThan(material(fill).emission[0]);
    expect(material(fill).emission[0]).toBeGreaterThan(0);

    // The floor is just below the lowest point, faces up and reaches well beyond the object.
    const size = length(sub(bounds.max, bounds.min)) || 1;
    for (const v of vertices(floor)) expect(v[1]).toBeLessThan(bounds.min[1]);
    expect(bounds.min[1] - floor.positions[1]!).toBeLessThan(1e-3 * size);
    for (const n of triangleNormals(floor)) expect(n[1]).toBeCloseTo(1);
    const floorBounds = boundsOfPositions(floor.positions);
    expect(floorBounds.min[0]).toBeLessThan(bounds.min[0] - 5 * size);
    expect(floorBounds.max[2]).toBeGreaterThan(bounds.max[2] + 5 * size);

    for (const light of [key, fill]) {
      // Entirely above the object, emitting side aimed at the bounds centre.
      for (const v of vertices(light)) expect(v[1]).toBeGreaterThan(bounds.max[1]);
      const toCentre = normalize(sub(centre, centroid(light)));
      for (const n of triangleNormals(light)) expect(dot(n, toCentre)).toBeGreaterThan(0.999);
      // Out of shot, so the image shows the object lit rather than the lamp (checked for a wide 16:9 frame).
      expect(inView(scene.camera, centroid(light), 16 / 9)).toBe(false);
    }
    // The key is in front: on the camera's side of the object.
    const toCamera = sub(scene.camera.position, centre);
    expect(dot(sub(centroid(key), centre), toCamera)).toBeGreaterThan(0);

    // Camera: y up, looking at the bounds centre, with every corner of the bounds in view even for a
    // square image, from above (a three-quarter view looks down a little).
    const cam = scene.camera;
    expect(cam.up).toEqual([0, 1, 0]);
    expect(cam.vfovDegrees).toBeGreaterThanOrEqual(35);
    expect(cam.vfovDegrees).toBeLessThanOrEqual(45);
    expect(dot(normalize(cam.forward), normalize(sub(centre, cam.position)))).toBeGreaterThan(0.99999);
    for (const c of corners(bounds)) expect(inView(scene.camera, c, 1)).toBe(true);
    expect(cam.position[1]).toBeGreaterThan(centre[1]);
    const view = normalize(sub(cam.position, centre));
    expect(Math.abs(view[0])).toBeGreaterThan(0.3); // three-quarter, not straight on
    expect(Math.abs(view[2])).toBeGreaterThan(0.3);
  });

  it('is scale-invariant: same light radiance, same view, at any size', () => {
    const small = studioScene('s', [box([-1, 0, -1], [1, 2, 1])], [white]);
    const big = studioScene('b', [box([-1000, 0, -1000], [1000, 2000, 1000])], [white]);
    expect(big.materials).toEqual(small.materials);
    expect(big.camera.position.map((x) => x / 1000)).toEqual(small.camera.position.map((x) => expect.closeTo(x, 9)));
    expect(normalize(big.camera.forward)).toEqual(normalize(small.camera.forward).map((x) => expect.closeTo(x, 9)));
  });

  it('keeps several meshes and their material ids, framing their union', () => {
    const a = box([0, 0, 0], [1, 1, 1]);
    const b = { ...box([5, 0, 0], [6, 3, 1]), materialIds: new Uint32Array(12).fill(1) };
    const red: Material = { kind: 'diffuse', name: 'red', albedo: [0.8, 0.1, 0.1], emission: [0, 0, 0] };
    const scene = studioScene('two', [a, b], [white, red]);
    validateScene(scene);
    expect(scene.materials.slice(0, 2)).toEqual([white, red]);
    expect(scene.meshes[1]!.materialIds[0]).toBe(1);
    expect(scene.meshes[2]!.materialIds[0]).toBe(2); // floor comes right after the caller's materials
    for (const c of corners({ min: [0, 0, 0], max: [6, 3, 1] })) expect(inView(scene.camera, c, 1)).toBe(true);
  });

  it('frames spheres and capsules by their surfaces, not their centres', () => {
    // No triangles: two spheres and a capsule whose ends stick out beyond both.
    const mesh: Mesh = {
      name: 'primitives',
      positions: new Float32Array(0),
      indices: new Uint32Array(0),
      materialIds: new Uint32Array(0),
      spheres: { centers: new Float32Array([0, 0, 0, 4, 1, 0]), radii: new Float32Array([1, 0.5]), materialIds: new Uint32Array(2) },
      capsules: { endpoints: new Float32Array([-3, 2, 0, 1, 2, 2]), radii: new Float32Array([0.25]), materialIds: new Uint32Array(1) },
    };
    const bounds = meshBounds(mesh);
    expect(bounds).toEqual({ min: [-3.25, -1, -1], max: [4.5, 2.25, 2.25] });
    const scene = studioScene('primitives', [mesh], [white]);
    const floor = scene.meshes[1]!;
    expect(floor.positions[1]).toBeLessThan(-1);
    expect(floor.positions[1]).toBeGreaterThan(-1.01);
    for (const c of corners(bounds)) expect(inView(scene.camera, c, 1)).toBe(true);
    // Triangles and primitives of one mesh together.
    expect(meshBounds({ ...box([10, 10, 10], [11, 11, 11]), spheres: mesh.spheres! })).toEqual({ min: [-1, -1, -1], max: [11, 11, 11] });
  });

  it('handles a single point and rejects empty geometry', () => {
    const point: Mesh = { name: 'p', positions: new Float32Array([1, 2, 3]), indices: new Uint32Array([0, 0, 0]), materialIds: new Uint32Array(1) };
    validateScene(studioScene('point', [point], [white]));
    const empty: Mesh = { name: 'e', positions: new Float32Array(0), indices: new Uint32Array(0), materialIds: new Uint32Array(0) };
    expect(() => studioScene('empty', [empty], [white])).toThrow(LanternError);
    expect(() => studioScene('none', [], [white])).toThrow(/no geometry/);
  });
});
