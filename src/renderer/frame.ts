/**
 * What every recipe's passes are given for a frame, built once by the Renderer per frame: the
 * device, the scene (its GPU resources and its prepared form), the view and the camera, the settings,
 * the image's targets, the torch the settings leave, the scene's size and the timer. Recipes
 * (renderer/recipes/) take a FrameContext and never the Renderer.
 *
 * The path tracers' dispatch record (tile, sample index, bounces, seed, light sampling, sampler,
 * torch, spectral) is built here, and only here, from the context: pathDispatch.
 */
import { boundsDiagonal } from '../bvh/stats.ts';
import type { GpuTimer } from '../gpu/timestamps.ts';
import type { SceneResources } from '../gpu/scene-resources.ts';
import type { ViewUniform } from '../gpu/view.ts';
import type { PathTraceDispatch, Tile } from '../passes/path-trace-pass.ts';
import type { Camera, Torch } from '../scene/types.ts';
import type { ImageTargets } from './image.ts';
import type { PreparedScene } from './prepare.ts';
import { effectiveTorch, resolveSampler, type RenderSettings } from './settings.ts';

export interface FrameContext {
  readonly device: GPUDevice;
  readonly scene: SceneResources;
  readonly prepared: PreparedScene;
  readonly view: ViewUniform;
  readonly camera: Camera;
  readonly settings: RenderSettings;
  /** The torch at the camera (the scene's, as the settings change it), if one is lit. */
  readonly torch?: Torch;
  readonly targets: ImageTargets;
  /** Half the diagonal of the scene's bounds (the depth view's scale; the hybrid's near plane is set from it). */
  readonly sceneSize: number;
  readonly timer?: GpuTimer;
}

/** A frame's context from what the Renderer holds (Renderer.frame): the torch the settings leave and the scene's size are derived here. */
export function frameContext(base: Omit<FrameContext, 'torch' | 'sceneSize' | 'timer'>, timer?: GpuTimer): FrameContext {
  const torch = effectiveTorch(base.prepared.scene, base.settings.torch);
  return { ...base, sceneSize: 0.5 * boundsDiagonal(base.prepared.bvh) || 1, ...(torch ? { torch } : {}), ...(timer ? { timer } : {}) };
}

/**
 * The path tracers' dispatch record for `samples` paths per pixel over `tile`, starting at sample
 * `sampleIndex`, as the frame's settings say. `use`: whose sampler 'auto' resolves to (the
 * progressive estimate's or the real-time frames'). Kernels compiled RGB only (the hybrid's) are
 * dispatched as RGB whatever `spectral` says.
 */
export function pathDispatch(frame: FrameContext, use: 'progressive' | 'real-time', tile: Tile, sampleIndex: number, samples: number): PathTraceDispatch {
  const s = frame.settings;
  return {
    tile,
    sampleIndex,
    samples,
    maxBounces: s.maxBounces,
    seed: s.seed,
    lightSampling: s.lightSampling,
    sampler: resolveSampler(s.sampler, use),
    ...(frame.torch ? { torch: frame.torch } : {}),
    spectral: s.spectral,
  };
}

/** The whole image as one tile. */
export const wholeImage = (targets: { readonly width: number; readonly height: number }): Tile => ({ x: 0, y: 0, width: targets.width, height: targets.height });
