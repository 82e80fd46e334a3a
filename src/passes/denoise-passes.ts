/**
 * The denoiser's image passes, each the TypeScript twin of its WGSL module: temporal accumulation
 * (shaders/passes/temporal.wgsl), the à-trous iterations over packed records
 * (shaders/passes/denoise-atrous.wgsl) and the output (shaders/passes/denoise-output.wgsl). Each is
 * an ImagePass; what differs is its parameters. The à-trous entry point runs 8 times a frame: once for
 * the depth slopes, then per iteration once to filter, the first two iterations after a dispatch
 * that writes their weight sums. The same à-trous pass filters the hybrid recipe's GI target
 * (createAtrousPass, PING_PONG): one filter for both recipes.
 */
import { DENOISE_VIEWS, type DenoiseView } from './variants.ts';
import { ImagePass } from './image-pass.ts';
import type { UniformValues } from './uniform-params.ts';
import { reflectModule } from '../gpu/wgsl/reflect.ts';

/** Bytes of an illumination pair (f16 rgb, f16 σ; denoise/gbuffer pack_illumination): what the à-trous filters. */
export const PAIR_BYTES = 8;
/** Bytes per pixel of the à-trous filter's own scratch (filter_scratch): its depth slopes and two regions of weight sums. */
export const ATROUS_SCRATCH_BYTES = 12;

/** The size of a struct of a WGSL module (default denoise/gbuffer, the packed records), by reflection. */
export function structSize(name: string, module = 'denoise/gbuffer'): number {
  const def = reflectModule(module).defs.structs[name];
  if (!def) throw new Error(`${module} has no struct ${name}`);
  return def.size;
}

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
}

export interface DenoisePasses {
  readonly temporal: ImagePass<UniformValues>;
  readonly atrous: ImagePass<UniformValues>;
  readonly output: ImagePass<UniformValues>;
}

/** The chain's passes as GpuTimer labels them (renderer/recipes/real-time.ts). */
const TEMPORAL_LABEL = 'temporal';
const OUTPUT_LABEL = 'denoise output';
/** Iteration i's label (0-based): 'a-trous 1' … 'a-trous 5'. */
export const atrousLabel = (iteration: number): string => `a-trous ${iteration + 1}`;
/** The dispatch before iteration i that writes each pixel's weight sum: 'a-trous 1 weights' … */
export const atrousWeightsLabel = (iteration: number): string => `${atrousLabel(iteration)} weights`;
/** The dispatch before the iterations that writes each pixel's depth slopes. */
export const ATROUS_SLOPES_LABEL = 'a-trous slopes';

/** The iterations whose weight sums a dispatch of their own computes (passes/denoise-atrous ATROUS_WEIGHTS). */
export const EXACT_WEIGHT_ITERATIONS = 2;

/** The à-trous pass's parameter slots: the iterations', then the slopes', then the weights dispatches'. */
export const ATROUS_SLOPES_SLOT = ATROUS_STEPS.length;
export const atrousWeightsSlot = (iteration: number): number => ATROUS_STEPS.length + 1 + iteration;
const ATROUS_SLOTS = ATROUS_STEPS.length + 1 + EXACT_WEIGHT_ITERATIONS;

/** Whether a timed pass (its GpuTimer label) belongs to the real-time denoising chain: the temporal pass, an à-trous dispatch or the debug views' output. */
export const isDenoiseChainPass = (label: string): boolean =>
  label === TEMPORAL_LABEL || label === OUTPUT_LABEL || label === ATROUS_SLOPES_LABEL || ATROUS_STEPS.some((_, i) => atrousLabel(i) === label || atrousWeightsLabel(i) === label);

/** The à-trous pass (passes/denoise-atrous) with its parameter slots (ATROUS_SLOTS): the real-time chain's, and the hybrid recipe's GI filter. */
export const createAtrousPass = (device: GPUDevice, label: string): Promise<ImagePass<UniformValues>> =>
  ImagePass.create(device, 'passes/denoise-atrous', 'denoise_atrous_step', label, ATROUS_SLOTS);

