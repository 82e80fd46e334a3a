/**
 * A punctual light's power (luminance), the one figure the light table's alias weights and the
 * default-sky rule (default-light.ts) both need: 4πI for a point, the cone's solid angle × I for a spot
 * (to halfway between its inner and outer edge), E·πR² for a directional light over a scene of radius R.
 */
import { luminance } from '../math/vec3.ts';
import type { PunctualLight } from './types.ts';

export function punctualPower(light: PunctualLight, sceneRadius: number): number {
  switch (light.kind) {
    case 'point':
      return 4 * Math.PI * light.intensity * luminance(light.color);
    case 'spot': {
      const half = (light.innerConeAngle + light.outerConeAngle) / 2;
      return 2 * Math.PI * (1 - Math.cos(half)) * light.intensity * luminance(light.color);
    }
    case 'directional':
      return light.irradiance * luminance(light.color) * Math.PI * sceneRadius * sceneRadius;
  }
}
