/**
 * The real-time recipe (recipeFor's 'real-time'; Renderer.renderFrame), the chain once called the
 * Denoiser:
 *
 *   [ReSTIR: G-buffer, reservoirs: initial, temporal, spatial — the whole image, with the first band]
 *   path trace (N spp, demodulated radiance + G-buffer) → temporal (reprojected history, variance)
 *     → à-trous ×5 (steps 1, 2, 4, 8, 16; the last remodulates) → tone map
 *     (without the filter, or for a debug view: → output pass → tone map)
 *
 * after SVGF (Schied et al. 2017), with its feedback: the first à-trous iteration's output is the
 * colour history. The recipe owns the per-pixel buffers (72 bytes a pixel in all, 80 with ReSTIR, bufferSizes():
 * packed records, and buffers shared by passes whose lifetimes do not overlap, atrousSchedule),
 * ping-pongs the surface records and the moments between frames, and remembers the camera of the
 * previous frame, so moving the
 * camera (Renderer.setCamera) keeps the history: it is reprojected, not thrown away. Temporal off
 * still runs the temporal pass without history, which then only estimates the variance spatially;
 * spatial off skips the à-trous iterations.
 */
import { LanternError } from '../../errors.ts';
import type { SceneResources } from '../../gpu/scene-resources.ts';
import type { GpuTimer } from '../../gpu/timestamps.ts';
import { pathDispatch, wholeImage, type FrameContext } from '../frame.ts';
import type { FrameRecipe, RecipeFrame } from './frame-recipe.ts';
import {
  ATROUS_SCRATCH_BYTES, ATROUS_SLOPES_LABEL, ATROUS_SLOPES_SLOT, EXACT_WEIGHT_ITERATIONS, PAIR_BYTES, structSize, atrousLabel, atrousSchedule, atrousWeightsLabel, atrousWeightsSlot, createDenoisePasses, denoiseAtrousParams,
  denoiseOutputParams, denoiseSlopesParams, denoiseWeightsParams, temporalParams, type DenoisePasses,
} from '../../passes/denoise-passes.ts';
import type { SceneFeatures } from '../../gpu/pack/scene-pack.ts';
import type { Sampler } from '../../passes/variants.ts';
import { PathTraceFramePass, type FrameTarget } from '../../passes/path-trace-frame-pass.ts';
import { WavefrontFramePass } from '../../passes/wavefront-frame-pass.ts';
import { RestirPass, type RestirTarget } from '../../passes/restir-pass.ts';
import { readBuffer } from '../../gpu/readback.ts';
import type { Tile, TracingKernels } from '../../passes/path-trace-pass.ts';
import type { Camera } from '../../scene/types.ts';
import type { Integrator, RenderSettings } from '../settings.ts';
import type { ViewUniform } from '../../gpu/view.ts';

/** Bytes of the frame scratch per pixel: four words (FRAME_* of shaders/denoise/gbuffer.wgsl), at the end the output vec4f. */
const SCRATCH_BYTES = 16;

/** One buffer of the real-time chain and its bytes per pixel. */
export interface DenoiserBufferSize {
  readonly label: string;
  readonly bytesPerPixel: number;
}

interface Buffers {
  readonly width: number;
  readonly height: number;
  /**
   * Four words per pixel reused through the frame: the path tracer's radiance and motion, the
   * temporal output, two à-trous ping-pong pairs, and at the end the linear output (vec4f) that the
   * tone mapper and readFrame read.
   */
  readonly scratch: GPUBuffer;
  /** The pixel-centre surface records, [current, previous]: they swap every frame, as do the moments. */
  readonly surfaces: readonly [GPUBuffer, GPUBuffer];
  /** The current frame's albedo and emission (FrameTexel). */
  readonly frameRecords: GPUBuffer;
  readonly moments: readonly [GPUBuffer, GPUBuffer];
  /** The colour history (illumination pairs): written by the first à-trous iteration (feedback) or the output pass. */
  readonly history: GPUBuffer;
  /**
   * The last finished frame's final ReSTIR reservoirs (ReservoirTexel, shaders/restir/reservoir.wgsl),
   * allocated only while settings.restir is on. A frame's own go to the current moments until it finishes (restirTarget).
   */
  readonly reservoirs?: GPUBuffer;
  /** Bind groups per parity (which surface record is current). */
  readonly groups: readonly ParityGroups[];
}

