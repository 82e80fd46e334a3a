/**
 * The billboard animator (Scene.dynamics.billboards, scene/dynamics-types.ts): each step it poses the
 * billboards whose frame, rotation or facing changed, with the pose arithmetic of scene/billboards.ts
 * (Doom's R_ProjectSprite). Pure.
 */
import { billboardPose, facingYaw, frameAt, imageAt, rotationOf } from '../scene/billboards.ts';
import type { Billboard } from '../scene/dynamics-types.ts';
import type { Animator, AnimatorFactory, UpdateBuilder, Viewpoint } from './animator.ts';

interface Shown {
  frame: number;
  rotation: number;
  yaw: number;
}

/**
 * Poses billboards: each step, every billboard whose frame, rotation or yaw changed gets a new
 * transform and, if it changed, material; the others write nothing (a viewer who moves without
 * turning changes only the rotations that cross a sector boundary, and the frames that ran out).
 */
export class BillboardAnimator implements Animator {
  private readonly shown: (Shown | undefined)[];
  /** The yaw used while the viewer looks straight up or down (the last horizontal one). */
  private yaw = 0;

  constructor(private readonly billboards: readonly Billboard[]) {
    this.shown = billboards.map(() => undefined);
  }

  step(t: number, _dt: number, view: Viewpoint, out: UpdateBuilder): void {
    this.yaw = facingYaw(view.forward) ?? this.yaw;
    const yaw = this.yaw;
    this.billboards.forEach((b, i) => {
      const frame = frameAt(b, t);
      const rotation = rotationOf(b, frame, view.position);
      const before = this.shown[i];
      if (before && before.frame === frame && before.rotation === rotation && before.yaw === yaw) return;
      this.shown[i] = { frame, rotation, yaw };
      const image = imageAt(b, frame, rotation);
      const previous = before && imageAt(b, before.frame, before.rotation);
      out.pose(b.instance, {
        worldFromObject: billboardPose(b.position, image, yaw),
        ...(previous?.material !== image.material ? { material: image.material } : {}),
      });
    });
  }
}

export const billboardAnimator: AnimatorFactory = (scene) => {
  const billboards = scene.dynamics?.billboards;
  return billboards && billboards.length > 0 ? new BillboardAnimator(billboards) : undefined;
};
