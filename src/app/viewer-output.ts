/**
 * What the viewer hands out, read from its renderer once the image is a whole frame (Viewer waits
 * for that): the tone-mapped image as PNG bytes or as RGBA8 with its sample count (the test hook),
 * the linear radiance as EXR; and the view as a link's parameters (the page adds the scene's location).
 */
import { encodeExr } from '../image/exr.ts';
import { encodePng } from '../image/png.ts';
import type { Renderer } from '../renderer/renderer.ts';
import type { Environment } from '../scene/environment.ts';
import type { CameraController } from './camera-controller.ts';
import { linkOfEnvironment } from './environment-choice.ts';
import type { MaterialOverride } from './material-link.ts';
import { LINKED_RENDER_SETTINGS, type ViewParams } from './view-params.ts';
import type { ViewerSettings } from './viewer-types.ts';

/** The tone-mapped image as PNG bytes. */
export async function pngOf(renderer: Renderer): Promise<Uint8Array> {
  return encodePng(renderer.width, renderer.height, await renderer.readImage());
}

/** The tone-mapped image (RGBA8, what a screenshot holds) with `samples`, the sample count at the moment it is read. */
export async function imageOf(renderer: Renderer, samples: number): Promise<{ samples: number; width: number; height: number; rgba: number[] }> {
  const rgba = await renderer.readImage();
  return { samples, width: renderer.width, height: renderer.height, rgba: Array.from(rgba) };
}

/** The linear radiance as EXR bytes: float32 RGB, before exposure and tone mapping; `realTime`: the denoised frame is shown, else the estimate. */
export async function exrOf(renderer: Renderer, realTime: boolean): Promise<Uint8Array> {
  const { width, height, radiance } = realTime ? await renderer.readFrame() : await renderer.readAccumulation();
  return encodeExr(width, height, radiance);
}

/** What a link says of the view: the camera, the settings, the environment and the material edits. */
export interface LinkedView {
  readonly controller: CameraController | undefined;
  readonly settings: ViewerSettings;
  /** Whether the user fixed the resolution (else the budget of whoever opens the link chooses it). */
  readonly scaleFixed: boolean;
  /** The environment that replaces the scene's own, if any. */
  readonly environment: Environment | undefined;
  /** The material edits, if any were made. */
  readonly materials: MaterialOverride[] | undefined;
}

/** The camera and settings as URL parameters (the page adds the scene's location). */
export function viewParamsOf(view: LinkedView): ViewParams {
  const c = view.controller;
  const s = view.settings;
  const t = s.render.torch;
  return {
    ...(c ? { pose: c.pose, fovDegrees: c.vfovDegrees, mode: c.mode } : {}),
    ...(c?.lens ? { apertureRadius: c.lens.apertureRadius, focusDistance: c.lens.focusDistance } : {}),
    samplesPerFrame: s.samplesPerFrame,
    // A link carries a scale only where the user fixed one: otherwise the budget of whoever opens it chooses.
    ...(view.scaleFixed ? { scale: s.scale } : {}),
    accumulate: s.accumulate,
    ...(s.animate ? {} : { animate: false }),
    ...(s.convergeWhenStill ? {} : { convergeWhenStill: false }),
    ...Object.fromEntries(LINKED_RENDER_SETTINGS.map((k) => [k, s.render[k]])),
    ...linkOfEnvironment(view.environment),
    ...(view.materials ? { materials: view.materials } : {}),
    torch: { enabled: t.enabled, ...(t.color ? { color: [t.color[0], t.color[1], t.color[2]] } : {}), ...(t.intensity !== undefined ? { intensity: t.intensity } : {}), ...(t.range !== undefined ? { range: t.range } : {}) },
  };
}
