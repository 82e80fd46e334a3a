/**
 * A hexagonal grid of spheres (each row shifted half a spacing, rows √3/2 apart, so every sphere has
 * six equidistant neighbours) in glossy colours with a few mirrors, on a pale floor under a gradient
 * sky, seen low through a thin lens focused on the middle of the field: the regular pattern makes
 * the blur before and behind the plane in focus easy to read. A focal-blur study.
 */
import { floorSquare } from '../../scene/shapes.ts';
import { placeEachOnce } from '../../scene/instances.ts';
import { diffuse, metallicRoughness, type Material, type Scene } from '../../scene/types.ts';
import type { Vec3 } from '../../math/vec3.ts';
import { lookAt, sphereMesh, type Sphere } from './sphere-mesh.ts';

/** Columns and rows of the grid, sphere radius and the distance between neighbours. */
export const HEX_GRID = { columns: 11, rows: 17, radius: 0.4, spacing: 1 } as const;

const PALETTE: readonly Vec3[] = [
  [0.75, 0.12, 0.1],
  [0.9, 0.55, 0.08],
  [0.15, 0.45, 0.75],
  [0.12, 0.55, 0.25],
  [0.85, 0.85, 0.82],
];

/** The centre of the sphere in column c, row r (both from 0), on the floor. */
export function hexCenter(column: number, row: number): Vec3 {
  const { columns, rows, radius, spacing } = HEX_GRID;
  const x = (column - (columns - 1) / 2 + (row % 2) * 0.5) * spacing;
  const z = (row - (rows - 1) / 2) * spacing * (Math.sqrt(3) / 2);
  return [x, radius, z];
}

export function hexGridScene(): Scene {
  const { columns, rows, radius } = HEX_GRID;
  const materials: Material[] = [
    diffuse('floor', [0.6, 0.6, 0.58]),
    ...PALETTE.map((c, i) => metallicRoughness(`plastic ${i + 1}`, { baseColor: c, metallic: 0, roughness: 0.25 })),
    metallicRoughness('mirror', { baseColor: [0.95, 0.93, 0.88], metallic: 1, roughness: 0.05 }),
  ];
  const mirror = materials.length - 1;
  const spheres: Sphere[] = [];
  for (let row = 0; row < rows; row++) {
    for (let column = 0; column < columns; column++) {
      // Colours run diagonally through the palette; one sphere in seven is a mirror.
      const k = row * columns + column;
      const material = k % 7 === 3 ? mirror : 1 + ((column + 2 * row) % PALETTE.length);
      spheres.push({ center: hexCenter(column, row), radius, material });
    }
  }
  const meshes = [floorSquare('floor', 40, 1, 0), sphereMesh('spheres', spheres)];
  const focusOn = hexCenter((columns - 1) / 2, Math.floor(rows / 2));
  return {
    name: 'hex-grid',
    meshes,
    instances: placeEachOnce(meshes),
    materials,
    // Looking down about 15°: the field fills the frame up to the horizon (a level view was half sky).
    camera: lookAt([0.8, 2.6, 8.5], [0, 0, -1], 30, { apertureRadius: 0.2, focusOn }),
    environment: { kind: 'gradient', zenith: [0.45, 0.6, 0.95], horizon: [0.95, 0.95, 0.95], ground: [0.35, 0.33, 0.3] },
  };
}
