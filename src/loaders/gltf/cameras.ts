/**
 * glTF cameras → the scene's one view. A glTF camera looks down its node's local −Z with +Y up
 * (glTF 2.0 §3.10.1); yfov is in radians, Lantern's vfov in degrees.
 */
import type { Camera as GltfCamera } from '@gltf-transform/core';
import { transformDirection, transformPoint, type Mat4 } from '../../math/mat4.ts';
import { normalize, scale, sub } from '../../math/vec3.ts';
import type { Camera } from '../../scene/types.ts';
import type { Warnings } from './warnings.ts';

/** Field of view given to an orthographic camera's stand-in. */
const ORTHO_STAND_IN_VFOV = 30;

export function convertCamera(camera: GltfCamera, worldFromCamera: Mat4, warnings: Warnings): Camera {
  const position = transformPoint(worldFromCamera, [0, 0, 0]);
  const forward = normalize(transformDirection(worldFromCamera, [0, 0, -1]));
  const up = normalize(transformDirection(worldFromCamera, [0, 1, 0]));
  if (camera.getType() === 'perspective') {
    return { position, forward, up, vfovDegrees: (camera.getYFov() * 180) / Math.PI };
  }
  // A pinhole cannot be orthographic: back off along the view axis until the ortho view's half-height
  // (ymag, in world units after the node's scale) fills the same vertical angle at its old position.
  const ymag = Math.abs(camera.getYMag()) * Math.hypot(worldFromCamera[4]!, worldFromCamera[5]!, worldFromCamera[6]!);
  const distance = ymag / Math.tan(((ORTHO_STAND_IN_VFOV / 2) * Math.PI) / 180);
  warnings.add(`the orthographic camera '${camera.getName() || 'camera'}' is shown as a perspective camera of similar framing`);
  return { position: sub(position, scale(forward, distance)), forward, up, vfovDegrees: ORTHO_STAND_IN_VFOV };
}
