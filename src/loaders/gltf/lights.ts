/**
 * KHR_lights_punctual → Scene.lights, placed in world space by their node: a light sits at the node's
 * origin and shines down its local −Z. Intensities are taken one to one (candela as W/sr, lux as
 * W/m², see PunctualLight in scene/types.ts); a range left out means no cut-off.
 *
 * A light whose node gives it no place (a transform past the float range) or, for spot and
 * directional lights, no direction (a zero scale) is left out with a warning.
 */
import type { Light } from '@gltf-transform/extensions';
import { transformDirection, transformPoint, type Mat4 } from '../../math/mat4.ts';
import { isFiniteVec3, unitOrUndefined } from '../../math/vec3.ts';
import type { PunctualLight } from '../../scene/types.ts';
import type { Warnings } from './warnings.ts';

export function convertLight(light: Light, worldFromLight: Mat4, fallbackName: string, warnings: Warnings): PunctualLight | undefined {
  const name = light.getName() || fallbackName;
  const color = [...light.getColor()] as [number, number, number];
  const intensity = light.getIntensity();
  const range = light.getRange() ?? Infinity;
  const position = transformPoint(worldFromLight, [0, 0, 0]);
  const type = light.getType();
  const direction = type === 'point' ? undefined : unitOrUndefined(transformDirection(worldFromLight, [0, 0, -1]));
  if ((type !== 'directional' && !isFiniteVec3(position)) || (type !== 'point' && !direction)) {
    warnings.add(`the ${type} light '${name}' is left out: its node's transform ${type === 'point' ? 'puts it past the float range' : 'gives it no direction (a zero scale, or numbers past the float range)'}`);
    return undefined;
  }
  switch (type) {
    case 'point':
      return { kind: 'point', name, position, color, intensity, range };
    case 'spot':
      return { kind: 'spot', name, position, direction: direction!, color, intensity, range, innerConeAngle: light.getInnerConeAngle(), outerConeAngle: light.getOuterConeAngle() };
    case 'directional':
      return { kind: 'directional', name, direction: direction!, color, irradiance: intensity };
  }
}
