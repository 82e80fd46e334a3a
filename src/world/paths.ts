/**
 * The animator of Scene.dynamics.paths: the instances carried along closed paths (scene/paths.ts
 * compiles the curves), each posed at every step with time passing. A pose is a pure function of
 * time, so `lantern render --time t` and the viewer agree. Pure.
 */
import { compilePaths } from '../scene/paths.ts';
import type { Scene } from '../scene/types.ts';
import type { Animator, AnimatorFactory, UpdateBuilder } from './animator.ts';

/** Plays Scene.dynamics.paths: every step with time passing writes each carried instance's pose at t. */
export const pathAnimator: AnimatorFactory = (scene: Scene): Animator | undefined => {
  const paths = compilePaths(scene);
  if (paths.length === 0) return undefined;
  return {
    step(t: number, dt: number, _view, out: UpdateBuilder, first: boolean): void {
      if (!first && dt === 0) return;
      for (const p of paths) out.pose(p.path.instance, { worldFromObject: p.poseAt(t) });
    },
  };
};
