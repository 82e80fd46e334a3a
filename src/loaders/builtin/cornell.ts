/**
 * The Cornell box as measured by the Cornell Program of Computer Graphics
 * (https://www.graphics.cornell.edu/online/box/data.html), in millimetres. Every quad is listed in the
 * published vertex order and split into (v0,v1,v2), (v0,v2,v3). Two deliberate departures, both from
 * Lantern's issue #2: the light quad sits at y = 548.7 (0.1 mm below the ceiling, so the two are not
 * coplanar) and emits downward only; reflectances are the published spectra reduced to linear RGB.
 */
import type { Vec3 } from '../../math/vec3.ts';
import { MeshBuilder } from '../../scene/builder.ts';
import { placeEachOnce } from '../../scene/instances.ts';
import { diffuse, type Scene } from '../../scene/types.ts';

export const CORNELL_WHITE: Vec3 = [0.885809, 0.698859, 0.666422];
export const CORNELL_RED: Vec3 = [0.570068, 0.0430135, 0.0443706];
export const CORNELL_GREEN: Vec3 = [0.105421, 0.37798, 0.076425];
export const CORNELL_LIGHT_EMISSION: Vec3 = [18.387, 13.9873, 6.75357];
const BLACK: Vec3 = [0, 0, 0];

export function cornellBox(): Scene {
  const b = new MeshBuilder('cornell');
  const white = b.material(diffuse('white', CORNELL_WHITE, BLACK));
  const red = b.material(diffuse('red', CORNELL_RED, BLACK));
  const green = b.material(diffuse('green', CORNELL_GREEN, BLACK));
  const light = b.material(diffuse('light', [0.78, 0.78, 0.78], CORNELL_LIGHT_EMISSION));

  // Floor, ceiling, back wall.
  b.quad(white, [552.8, 0, 0], [0, 0, 0], [0, 0, 559.2], [549.6, 0, 559.2]);
  b.quad(white, [556.0, 548.8, 0], [556.0, 548.8, 559.2], [0, 548.8, 559.2], [0, 548.8, 0]);
  b.quad(white, [549.6, 0, 559.2], [0, 0, 559.2], [0, 548.8, 559.2], [556.0, 548.8, 559.2]);
  // Green wall at x = 0 (on the right of the image), red wall at x ≈ 550 (on the left).
  b.quad(green, [0, 0, 559.2], [0, 0, 0], [0, 548.8, 0], [0, 548.8, 559.2]);
  b.quad(red, [552.8, 0, 0], [549.6, 0, 559.2], [556.0, 548.8, 559.2], [556.0, 548.8, 0]);
  // The light: (v1 - v0) x (v2 - v0) points to -y, so it emits downward.
  b.quad(light, [343.0, 548.7, 227.0], [343.0, 548.7, 332.0], [213.0, 548.7, 332.0], [213.0, 548.7, 227.0]);

  // Short block.
  b.quad(white, [130.0, 165.0, 65.0], [82.0, 165.0, 225.0], [240.0, 165.0, 272.0], [290.0, 165.0, 114.0]);
  b.quad(white, [290.0, 0, 114.0], [290.0, 165.0, 114.0], [240.0, 165.0, 272.0], [240.0, 0, 272.0]);
  b.quad(white, [130.0, 0, 65.0], [130.0, 165.0, 65.0], [290.0, 165.0, 114.0], [290.0, 0, 114.0]);
  b.quad(white, [82.0, 0, 225.0], [82.0, 165.0, 225.0], [130.0, 165.0, 65.0], [130.0, 0, 65.0]);
  b.quad(white, [240.0, 0, 272.0], [240.0, 165.0, 272.0], [82.0, 165.0, 225.0], [82.0, 0, 225.0]);

  // Tall block.
  b.quad(white, [423.0, 330.0, 247.0], [265.0, 330.0, 296.0], [314.0, 330.0, 456.0], [472.0, 330.0, 406.0]);
  b.quad(white, [423.0, 0, 247.0], [423.0, 330.0, 247.0], [472.0, 330.0, 406.0], [472.0, 0, 406.0]);
  b.quad(white, [472.0, 0, 406.0], [472.0, 330.0, 406.0], [314.0, 330.0, 456.0], [314.0, 0, 456.0]);
  b.quad(white, [314.0, 0, 456.0], [314.0, 330.0, 456.0], [265.0, 330.0, 296.0], [265.0, 0, 296.0]);
  b.quad(white, [265.0, 0, 296.0], [265.0, 330.0, 296.0], [423.0, 330.0, 247.0], [423.0, 0, 247.0]);

  const meshes = [b.build()];
  return {
    name: 'cornell',
    meshes,
    instances: placeEachOnce(meshes),
    materials: b.materials,
    // Published camera: focal length 35 mm, 25 mm film: 2·atan(12.5 / 35) = 39.3077°.
    camera: { position: [278, 273, -800], forward: [0, 0, 1], up: [0, 1, 0], vfovDegrees: 39.3077 },
    metersPerUnit: 0.001,
  };
}
