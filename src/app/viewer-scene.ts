/**
 * What a loaded scene becomes in the viewer, apart from the GPU: its camera controller with what a
 * link says of the view applied (pose, mode, field of view, lens), and where a lens focuses when
 * nothing says.
 */
import { boundsDiagonal } from '../bvh/stats.ts';
import { centreFocusDistance } from '../renderer/focus.ts';
import type { Environment } from '../scene/environment.ts';
import type { Camera } from '../scene/types.ts';
import { CameraController, sceneSpeed } from './camera-controller.ts';
import type { LoadedScene } from './scene-request.ts';
import type { SceneView } from './viewer-types.ts';

/** A scene without an environment has this one (black), one object so that it compares equal to itself. */
export const NO_ENVIRONMENT: Environment = Object.freeze({ kind: 'none' });

/** The camera controller of a scene: the scene's camera, walking where it can, then the link's view. */
export function sceneController(prepared: LoadedScene['prepared'], view: SceneView): CameraController {
  const { scene, bvh } = prepared;
  // The controller keeps its own heights of the walk map (doors and lifts change them).
  const controller = new CameraController(scene.camera, sceneSpeed(boundsDiagonal(bvh), scene.metersPerUnit, scene.walkMap), scene.walkMap);
  if (view.pose) controller.setPose(view.pose);
  if (view.fovDegrees !== undefined) controller.vfovDegrees = view.fovDegrees;
  controller.setMode(view.mode ?? (controller.canWalk ? 'walk' : 'fly'));
  if (view.apertureRadius !== undefined || view.focusDistance !== undefined) {
    // What the link leaves out comes from the scene's lens; a focus distance from neither, from the image centre.
    const focusDistance = view.focusDistance ?? controller.lens?.focusDistance ?? defaultFocus(prepared, controller.camera());
    controller.lens = { apertureRadius: view.apertureRadius ?? controller.lens?.apertureRadius ?? 0, focusDistance };
  }
  return controller;
}

/** The depth at the image centre, or half the scene's size when the centre ray meets nothing. */
export function defaultFocus(prepared: LoadedScene['prepared'], camera: Camera): number {
  return centreFocusDistance(prepared, camera) ?? Math.max(boundsDiagonal(prepared.bvh) / 2, 1e-3);
}
