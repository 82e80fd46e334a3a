/**
 * The real-time frame recipe (Renderer.renderFrame):
 *
 *   path trace (N spp, demodulated radiance + G-buffer) → temporal (reprojected history, variance)
 *     → à-trous ×5 (steps 1, 2, 4, 8, 16) → output (remodulate, or a debug view) → tone map
 *
 * after SVGF (Schied et al. 2017). The Denoiser owns the per-pixel buffers, ping-pongs the G-buffer
 * and the history between frames, and remembers the camera of the previous frame, so moving the
 * camera (Renderer.setCamera) keeps the history: it is reprojected, not thrown away. Temporal off
 * still runs the temporal pass without history, which then only estimates the variance spatially;
 * spatial off skips the à-trous iterations.
 */
import { LanternError } from '../errors.ts';
import type { SceneResources } from '../gpu/scene-resources.ts';
import type { GpuTimer } from '../gpu/timestamps.ts';
import { reflectModule } from '../gpu/wgsl/reflect.ts';
import { ATROUS_STEPS, atrousParams, createDenoisePasses, denoiseOutputParams, temporalParams, type DenoisePasses } from '../passes/denoise-passes.ts';
import type { SceneFeatures } from '../gpu/pack/scene-pack.ts';
import { PathTraceFramePass } from '../passes/path-trace-frame-pass.ts';
import type { TracingKernels } from '../passes/path-trace-pass.ts';
import type { Camera, Torch } from '../scene/types.ts';
import type { RenderSettings } from './settings.ts';
import type { ViewUniform } from '../gpu/view.ts';

/** Bytes of one vec4f per pixel. */
const VEC4_BYTES = 16;

function structSize(name: string): number {
  const def = reflectModule('denoise/gbuffer').defs.structs[name];
  if (!def) throw new Error(`denoise/gbuffer has no struct ${name}`);
  return def.size;
}

interface Buffers {
  readonly width: number;
  readonly height: number;
  readonly frameRadiance: GPUBuffer;
  /** Normal and depth of the current frame (vec4f), read by the à-trous iterations. */
  readonly guide: GPUBuffer;
  /** [current, previous] swap every frame, as do the histories. */
  readonly gbuffers: readonly [GPUBuffer, GPUBuffer];
  readonly histories: readonly [GPUBuffer, GPUBuffer];
  /** The temporal pass's output (illumination + variance), the first à-trous input. */
  readonly temporalOut: GPUBuffer;
  readonly filterA: GPUBuffer;
  readonly filterB: GPUBuffer;
  /** Linear radiance (vec4f), what the tone mapper and readFrame read. */
  readonly output: GPUBuffer;
  /** Bind groups per parity (which G-buffer is current). */
  readonly groups: readonly ParityGroups[];
}

interface ParityGroups {
  readonly temporal: Record<number, GPUBindGroup>;
  readonly atrous: readonly Record<number, GPUBindGroup>[];
  /** Output pass reading the à-trous result [0] or the temporal result [1]. */
  readonly outputFiltered: Record<number, GPUBindGroup>;
  readonly outputUnfiltered: Record<number, GPUBindGroup>;
}

export interface FrameRequest {
  readonly scene: SceneResources;
  readonly view: ViewUniform;
  readonly camera: Camera;
  readonly settings: RenderSettings;
  readonly torch?: Torch;
  readonly samples: number;
  /** Where extension and shadow rays are counted (the renderer's counters). */
  readonly rayCounters: GPUBuffer;
  /** Linear depth shown as mid grey in the depth view. */
  readonly depthScale: number;
  readonly timer?: GpuTimer;
}

export class Denoiser {
  private buffers?: Buffers;
  private previousCamera?: Camera;
  private parity = 0;
  private sampleIndex = 0;
  private historyValid = false;

  private constructor(
    private readonly device: GPUDevice,
    private readonly frame: PathTraceFramePass,
    private readonly passes: DenoisePasses,
  ) {}

  static async create(device: GPUDevice): Promise<Denoiser> {
    const [frame, passes] = await Promise.all([PathTraceFramePass.create(device), createDenoisePasses(device)]);
    return new Denoiser(device, frame, passes);
  }

  /** Compiles the frame path tracer's variant for a scene with these features. */
  prepare(features: SceneFeatures, spectral = false): Promise<void> {
    return this.frame.prepare(features, spectral);
  }

  /** The frame path tracer's kernels (the renderer specialises them with the progressive ones). */
  get frameKernels(): TracingKernels {
    return this.frame.kernels;
  }

  /** The chain's linear output of the last frame (vec4f per pixel), if a frame was rendered. */
  get output(): GPUBuffer | undefined {
    return this.buffers?.output;
  }

  /** Forgets the history: the next frame starts from its own samples alone. */
  resetHistory(): void {
    this.historyValid = false;
    this.previousCamera = undefined;
  }