/** A frame begun and not yet finished or abandoned. */
interface OpenFrame {
  readonly frame: FrameContext;
  /** Paths per pixel. */
  readonly samples: number;
  readonly buffers: Buffers;
  /** Whether it runs ReSTIR (settled when it begins). */
  readonly restir: boolean;
  /** Whether its first band recorded the whole image's G-buffer and reservoir passes (ReSTIR). */
  preludeDone: boolean;
}

/** How encodeTrace records a frame's tracing. */
interface TraceOptions {
  /** The band traced (default the whole image). */
  readonly tile?: Tile;
  /** Times the wavefront's stages apart. */
  readonly breakdown?: boolean;
  /** ReSTIR: the paths shade the frame's final reservoirs; `prelude` records the whole image's G-buffer and reservoir passes first. */
  readonly restir?: boolean;
  readonly prelude?: boolean;
}

interface ParityGroups {
  readonly temporal: Record<number, GPUBindGroup>;
  /** Each schedule's iterations (atrousSchedule: index 0 without feedback, 1 with): the weight sums' dispatch (the first EXACT_WEIGHT_ITERATIONS) and the filter's. */
  readonly atrous: readonly (readonly { readonly weights?: Record<number, GPUBindGroup>; readonly filter: Record<number, GPUBindGroup> }[])[];
  /** The depth slopes' dispatch, before the iterations. */
  readonly slopes: Record<number, GPUBindGroup>;
  readonly output: Record<number, GPUBindGroup>;
}

/** Timestamp slots a split frame leaves for the passes after its bands (temporal, à-trous ×5, tone map, present, debug). */
const TIMER_ROOM_AFTER_BANDS = 12;
/**
 * The most timed passes one band records: its G-buffer, emission and paths (3), or with ReSTIR the
 * first band's whole-image G-buffer and emission, 'restir initial', 'restir temporal', 'restir
 * spatial', 'restir lend' and its paths (7).
 */
const TIMER_SLOTS_PER_BAND = 7;

/** The frame with its timer while the timer has room for a band's passes and those after the bands (each band's passes are named alike: readers sum them). */
function timedWhileRoom(frame: FrameContext, timer: GpuTimer | undefined): FrameContext {
  if (!timer || timer.room >= TIMER_ROOM_AFTER_BANDS + TIMER_SLOTS_PER_BAND) return frame;
  const { timer: _, ...untimed } = frame;
  return untimed;
}

/** The raw output of a frame's path tracing (before any filter), as the frame kernels write it, unpacked. */
export interface FrameTrace {
  readonly width: number;
  readonly height: number;
  /** vec4f per pixel: mean demodulated radiance, 1. */
  readonly radiance: Float32Array;
  /** SurfaceTexel per pixel (shaders/denoise/gbuffer.wgsl), raw bytes: the pixel-centre surface. */
  readonly gbuffer: ArrayBuffer;
  /** vec4f per pixel: normal, linear depth (the surface records unpacked). */
  readonly guide: Float32Array;
  /** rgb per pixel: mean first-hit albedo and kept first-hit emission of the samples. */
  readonly albedo: Float32Array;
  readonly emission: Float32Array;
  /** Which integrator traced it. */
  readonly integrator: Integrator;
}

export class RealTimeRecipe implements FrameRecipe {
  private buffers?: Buffers;
  /** The wavefront frame path tracer, made by compileWavefront (settings.integrator = 'wavefront'). */
  private wavefront?: WavefrontFramePass;
  private wavefrontPending?: Promise<WavefrontFramePass>;
  /** Every (features, spectral) the frame kernels were prepared for, so a wavefront made later compiles them too. */
  private readonly preparedFor = new Map<string, { readonly features: SceneFeatures; readonly spectral: boolean }>();
  private readonly wavefrontReady = new Set<string>();
  private lastIntegrator: Integrator = 'megakernel';
  private previousCamera?: Camera;
  private parity = 0;
  private sampleIndex = 0;
  private historyValid = false;
  /** The frame begun (beginFrame) and not yet finished or abandoned. */
  private open?: OpenFrame;
  /** Whether the reservoirs hold the last finished frame's (it ran ReSTIR at this size). */
  private restirHistoryValid = false;
  /** The ReSTIR passes, made by compileRestir (settings.restir), and the scenes they are compiled for. */
  private restir?: RestirPass;
  private restirPending?: Promise<RestirPass>;
  private readonly restirReady = new Set<string>();

