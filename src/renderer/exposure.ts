/**
 * Exposure: which one an image gets (the scene's own, a manual one, or automatic), and the CPU twin of
 * the automatic exposure's GPU pass (shaders/passes/exposure.wgsl), which its tests hold the pass to.
 *
 * Automatic exposure works as an eye adapting to a room: the image's log-average luminance L̄ (the
 * geometric mean, Reinhard et al. 2002, "Photographic Tone Reproduction for Digital Images", eq. 1)
 * is mapped to middle grey, so target = log2(0.18 / L̄) + compensation stops, and the exposure in use
 * moves toward it exponentially in stops: e(t + Δt) = target + (e(t) − target)·exp(−Δt / τ), τ the
 * adaptation time. Working in stops makes a change of brightness by a factor take the same time
 * whether the room gets brighter or darker. Pure: no GPU, no DOM.
 */
import type { Scene } from '../scene/types.ts';
import type { RenderSettings } from './settings.ts';

/** Reinhard's key of a normal scene: the log-average luminance is mapped to it (lib/exposure.wgsl). */
export const MIDDLE_GREY = 0.18;
/** The luminance clamp before the log (lib/exposure.wgsl): an unlit pixel would pull the average to −∞. */
export const MIN_EXPOSURE_LUMINANCE = 2 ** -20;
export const MAX_EXPOSURE_LUMINANCE = 2 ** 20;

/** Rec. 709 luminance of linear RGB (lib/color.wgsl luminance). */
const luminance = (r: number, g: number, b: number) => 0.2126 * r + 0.7152 * g + 0.0722 * b;

/**
 * log2 of the log-average luminance of linear RGB pixels (`channels` floats a pixel, RGB first, each
 * scaled by `scale`), each luminance clamped as the GPU pass does. An empty image gives middle grey.
 */
export function log2AverageLuminance(pixels: ArrayLike<number>, channels: 3 | 4, scale = 1): number {
  const n = Math.floor(pixels.length / channels);
  if (n === 0) return Math.log2(MIDDLE_GREY);
  let sum = 0;
  for (let i = 0; i < n; i++) {
    const o = i * channels;
    const l = luminance(pixels[o]! * scale, pixels[o + 1]! * scale, pixels[o + 2]! * scale);
    sum += Math.log2(Number.isFinite(l) ? Math.min(MAX_EXPOSURE_LUMINANCE, Math.max(MIN_EXPOSURE_LUMINANCE, l)) : MAX_EXPOSURE_LUMINANCE);
  }
  return sum / n;
}

/** The exposure in stops that maps a log-average luminance (log2) to middle grey, plus the compensation. */
export function targetExposureStops(log2Average: number, compensationStops: number): number {
  return Math.log2(MIDDLE_GREY) - log2Average + compensationStops;
}

/** The fraction of the way to the target left after `seconds` of adapting with time constant `tau`. */
export function adaptationKeep(seconds: number, tau: number): number {
  return Math.exp(-Math.max(0, seconds) / tau);
}

/** One step of adaptation: the exposure (stops) after `seconds` toward `target` (stops). */
export function adaptExposureStops(current: number, target: number, seconds: number, tau: number): number {
  return target + (current - target) * adaptationKeep(seconds, tau);
}

/** How an image is exposed: a fixed number of stops, or automatically with a compensation. */
export type ExposureChoice =
  | { readonly kind: 'manual'; readonly stops: number }
  | { readonly kind: 'auto'; readonly compensationStops: number; readonly adaptationSeconds: number };

/**
 * The exposure the settings give a scene. The exposure setting absent: the scene's kind decides
 * (Scene.autoExposure: the game maps adapt, reference scenes keep their camera's exposure); a number:
 * that many stops over the camera's exposure; 'auto': automatic whatever the scene.
 */
export function exposureChoice(
  scene: Pick<Scene, 'autoExposure'> | undefined,
  cameraStops: number,
  s: Pick<RenderSettings, 'exposureStops' | 'exposureCompensation' | 'exposureAdaptation'>,
): ExposureChoice {
  const auto = s.exposureStops === 'auto' || (s.exposureStops === undefined && scene?.autoExposure === true);
  if (auto) return { kind: 'auto', compensationStops: s.exposureCompensation, adaptationSeconds: s.exposureAdaptation };
  return { kind: 'manual', stops: cameraStops + (typeof s.exposureStops === 'number' ? s.exposureStops : 0) };
}
