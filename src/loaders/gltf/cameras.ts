/**
 * glTF cameras → the scene's one view. A glTF camera looks down its node's local −Z with +Y up
 * (glTF 2.0 §3.10.1); yfov is in radians, Lantern's vfov in degrees.
 *
 * A camera whose node collapses its view (a zero scale, a shear that folds −Z onto +Y, a transform
 * past the float range) or whose field of view is not an angle is left out with a warning, and the
 * next camera, or the framing of the model, takes its place.
 */
import type { Camera as GltfCamera } from '@gltf-transform/core';
import { transformDirection, transformPoint, type Mat4 } from '../../math/mat4.ts';
import { cross, isFiniteVec3, length, scale, sub, unitOrUndefined } from '../../math/vec3.ts';
import type { Camera } from '../../scene/types.ts';
import type { Warnings } from './warnings.ts';

/** Field of view given to an orthographic camera's stand-in. */
const ORTHO_STAND_IN_VFOV = 30;

export function convertCamera(camera: GltfCamera, worldFromCamera: Mat4, warnings: Warnings): Camera | undefined {
  const name = camera.getName() || 'camera';
  const position = transformPoint(worldFromCamera, [0, 0, 0]);
  const forward = unitOrUndefined(transformDirection(worldFromCamera, [0, 0, -1]));
  const up = unitOrUndefined(transformDirection(worldFromCamera, [0, 1, 0]));
  if (!isFiniteVec3(position) || !forward || !up || !(length(cross(forward, up)) > 1e-6)) {
    warnings.add(`the camera '${name}' is left out: its node's transform collapses its view (a zero scale, or numbers past the float range)`);
    return undefined;
  }
  if (camera.getType() === 'perspective') {
    const vfovDegrees = (camera.getYFov() * 180) / Math.PI;
    if (!(vfovDegrees > 0 && vfovDegrees < 180)) {
      warnings.add(`the camera '${name}' is left out: its field of view (yfov ${camera.getYFov()}) is not an angle between 0 and π radians`);
      return undefined;
    }
    return { position, forward, up, vfovDegrees };
  }
  // A pinhole cannot be orthographic: back off along the view axis until the ortho view's half-height
  // (ymag, in world units after the node's scale) fills the same vertical angle at its old position.
  const ymag = Math.abs(camera.getYMag()) * Math.hypot(worldFromCamera[4]!, worldFromCamera[5]!, worldFromCamera[6]!);
  const distance = ymag / Math.tan(((ORTHO_STAND_IN_VFOV / 2) * Math.PI) / 180);
  const backed = sub(position, scale(forward, distance));
  if (!isFiniteVec3(backed)) {
    warnings.add(`the camera '${name}' is left out: its orthographic size (ymag ${camera.getYMag()}) is past the float range`);
    return undefined;
  }
  warnings.add(`the orthographic camera '${name}' is shown as a perspective camera of similar framing`);
  return { position: backed, forward, up, vfovDegrees: ORTHO_STAND_IN_VFOV };
}