  private constructor(
    private readonly device: GPUDevice,
    private readonly frame: PathTraceFramePass,
    private readonly passes: DenoisePasses,
    /** The features create() was given (the scene to be rendered, where known). */
    private readonly first: SceneFeatures | undefined,
  ) {}

  /** `first`: the features of the scene to be rendered, where known (its frame kernels compile instead of a plain scene's). */
  /** `sampler`: the frame path tracer's, as the settings resolve it (PathTraceFramePass.create). */
  static async create(device: GPUDevice, first?: SceneFeatures, sampler?: Sampler): Promise<RealTimeRecipe> {
    const [frame, passes] = await Promise.all([PathTraceFramePass.create(device, first, sampler), createDenoisePasses(device)]);
    return new RealTimeRecipe(device, frame, passes, first);
  }

  /** Compiles the frame path tracer's variant for a scene with these features. */
  async prepare(features: SceneFeatures, spectral = false): Promise<void> {
    this.preparedFor.set(featureKey(features, spectral), { features, spectral });
    await Promise.all([this.frame.prepare(features, spectral), this.restir && !spectral ? this.prepareRestir(this.restir, features) : undefined, this.wavefront ? this.prepareWavefront(this.wavefront, features, spectral) : undefined]);
  }

  /**
   * Compiles the wavefront frame path tracer for `current` (the scene set now, if one is), every scene
   * prepared while it compiles, and every later one (prepare). Until it is ready for a frame's scene,
   * frames asking for it are traced by the megakernel (frameIntegrator says which ran).
   */
  async compileWavefront(current?: SceneFeatures): Promise<void> {
    if (!this.wavefrontPending) {
      const wanted = this.wantedBy(current);
      this.wavefrontPending = WavefrontFramePass.create(this.device, current ?? this.firstPrepared(false)).then(async (w) => {
        await Promise.all(wanted().map((p) => this.prepareWavefront(w, p.features, p.spectral)));
        this.wavefront = w;
        return w;
      });
      this.wavefrontPending.catch(() => (this.wavefrontPending = undefined));
    }
    await this.wavefrontPending;
  }

  /** Compiles the ReSTIR passes as compileWavefront does the wavefront; frames use them once ready for their scene. */
  async compileRestir(current?: SceneFeatures): Promise<void> {
    if (!this.restirPending) {
      const wanted = this.wantedBy(current);
      this.restirPending = RestirPass.create(this.device, current ?? this.firstPrepared(false)).then(async (r) => {
        await Promise.all(wanted().filter((p) => !p.spectral).map((p) => this.prepareRestir(r, p.features)));
        this.restir = r;
        return r;
      });
      this.restirPending.catch(() => (this.restirPending = undefined));
    }
    await this.restirPending;
  }

  /**
   * What a pass enabled now compiles once made: the variants prepared for `current`, and those
   * prepared from now on (while it compiles, prepare() cannot reach it). Without `current`, every
   * variant prepared. The other scenes prepared before get theirs when they are set again (prepare):
   * compiling ReSTIR for every scene a renderer had traced cost the denoise test 12 compiles.
   */
  private wantedBy(current: SceneFeatures | undefined): () => { readonly features: SceneFeatures; readonly spectral: boolean }[] {
    const before = new Set(this.preparedFor.keys());
    const currentKey = current && featureKey(current, false);
    return () => [...this.preparedFor.entries()].filter(([k, p]) => !current || !before.has(k) || featureKey(p.features, false) === currentKey).map(([, p]) => p);
  }

  /**
   * The features a pass made now compiles for first: the first scene prepared, or before any, the one
   * create() was told of (ReSTIR or the wavefront enabled before the scene is set compiled a plain
   * scene's variants beside it: 4 pipelines for nothing in the ReSTIR test).
   */
  private firstPrepared(spectral: boolean): SceneFeatures | undefined {
    for (const p of this.preparedFor.values()) if (p.spectral === spectral) return p.features;
    return spectral ? undefined : this.first;
  }