  /** Records one real-time frame into `encoder` (parameters are written now: submit before the next frame). */
  encodeFrame(encoder: GPUCommandEncoder, r: FrameRequest): void {
    const b = this.ensureBuffers(r.view);
    this.parity ^= 1;
    const groups = b.groups[this.parity]!;
    const s = r.settings;
    const previousCamera = this.previousCamera ?? r.camera;
    const still = sameCamera(previousCamera, r.camera);
    const dispatch = { tile: { x: 0, y: 0, width: b.width, height: b.height }, sampleIndex: this.sampleIndex, samples: r.samples, maxBounces: s.maxBounces, seed: s.seed, lightSampling: s.lightSampling, spectral: s.spectral, ...(r.torch ? { torch: r.torch } : {}) };
    const target = { frameRadiance: b.frameRadiance, gbuffer: b.gbuffers[this.parity]!, guide: b.guide, rayCounters: r.rayCounters };
    this.frame.encode(encoder, r.scene, r.view, previousCamera, target, dispatch, r.timer);

    const unlimited = s.historyCap === 'unlimited';
    this.passes.temporal.write(temporalParams({
      historyCap: unlimited ? Infinity : (s.historyCap as number),
      // A still camera with no cap converges without limit: nothing to clamp against.
      clampK: unlimited && still ? 0 : s.clampK,
      useHistory: s.temporal && this.historyValid,
      stillCamera: still,
    }));
    this.passes.temporal.encode(encoder, groups.temporal, b.width, b.height, r.timer);
    if (s.denoise) {
      ATROUS_STEPS.forEach((_, i) => {
        this.passes.atrous.write(atrousParams(i), i);
        this.passes.atrous.encode(encoder, groups.atrous[i]!, b.width, b.height, r.timer, `a-trous ${i + 1}`);
      });
    }
    const fullHistory = unlimited ? 256 : (s.historyCap as number);
    this.passes.output.write(denoiseOutputParams(s.denoiseView, fullHistory, r.depthScale));
    this.passes.output.encode(encoder, s.denoise ? groups.outputFiltered : groups.outputUnfiltered, b.width, b.height, r.timer);

    this.sampleIndex = (this.sampleIndex + r.samples) >>> 0;
    this.previousCamera = r.camera;
    this.historyValid = true;
  }

  destroy(): void {
    this.destroyBuffers();
    this.frame.destroy();
    for (const p of Object.values(this.passes)) p.destroy();
  }

  private ensureBuffers(view: ViewUniform): Buffers {
    const { width, height } = view;
    if (this.buffers && this.buffers.width === width && this.buffers.height === height) return this.buffers;
    this.destroyBuffers();
    this.resetHistory();
    const pixels = width * height;
    const limits = this.device.limits;
    const gbufferBytes = pixels * structSize('GBufferTexel');
    const historyBytes = pixels * structSize('HistoryTexel');
    const largest = Math.max(gbufferBytes, historyBytes);
    if (largest > limits.maxStorageBufferBindingSize || largest > limits.maxBufferSize) {
      throw new LanternError(`image ${width}×${height} is too large for the real-time denoiser on this GPU (its G-buffer needs ${(largest / 2 ** 20).toFixed(0)} MiB in one buffer)`);
    }
    const make = (label: string, size: number) => this.device.createBuffer({ label, size, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC });
    const gbuffers = [make('g-buffer 0', gbufferBytes), make('g-buffer 1', gbufferBytes)] as const;
    const histories = [make('history 0', historyBytes), make('history 1', historyBytes)] as const;
    const frameRadiance = make('frame radiance', pixels * VEC4_BYTES);
    const guide = make('a-trous guide', pixels * VEC4_BYTES);
    const temporalOut = make('temporal output', pixels * VEC4_BYTES);
    const filterA = make('a-trous A', pixels * VEC4_BYTES);
    const filterB = make('a-trous B', pixels * VEC4_BYTES);
    const output = make('denoised radiance', pixels * VEC4_BYTES);
    // Iteration i reads chain[i] and writes chain[i + 1]; the last result is in filterA.
    const chain = [temporalOut, filterA, filterB, filterA, filterB, filterA];
    const { temporal, atrous, output: out } = this.passes;
    const groups = [0, 1].map((p): ParityGroups => {
      const gbuffer = gbuffers[p]!, history = histories[p]!;
      const outputGroups = (illumination: GPUBuffer) => out.bindGroups(view, { gbuffer, history, filter_input: temporalOut, illumination, output });
      return {
        temporal: temporal.bindGroups(view, { frame_radiance: frameRadiance, gbuffer, previous_gbuffer: gbuffers[1 - p]!, previous_history: histories[1 - p]!, history, filter_input: temporalOut }),
        atrous: ATROUS_STEPS.map((_, i) => atrous.bindGroups(view, { guide, filter_source: chain[i]!, filter_result: chain[i + 1]! }, i)),
        outputFiltered: outputGroups(chain[ATROUS_STEPS.length]!),
        outputUnfiltered: outputGroups(temporalOut),
      };
    });
    this.buffers = { width, height, frameRadiance, guide, gbuffers, histories, temporalOut, filterA, filterB, output, groups };
    return this.buffers;
  }

  private destroyBuffers(): void {
    const b = this.buffers;
    if (!b) return;
    for (const buffer of [b.frameRadiance, b.guide, ...b.gbuffers, ...b.histories, b.temporalOut, b.filterA, b.filterB, b.output]) buffer.destroy();
    this.buffers = undefined;
  }
}

/** Whether two cameras see the same image: pose, field of view and lens (a refocus is a change: the history is clamped, not trusted). */
function sameCamera(a: Camera, b: Camera): boolean {
  const aperture = (c: Camera) => c.lens?.apertureRadius ?? 0;
  const sameLens = aperture(a) === aperture(b) && (aperture(a) === 0 || a.lens?.focusDistance === b.lens?.focusDistance);
  return a === b || (a.vfovDegrees === b.vfovDegrees && sameLens && [0, 1, 2].every((i) => a.position[i] === b.position[i] && a.forward[i] === b.forward[i] && a.up[i] === b.up[i]));
}