export async function createDenoisePasses(device: GPUDevice): Promise<DenoisePasses> {
  const [temporal, atrous, output] = await Promise.all([
    ImagePass.create(device, 'passes/temporal', 'temporal_accumulate', TEMPORAL_LABEL),
    createAtrousPass(device, 'a-trous'),
    ImagePass.create(device, 'passes/denoise-output', 'denoise_output', OUTPUT_LABEL),
  ]);
  return { temporal, atrous, output };
}

/** Largest f32-safe stand-in for an unlimited history. */
const NO_CAP = 1e30;

export const temporalParams = (t: TemporalValues): UniformValues => ({
  history_cap: Number.isFinite(t.historyCap) ? t.historyCap : NO_CAP,
  clamp_k: t.clampK,
  use_history: t.useHistory ? 1 : 0,
});

export const atrousParams = (iteration: number): UniformValues => ({
  step: ATROUS_STEPS[iteration]!,
  sigma_luminance: ATROUS_SIGMAS.luminance,
  sigma_normal: ATROUS_SIGMAS.normal,
  sigma_depth: ATROUS_SIGMAS.depth,
});

/** Where an iteration's illumination pairs are: bound array (a: the frame scratch, b: the colour history or the previous moments), words stride · pixel + offset. */
export interface PairRegion {
  readonly array: 'a' | 'b';
  readonly stride: number;
  readonly offset: number;
}

/** One à-trous iteration: its source, its result, whether it copies its source to `b`. */
export interface AtrousStep {
  readonly source: PairRegion;
  /** 'output': remodulate and write the frame's linear output over the frame scratch (`a`). */
  readonly result: PairRegion | 'output';
  /** Also copy the source's own pairs into the colour history (`b`): the history without feedback. */
  readonly copyHistory: boolean;
}

/** One à-trous iteration of the real-time chain: also what `b` is bound to. */
export interface AtrousIteration extends AtrousStep {
  readonly b: 'history' | 'previous-moments';
}

/**
 * An iteration from the pairs of one buffer (`a`) into another (`b`), a pair per pixel: the hybrid
 * recipe's GI filter, whose two GI buffers swap roles every iteration.
 */
export const PING_PONG: AtrousStep = { source: { array: 'a', stride: 2, offset: 0 }, result: { array: 'b', stride: 2, offset: 0 }, copyHistory: false };

const SCRATCH_LOW: PairRegion = { array: 'a', stride: 4, offset: 0 };
/** Words 2–3 of the frame scratch: where the temporal pass leaves its output (FRAME_TEMPORAL). */
const SCRATCH_HIGH: PairRegion = { array: 'a', stride: 4, offset: 2 };
const IN_B: PairRegion = { array: 'b', stride: 2, offset: 0 };

/**
 * The five iterations' buffers. With feedback (SVGF §4) the first writes the colour history, which
 * the temporal pass has finished reading, and the next ones read it from there; without, the first
 * copies the temporal output into the history unfiltered. Both then ping-pong between the two halves
 * of the frame scratch, pass through the previous frame's moments (read by the temporal pass, free
 * until the next frame writes them) and end in the output, which overwrites the frame scratch: no
 * buffer of the chain is allocated for one iteration alone.
 */