  private async prepareRestir(r: RestirPass, features: SceneFeatures): Promise<void> {
    await r.prepare(features);
    this.restirReady.add(featureKey(features, false));
  }

  private async prepareWavefront(w: WavefrontFramePass, features: SceneFeatures, spectral: boolean): Promise<void> {
    await w.prepare(features, spectral);
    this.wavefrontReady.add(featureKey(features, spectral));
  }

  /** The wavefront frame path tracer, once compileWavefront made it (the renderer specialises it with the other tracing kernels). */
  get wavefrontPass(): WavefrontFramePass | undefined {
    return this.wavefront;
  }

  /** Whether a frame of this scene in these settings is traced by the wavefront (which traces whole frames only: no bands). */
  tracesWavefront(scene: SceneResources, s: RenderSettings): boolean {
    return s.integrator === 'wavefront' && this.wavefront !== undefined && this.wavefrontReady.has(featureKey(scene.features, s.spectral));
  }

  /** Which integrator traced the last frame. */
  get frameIntegrator(): Integrator {
    return this.lastIntegrator;
  }

  /** Bytes of the wavefront's own buffers now (path state, queues), beyond the frame's outputs; 0 until it traced a frame. */
  get wavefrontAllocatedBytes(): number {
    return this.wavefront?.allocatedBytes ?? 0;
  }

  /** The frame path tracer's kernels (the renderer specialises them with the progressive ones). */
  get frameKernels(): TracingKernels {
    return this.frame.kernels;
  }

  /** The chain's linear output of the last frame (vec4f per pixel, over the frame scratch), if a frame was rendered. */
  get output(): GPUBuffer | undefined {
    return this.buffers?.scratch;
  }

  /** The buffers of the real-time chain as allocated now (empty before the first frame), with their bytes per pixel. */
  bufferSizes(): readonly DenoiserBufferSize[] {
    const b = this.buffers;
    if (!b) return [];
    const pixels = b.width * b.height;
    return [b.scratch, ...b.surfaces, b.frameRecords, ...b.moments, b.history, ...(b.reservoirs ? [b.reservoirs] : [])].map((buffer) => ({ label: buffer.label, bytesPerPixel: buffer.size / pixels }));
  }

  /** Bytes per pixel of everything the real-time chain allocates (bufferSizes); 0 before the first frame. */
  bytesPerPixel(): number {
    return this.bufferSizes().reduce((sum, b) => sum + b.bytesPerPixel, 0);
  }

  /** A debug view of the chain (settings.denoiseView) is shown as computed: no exposure, no tone curve. */
  showsRawValues(frame: Pick<FrameContext, 'settings'>): boolean {
    return frame.settings.denoiseView !== 'output';
  }

  /**
   * The next frame draws the random streams of samples `sampleIndex` on, as if the frames before it
   * had been rendered (frame f of a sequence of `spp` samples a frame: f·spp). For frames without
   * history (no temporal pass, filter or ReSTIR), the only thing a frame inherits: a farm's chunk of
   * frames renders its own frames alone. `previousCamera`: the camera of the frame before (none
   * before a sequence's first), which a frame compares its own with (a still camera converges).
   */
  seek(sampleIndex: number, previousCamera: Camera | undefined): void {
    this.sampleIndex = sampleIndex >>> 0;
    this.previousCamera = previousCamera;
  }

  /** Forgets the history: the next frame starts from its own samples alone. */
  resetHistory(): void {
    this.historyValid = false;
    this.restirHistoryValid = false;
    this.previousCamera = undefined;
  }

  /**
   * Begins a frame of `samples` paths per pixel: its path tracing is recorded in row bands (each band
   * may go in a submission of its own; the wavefront traces whole frames only), its temporal pass and
   * filter with the last (finish). Until then, abandon gives the frame up and leaves the history as
   * it was. Parameters are written as each part is recorded: submit it before the next is recorded.
   */
  begin(frame: FrameContext, samples: number): RecipeFrame {
    if (this.open) throw new Error('RealTimeRecipe: finish or abandon a frame before the next begins');
    const buffers = this.ensureBuffers(frame.view, frame.settings.restir);
    // The surface records ping-pong: this frame writes the other one.
    this.parity ^= 1;
    // Whether the frame runs ReSTIR is settled now, for all its bands (the passes may become ready mid-frame).
    const open: OpenFrame = { frame, samples, buffers, restir: this.usesRestir(frame, buffers), preludeDone: false };
    this.open = open;
    const whole = this.tracesWavefront(frame.scene, frame.settings);
    return {
      splittable: !whole,
      band: (encoder, tile) => this.encodeBand(encoder, open, timedWhileRoom(frame, frame.timer), whole ? undefined : tile),
      finish: (encoder) => this.finishFrame(encoder, open),
      abandon: () => this.abandonFrame(open),
    };
  }

