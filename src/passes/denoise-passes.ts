/**
 * The denoiser's image passes, each the TypeScript twin of its WGSL module: temporal accumulation
 * (shaders/passes/temporal.wgsl), the à-trous iterations (shaders/passes/atrous.wgsl) and the output
 * (shaders/passes/denoise-output.wgsl). Each is an ImagePass; what differs is its parameters.
 */
import { DENOISE_VIEWS, type DenoiseView } from './variants.ts';
import { ImagePass } from './image-pass.ts';
import type { UniformValues } from './uniform-params.ts';

/** Steps of the five à-trous iterations (SVGF). */
export const ATROUS_STEPS = [1, 2, 4, 8, 16] as const;
/** SVGF's edge-stopping parameters (Schied et al. 2017, §5). */
export const ATROUS_SIGMAS = { luminance: 4, normal: 128, depth: 1 } as const;

export interface TemporalValues {
  /** Largest history length (Infinity: no cap). */
  readonly historyCap: number;
  /** 0: no clamp. */
  readonly clampK: number;
  readonly useHistory: boolean;
  /** The camera is where it was in the previous frame (first-hit emission is averaged only then). */
  readonly stillCamera: boolean;
}

export interface DenoisePasses {
  readonly temporal: ImagePass<UniformValues>;
  readonly atrous: ImagePass<UniformValues>;
  readonly output: ImagePass<UniformValues>;
}

export async function createDenoisePasses(device: GPUDevice): Promise<DenoisePasses> {
  const [temporal, atrous, output] = await Promise.all([
    ImagePass.create(device, 'passes/temporal', 'temporal_accumulate', 'temporal'),
    ImagePass.create(device, 'passes/atrous', 'atrous_step', 'a-trous', ATROUS_STEPS.length),
    ImagePass.create(device, 'passes/denoise-output', 'denoise_output', 'denoise output'),
  ]);
  return { temporal, atrous, output };
}

/** Largest f32-safe stand-in for an unlimited history. */
const NO_CAP = 1e30;

export const temporalParams = (t: TemporalValues): UniformValues => ({
  history_cap: Number.isFinite(t.historyCap) ? t.historyCap : NO_CAP,
  clamp_k: t.clampK,
  use_history: t.useHistory ? 1 : 0,
  still_camera: t.stillCamera ? 1 : 0,
});

export const atrousParams = (iteration: number): UniformValues => ({
  step: ATROUS_STEPS[iteration]!,
  sigma_luminance: ATROUS_SIGMAS.luminance,
  sigma_normal: ATROUS_SIGMAS.normal,
  sigma_depth: ATROUS_SIGMAS.depth,
});

export const denoiseOutputParams = (view: DenoiseView, fullHistory: number, depthScale: number): UniformValues => ({
  view_mode: DENOISE_VIEWS.indexOf(view),
  full_history: fullHistory,
  depth_scale: depthScale,
});
