/**
 * A square grid of gold spheres on a pale stone floor under a clear sky, shot low along a diagonal through
 * a wide-open thin lens: the sphere in focus is sharp, the rows before and behind it melt, and every
 * sphere mirrors the sky and its neighbours. A depth-of-field study.
 */
import { DAYLIGHT_EXPOSURE_STOPS } from '../../scene/sky.ts';
import { floorSquare } from '../../scene/shapes.ts';
import { placeEachOnce } from '../../scene/instances.ts';
import { diffuse, metallicRoughness, type Scene } from '../../scene/types.ts';
import { GOLD } from './materials.ts';
import { lookAt, sphereMesh, type Sphere } from './sphere-mesh.ts';

/** Spheres per side, their radius and the distance between centres. */
export const GOLDEN_GRID = { count: 9, radius: 0.35, spacing: 1 } as const;
/** The grid cell in focus (column, row from the camera's near corner). */
const FOCUS_CELL = [3, 3] as const;

export function goldenGridScene(): Scene {
  const { count, radius, spacing } = GOLDEN_GRID;
  const centre = (i: number) => (i - (count - 1) / 2) * spacing;
  const spheres: Sphere[] = [];
  for (let row = 0; row < count; row++) {
    for (let column = 0; column < count; column++) spheres.push({ center: [centre(column), radius, centre(row)], radius, material: 1 });
  }
  const meshes = [floorSquare('floor', 30, 1, 0), sphereMesh('gold spheres', spheres)];
  // The camera stands off the grid's +x, +z corner; the focus cell counts from that corner.
  const focusOn = [centre(count - 1 - FOCUS_CELL[0]), radius, centre(count - 1 - FOCUS_CELL[1])] as const;
  return {
    name: 'golden-grid',
    meshes,
    instances: placeEachOnce(meshes),
    // A pale floor: the spheres mirror it, and a dark one made the gold look olive (SwiftShader render).
    materials: [diffuse('floor', [0.5, 0.47, 0.42]), metallicRoughness('gold', { baseColor: GOLD, metallic: 1, roughness: 0.15 })],
    // A wide aperture (radius 0.15 at a focus distance of about 5: f/2-like blur for a 35 mm-ish view).
    camera: lookAt([6.2, 1.6, 6.2], [-0.5, 0.1, -0.5], 32, { apertureRadius: 0.15, focusOn }, DAYLIGHT_EXPOSURE_STOPS),
    environment: { kind: 'sky', sunElevationDeg: 40, sunAzimuthDeg: 150, turbidity: 3, groundAlbedo: 0.3, intensity: 1 },
    metersPerUnit: 0.1,
  };
}