export function atrousSchedule(feedback: boolean): readonly AtrousIteration[] {
  return feedback
    ? [
        { b: 'history', source: SCRATCH_HIGH, result: IN_B, copyHistory: false },
        { b: 'history', source: IN_B, result: SCRATCH_LOW, copyHistory: false },
        { b: 'history', source: SCRATCH_LOW, result: SCRATCH_HIGH, copyHistory: false },
        { b: 'previous-moments', source: SCRATCH_HIGH, result: IN_B, copyHistory: false },
        { b: 'previous-moments', source: IN_B, result: 'output', copyHistory: false },
      ]
    : [
        { b: 'history', source: SCRATCH_HIGH, result: SCRATCH_LOW, copyHistory: true },
        { b: 'history', source: SCRATCH_LOW, result: SCRATCH_HIGH, copyHistory: false },
        { b: 'history', source: SCRATCH_HIGH, result: SCRATCH_LOW, copyHistory: false },
        { b: 'previous-moments', source: SCRATCH_LOW, result: IN_B, copyHistory: false },
        { b: 'previous-moments', source: IN_B, result: 'output', copyHistory: false },
      ];
}

/**
 * Parameters of iteration i of `iterations` (shaders/passes/denoise-atrous.wgsl), whose bind group
 * has the buffer of `it.source` as source_words and the other as other_words (renderer/recipes/
 * real-time.ts: the chain's five; renderer/recipes/hybrid.ts: the GI filter's three, PING_PONG).
 */
export const denoiseAtrousParams = (iteration: number, it: AtrousStep | AtrousIteration, iterations: number = ATROUS_STEPS.length): UniformValues => {
  const result = it.result === 'output' ? SCRATCH_LOW : it.result;
  // The copy goes to other_words, which must then be the colour history.
  if (it.copyHistory && !(it.source.array === 'a' && 'b' in it && it.b === 'history')) throw new Error('atrous: the history copy needs the source in the frame scratch');
  if (iteration >= iterations || iterations > ATROUS_STEPS.length) throw new Error(`atrous: iteration ${iteration + 1} of ${iterations} (at most ${ATROUS_STEPS.length})`);
  return {
    ...atrousParams(iteration),
    source_stride: it.source.stride,
    source_offset: it.source.offset,
    // 0: the source's buffer, 1: the other.
    result_array: result.array === it.source.array ? 0 : 1,
    result_stride: result.stride,
    result_offset: result.offset,
    // ATROUS_PLAIN, ATROUS_COPY_HISTORY, ATROUS_OUTPUT.
    mode: it.result === 'output' ? 2 : it.copyHistory ? 1 : 0,
    // Iteration i reads the weight sums in region 1 + i % 2: its weights dispatch's (the first
    // EXACT_WEIGHT_ITERATIONS), else those its predecessor wrote there, capping its coefficients.
    weights_read: weightsRegion(iteration),
    weights_write: iteration + 1 >= EXACT_WEIGHT_ITERATIONS && iteration + 1 < iterations ? weightsRegion(iteration + 1) : 0,
    capped: iteration >= EXACT_WEIGHT_ITERATIONS ? 1 : 0,
  };
};

const weightsRegion = (iteration: number): number => 1 + (iteration % 2);

/** The dispatch before iteration i (its step, its source) that writes the weight sums: ATROUS_WEIGHTS. */
export const denoiseWeightsParams = (iteration: number, it: AtrousStep | AtrousIteration, iterations: number = ATROUS_STEPS.length): UniformValues => {
  if (iteration >= EXACT_WEIGHT_ITERATIONS) throw new Error(`atrous: iteration ${iteration + 1} has no weights dispatch`);
  return { ...denoiseAtrousParams(iteration, it, iterations), mode: 4, weights_read: 0, weights_write: weightsRegion(iteration) };
};

/** The dispatch before the iterations that writes the depth slopes (ATROUS_SLOPES); it reads no pairs. */
export const denoiseSlopesParams = (): UniformValues => ({ ...denoiseAtrousParams(0, atrousSchedule(false)[0]!), mode: 3, weights_read: 0, weights_write: 0, capped: 0 });

export const denoiseOutputParams = (view: DenoiseView, fullHistory: number, depthScale: number): UniformValues => ({
  view_mode: DENOISE_VIEWS.indexOf(view),
  full_history: fullHistory,
  depth_scale: depthScale,
});