  /**
   * Records the path tracing of `tile` (default the whole image) of the frame begun. Each pixel's
   * paths and G-buffer depend on that pixel alone, so bands add up to exactly the unsplit frame.
   * With ReSTIR, the spatial reuse reads every pixel's temporal reservoir: the first band records the
   * whole image's G-buffer and reservoir passes before its paths, and every band traces paths alone.
   * The wavefront traces whole frames only: it asks for the whole image.
   */
  private encodeBand(encoder: GPUCommandEncoder, f: OpenFrame, r: FrameContext, tile?: Tile): void {
    if (this.open !== f) throw new Error('RealTimeRecipe: a band of a frame finished or given up');
    this.encodeTrace(encoder, r, f.samples, f.buffers, this.sampleIndex, { ...(tile ? { tile } : {}), restir: f.restir, prelude: !f.preludeDone });
    f.preludeDone = true;
  }

  /** Records the frame's temporal pass and filter (after every band) and makes it the history. */
  private finishFrame(encoder: GPUCommandEncoder, f: OpenFrame): void {
    if (this.open !== f) throw new Error('RealTimeRecipe: a frame finished or given up already');
    this.open = undefined;
    const r = f.frame;
    const b = f.buffers;
    const groups = b.groups[this.parity]!;
    // The frame's final reservoirs become the history before the temporal pass overwrites the moments they were lent.
    if (f.restir) this.restir!.keepHistory(encoder, this.restirTarget(b, r));
    this.restirHistoryValid = f.restir;
    const s = r.settings;
    const previousCamera = this.previousCamera ?? r.camera;
    const still = sameCamera(previousCamera, r.camera);

    const unlimited = s.historyCap === 'unlimited';
    // A still camera with no cap converges without limit: nothing to clamp against.
    const converging = unlimited && still;
    // Feedback (the first à-trous iteration's output as the history, SVGF §4) only while the camera
    // moves: there it steadies the history that reprojection resamples; on a still camera the filtered
    // colour fed back frame after frame blurs what the accumulation should converge to (measured on
    // the H200, Cornell box 960×540 at 4 spp: relMSE 0.00052 with feedback always, docs/denoise.md).
    const feedback = !still;
    this.passes.temporal.write(temporalParams({
      historyCap: unlimited ? Infinity : (s.historyCap as number),
      clampK: converging ? 0 : s.clampK,
      useHistory: s.temporal && this.historyValid,
    }));
    this.passes.temporal.encode(encoder, { groups: groups.temporal, width: b.width, height: b.height, timer: r.timer });
    // Debug views show the unfiltered records: the filter is skipped for them.
    if (s.denoise && s.denoiseView === 'output') {
      const atrous = this.passes.atrous;
      atrous.write(denoiseSlopesParams(), ATROUS_SLOPES_SLOT);
      atrous.encode(encoder, { groups: groups.slopes, width: b.width, height: b.height, timer: r.timer, label: ATROUS_SLOPES_LABEL });
      atrousSchedule(feedback).forEach((it, i) => {
        const iteration = groups.atrous[feedback ? 1 : 0]![i]!;
        if (iteration.weights) {
          atrous.write(denoiseWeightsParams(i, it), atrousWeightsSlot(i));
          atrous.encode(encoder, { groups: iteration.weights, width: b.width, height: b.height, timer: r.timer, label: atrousWeightsLabel(i) });
        }
        atrous.write(denoiseAtrousParams(i, it), i);
        atrous.encode(encoder, { groups: iteration.filter, width: b.width, height: b.height, timer: r.timer, label: atrousLabel(i) });
      });
    } else {
      const fullHistory = unlimited ? 256 : (s.historyCap as number);
      this.passes.output.write(denoiseOutputParams(s.denoiseView, fullHistory, r.sceneSize));
      this.passes.output.encode(encoder, { groups: groups.output, width: b.width, height: b.height, timer: r.timer });
    }

    this.sampleIndex = (this.sampleIndex + f.samples) >>> 0;
    this.previousCamera = r.camera;
    this.historyValid = true;
  }

