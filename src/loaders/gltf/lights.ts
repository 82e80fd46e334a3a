/**
 * KHR_lights_punctual → Scene.lights, placed in world space by their node: a light sits at the node's
 * origin and shines down its local −Z. Intensities are taken one to one (candela as W/sr, lux as
 * W/m², see PunctualLight in scene/types.ts); a range left out means no cut-off.
 */
import type { Light } from '@gltf-transform/extensions';
import { transformDirection, transformPoint, type Mat4 } from '../../math/mat4.ts';
import { normalize } from '../../math/vec3.ts';
import type { PunctualLight } from '../../scene/types.ts';

export function convertLight(light: Light, worldFromLight: Mat4, fallbackName: string): PunctualLight {
  const name = light.getName() || fallbackName;
  const color = [...light.getColor()] as [number, number, number];
  const intensity = light.getIntensity();
  const range = light.getRange() ?? Infinity;
  const position = transformPoint(worldFromLight, [0, 0, 0]);
  const direction = normalize(transformDirection(worldFromLight, [0, 0, -1]));
  switch (light.getType()) {
    case 'point':
      return { kind: 'point', name, position, color, intensity, range };
    case 'spot':
      return { kind: 'spot', name, position, direction, color, intensity, range, innerConeAngle: light.getInnerConeAngle(), outerConeAngle: light.getOuterConeAngle() };
    case 'directional':
      return { kind: 'directional', name, direction, color, irradiance: intensity };
  }
}