  /**
   * Gives up the frame begun: the surface records' ping-pong goes back, so the next frame reprojects
   * against the last finished one. The temporal pass, the filter and the history buffers (the ReSTIR
   * reservoirs included: finishFrame copies a frame's to them) were not touched by the bands; the scratch (the output of the last frame) was, so present the next frame,
   * not this one's.
   */
  private abandonFrame(f: OpenFrame): void {
    if (this.open !== f) return;
    this.open = undefined;
    this.parity ^= 1;
  }

  /**
   * One frame's path tracing alone (settings.integrator), with the random streams of frame
   * `sampleIndex`: no filter runs and the history is kept, but the current G-buffer and the frame
   * scratch (where the last frame's output was) are overwritten. ReSTIR does not run (its final
   * reservoirs borrow the moments, which here belong to the history): one light sample per bounce.
   * For timing the integrators (bench) and comparing them (readTrace); returns which one traced.
   */
  encodeTraceOnly(encoder: GPUCommandEncoder, r: FrameContext, samples: number, sampleIndex: number, breakdown = false): Integrator {
    return this.encodeTrace(encoder, r, samples, this.ensureBuffers(r.view, r.settings.restir), sampleIndex, { breakdown });
  }

  /** The raw output of the last encodeTraceOnly, once it is submitted (encodeFrame reuses the radiance words for its output). */
  async readTrace(): Promise<FrameTrace> {
    const b = this.buffers;
    if (!b) throw new Error('RealTimeRecipe: no frame traced yet');
    const [scratch, gbuffer, records] = await Promise.all([readBuffer(this.device, b.scratch), readBuffer(this.device, b.surfaces[this.parity]!), readBuffer(this.device, b.frameRecords)]);
    const pixels = b.width * b.height;
    const words = new Uint32Array(scratch), surface = new DataView(gbuffer), frame = new Uint32Array(records);
    const radiance = new Float32Array(pixels * 4), guide = new Float32Array(pixels * 4), albedo = new Float32Array(pixels * 3), emission = new Float32Array(pixels * 3);
    const surfaceBytes = structSize('SurfaceTexel');
    for (let i = 0; i < pixels; i++) {
      radiance.set([...unpackRgb9e5(words[4 * i]!), 1], 4 * i);
      const depth = surface.getFloat32(i * surfaceBytes, true);
      guide.set([...unpackOctahedral(surface.getUint32(i * surfaceBytes + 4, true)), depth], 4 * i);
      albedo.set(unpackRgb9e5(frame[2 * i]!), 3 * i);
      emission.set(unpackRgb9e5(frame[2 * i + 1]!), 3 * i);
    }
    return { width: b.width, height: b.height, radiance, gbuffer, guide, albedo, emission, integrator: this.lastIntegrator };
  }

  /** Whether a frame of this request runs ReSTIR: asked for, compiled for its scene, and traced by the megakernel in RGB with bounces. */
  private usesRestir(r: FrameContext, b: Buffers): boolean {
    const s = r.settings;
    // The wavefront's shade kernel and spectral paths keep one light sample per bounce.
    return b.reservoirs !== undefined && this.restir !== undefined && this.restirReady.has(featureKey(r.scene.features, false)) && !this.tracesWavefront(r.scene, s) && !s.spectral && s.maxBounces > 0;
  }

  /**
   * The ReSTIR passes' buffers in the frame begun. The frame's final reservoirs are written to the
   * moments the temporal pass writes at the end of the frame (8 bytes a pixel too; until then they
   * hold nothing the frame needs), so that a frame given up leaves the history's reservoirs alone.
   */
  private restirTarget(b: Buffers, r: FrameContext): RestirTarget {
    if (!b.reservoirs) throw new Error('RealTimeRecipe: ReSTIR without its reservoirs');
    return { scratch: b.scratch, surface: b.surfaces[this.parity]!, previousSurface: b.surfaces[1 - this.parity]!, reservoirs: b.moments[this.parity]!, previousReservoirs: b.reservoirs, rayCounters: r.targets.rayCounters };
  }

  private encodeTrace(encoder: GPUCommandEncoder, r: FrameContext, samples: number, b: Buffers, sampleIndex: number, o: TraceOptions): Integrator {
    const s = r.settings;
    const previousCamera = this.previousCamera ?? r.camera;
    const image = wholeImage(b);
    const dispatch = pathDispatch(r, 'real-time', o.tile ?? image, sampleIndex, samples);
    const restir = o.restir ? this.restirTarget(b, r) : undefined;
    // The path kernel always binds the reservoirs' buffer (and reads it only with ReSTIR).
    const target: FrameTarget = { scratch: b.scratch, surface: b.surfaces[this.parity]!, frameRecords: b.frameRecords, rayCounters: r.targets.rayCounters, restir: restir !== undefined };
    if (restir) {
      // The whole image's G-buffer and reservoirs before the first band's paths (encodeBand).
      if (o.prelude) {
        const whole = { ...dispatch, tile: image };
        this.frame.encode(encoder, { scene: r.scene, view: r.view, previousCamera, target, dispatch: whole, timer: r.timer, only: 'gbuffer' });
        this.restir!.encode(encoder, { scene: r.scene, view: r.view, previousCamera, target: restir, dispatch: { trace: whole, candidates: s.restirCandidates, useHistory: this.restirHistoryValid }, timer: r.timer });
      }
      this.frame.encode(encoder, { scene: r.scene, view: r.view, previousCamera, target, dispatch, timer: r.timer, only: 'paths' });
      this.lastIntegrator = 'megakernel';
      return this.lastIntegrator;
    }
    const wavefront = this.tracesWavefront(r.scene, s) ? this.wavefront : undefined;
    // The pixel-centre G-buffer is the frame kernel's own pass for both integrators.
    const traced = { scene: r.scene, view: r.view, previousCamera, target, dispatch, timer: r.timer };
    this.frame.encode(encoder, wavefront ? { ...traced, only: 'gbuffer' } : traced);
    if (wavefront) wavefront.encode(encoder, { ...traced, breakdown: o.breakdown ?? false });
    this.lastIntegrator = wavefront ? 'wavefront' : 'megakernel';
    return this.lastIntegrator;
  }

  destroy(): void {
    this.destroyBuffers();
    this.frame.destroy();
    this.restir?.destroy();
    this.wavefront?.destroy();
    for (const p of Object.values(this.passes)) p.destroy();
  }

  private ensureBuffers(view: ViewUniform, restir: boolean): Buffers {
    const { width, height } = view;
    if (this.buffers && this.buffers.width === width && this.buffers.height === height && (this.buffers.reservoirs !== undefined) === restir) return this.buffers;
    this.destroyBuffers();
    this.resetHistory();
    const pixels = width * height;
    const limits = this.device.limits;
    const largest = pixels * SCRATCH_BYTES;
    if (largest > limits.maxStorageBufferBindingSize || largest > limits.maxBufferSize) {
      throw new LanternError(`image ${width}×${height} is too large for the real-time denoiser on this GPU (its output needs ${(largest / 2 ** 20).toFixed(0)} MiB in one buffer)`);
    }
    const make = (label: string, size: number) => this.device.createBuffer({ label, size: pixels * size, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC });
    const surfaceBytes = structSize('SurfaceTexel'), momentBytes = structSize('MomentsTexel');
    // The à-trous dispatches borrow three words a pixel of the previous surface records (passes/denoise-atrous).
    if (surfaceBytes < ATROUS_SCRATCH_BYTES) throw new Error(`a surface record (${surfaceBytes} B) cannot lend the à-trous filter its ${ATROUS_SCRATCH_BYTES} bytes`);
    const scratch = make('frame scratch and output', SCRATCH_BYTES);
    const surfaces = [make('surface records 0', surfaceBytes), make('surface records 1', surfaceBytes)] as const;
    const frameRecords = make('frame records', structSize('FrameTexel'));
    const moments = [make('moments 0', momentBytes), make('moments 1', momentBytes)] as const;
    const history = make('colour history', PAIR_BYTES);
    const reservoirBytes = structSize('ReservoirTexel', 'restir/reservoir');
    // The frame's reservoirs are lent the current moments (restirTarget): they must fit.
    if (reservoirBytes > momentBytes) throw new Error(`a ReSTIR reservoir (${reservoirBytes} B) does not fit in a moments texel (${momentBytes} B)`);
    const reservoirs = restir ? this.device.createBuffer({ label: 'ReSTIR reservoirs', size: pixels * reservoirBytes, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC | GPUBufferUsage.COPY_DST }) : undefined;
    const { temporal, atrous, output } = this.passes;
    const groups = [0, 1].map((p): ParityGroups => {
      const surface = surfaces[p]!, previousMoments = moments[1 - p]!;
      // The à-trous dispatches keep their depth slopes and weight sums in the previous surface
      // records: the temporal pass has read them, and the next frame's G-buffer overwrites them.
      const previousSurface = surfaces[1 - p]!;
      return {
        temporal: temporal.bindGroups(view, { frame_scratch: scratch, surface_records: surface, previous_surface_records: previousSurface, history, previous_moments: previousMoments, moments: moments[p]! }),
        atrous: [false, true].map((feedback) =>
          atrousSchedule(feedback).map((it, i) => {
            const inScratch = it.source.array === 'a';
            const other = it.b === 'history' ? history : previousMoments;
            const resources = { surface_records: surface, frame_records: frameRecords, source_words: inScratch ? scratch : other, other_words: inScratch ? other : scratch, filter_scratch: previousSurface };
            const filter = atrous.bindGroups(view, resources, i);
            return i < EXACT_WEIGHT_ITERATIONS ? { weights: atrous.bindGroups(view, resources, atrousWeightsSlot(i)), filter } : { filter };
          }),
        ),
        slopes: atrous.bindGroups(view, { surface_records: surface, frame_records: frameRecords, source_words: scratch, other_words: history, filter_scratch: previousSurface }, ATROUS_SLOPES_SLOT),
        output: output.bindGroups(view, { surface_records: surface, frame_records: frameRecords, moments: moments[p]!, frame_scratch: scratch, history }),
      };
    });
    this.buffers = { width, height, scratch, surfaces, frameRecords, moments, history, ...(reservoirs ? { reservoirs } : {}), groups };
    return this.buffers;
  }

  private destroyBuffers(): void {
    const b = this.buffers;
    if (!b) return;
    for (const buffer of [b.scratch, ...b.surfaces, b.frameRecords, ...b.moments, b.history, ...(b.reservoirs ? [b.reservoirs] : [])]) buffer.destroy();
    this.buffers = undefined;
  }
}

/** rgb9e5 (shaders/denoise/gbuffer.wgsl pack_rgb9e5) to three floats. */
export function unpackRgb9e5(p: number): [number, number, number] {
  const scale = 2 ** ((p >>> 27) - 24);
  return [(p & 511) * scale, ((p >>> 9) & 511) * scale, ((p >>> 18) & 511) * scale];
}

/** An octahedral normal of two snorm16 (shaders/denoise/gbuffer.wgsl pack_normal) to a unit vector. */
export function unpackOctahedral(p: number): [number, number, number] {
  const snorm = (v: number) => Math.max(((v << 16) >> 16) / 32767, -1);
  let x = snorm(p & 0xffff), y = snorm(p >>> 16);
  const z = 1 - Math.abs(x) - Math.abs(y);
  const t = Math.max(-z, 0);
  x += x >= 0 ? -t : t;
  y += y >= 0 ? -t : t;
  const l = Math.hypot(x, y, z);
  return [x / l, y / l, z / l];
}

function featureKey(features: SceneFeatures, spectral: boolean): string {
  return `${JSON.stringify(Object.entries(features).sort(([a], [b]) => a.localeCompare(b)))}${spectral ? ' spectral' : ''}`;
}

/** Whether two cameras see the same image: pose, field of view and lens (a refocus is a change: the history is clamped, not trusted). */
function sameCamera(a: Camera, b: Camera): boolean {
  const aperture = (c: Camera) => c.lens?.apertureRadius ?? 0;
  const sameLens = aperture(a) === aperture(b) && (aperture(a) === 0 || a.lens?.focusDistance === b.lens?.focusDistance);
  return a === b || (a.vfovDegrees === b.vfovDegrees && sameLens && [0, 1, 2].every((i) => a.position[i] === b.position[i] && a.forward[i] === b.forward[i] && a.up[i] === b.up[i]));
}
