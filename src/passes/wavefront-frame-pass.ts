/**
 * The real-time frame's path tracer as a wavefront (shaders/wavefront/frame.wgsl): the estimator of
 * PathTraceFramePass (same random streams, same radiance, albedo and emission; the G-buffer pass is
 * PathTraceFramePass's own, run before: RealTimeRecipe.encodeTrace) run as generate →
 * per bounce (queue args → extend → shade → shadow args → light and torch shadow rays) → finish, with
 * the queues compacted by atomics and their sizes driving indirect dispatches (generate traces the
 * camera rays itself, in pixel tiles, so extension starts at the second bounce). All of a frame's
 * dispatches are one compute pass ('path trace (wavefront)'), so one timestamp pair times the whole
 * path tracing, as 'frame G-buffer' + 'frame emission' + 'path trace (frame)' time the megakernel's.
 */
import { pixelGroups, spectralConstants } from '../gpu/kernel-variants.ts';
import { LanternError } from '../errors.ts';
import { ComputeKernel, PLAIN_SCENE, SceneKernels, TRACING_FEATURES, type NamedResource } from '../gpu/kernel.ts';
import type { SceneFeatures } from '../gpu/pack/scene-pack.ts';
import type { SceneResources } from '../gpu/scene-resources.ts';
import { compileSpecialised, type SceneSpecialisation } from '../gpu/specialisation.ts';
import { cameraUniform, type ViewUniform } from '../gpu/view.ts';
import { reflectModule } from '../gpu/wgsl/reflect.ts';
import type { Camera } from '../scene/types.ts';
import type { FrameTarget } from './path-trace-frame-pass.ts';
import { cached, PATH_TRACE_MODULE, pathTraceParams, type PathTraceDispatch } from './path-trace-pass.ts';
import type { Pass, PassFrame } from './pass.ts';
import { UniformParams, type UniformValues } from './uniform-params.ts';

const MODULE = 'wavefront/frame';
/** Bytes of the queue counters before the items (Queues.counters in shaders/wavefront/paths.wgsl). */
const QUEUE_HEADER_BYTES = 32;
/** Byte offsets of the indirect arguments (ARGS_* of frame.wgsl): extension queue, light shadows, torch shadows. */
const ARGS_OFFSET = { extend: 0, light: 12, torch: 24 } as const;

const SCENE_ENTRIES = ['wavefront_generate', 'wavefront_extend', 'wavefront_shade', 'wavefront_shadow_light', 'wavefront_shadow_torch', 'wavefront_finish'] as const;
type SceneEntry = (typeof SCENE_ENTRIES)[number];
const ARGS_ENTRIES = ['wavefront_queue_args', 'wavefront_shadow_args'] as const;
type ArgsEntry = (typeof ARGS_ENTRIES)[number];

/** What the wavefront keeps per pixel beyond the frame's own outputs: the path fields and the two extension queues' slots. */
export function wavefrontBytesPerPixel(): number {
  const fields = reflectModule('wavefront/paths').defs.structs['PathSlotFields'];
  if (!fields) throw new Error('wavefront/paths has no struct PathSlotFields');
  return fields.size + 2 * 4;
}

interface StateBuffers {
  readonly pixels: number;
  readonly paths: GPUBuffer;
  readonly queues: GPUBuffer;
  readonly args: GPUBuffer;
}

/** What the wavefront is given for a frame: the whole image (its path slots are the pixels). */
export interface WavefrontFrame extends PassFrame {
  readonly scene: SceneResources;
  readonly view: ViewUniform;
  readonly previousCamera: Camera;
  readonly target: FrameTarget;
  readonly dispatch: PathTraceDispatch;
  /** With a timer, time each stage as a pass of its own (encode's comment). */
  readonly breakdown?: boolean;
}

export class WavefrontFramePass implements Pass<WavefrontFrame> {
  private spectral?: Record<SceneEntry, SceneKernels>;
  private state?: StateBuffers;
  /** One uniform per sample index of a frame (WavefrontSample), written once. */
  private readonly samples: UniformParams<UniformValues>[] = [];
  /** Group 2 per kernel, per target (the G-buffer ping-pongs) and sample; dropped when the state buffers are made again. */
  private targetGroups = new WeakMap<ComputeKernel, WeakMap<GPUBuffer, Map<number, GPUBindGroup>>>();
  private readonly sceneGroups = new WeakMap<ComputeKernel, WeakMap<SceneResources, GPUBindGroup>>();
  private readonly viewGroups = new WeakMap<ComputeKernel, WeakMap<ViewUniform, GPUBindGroup>>();
  /** Kernels specialised to one uploaded scene (gpu/specialisation.ts), used instead of the generic variants while set (RGB only). */
  private active?: { readonly scene: SceneResources; readonly kernels: Readonly<Record<SceneEntry, ComputeKernel>> };

  private constructor(
    private readonly device: GPUDevice,
    private readonly rgb: Record<SceneEntry, SceneKernels>,
    private readonly argsKernels: Record<ArgsEntry, ComputeKernel>,
    private readonly params: UniformParams<UniformValues>,
    private readonly frame: UniformParams<UniformValues>,
  ) {}

  /** `first`: the features of the scene to be rendered, where known: its variants are compiled instead of a plain scene's. */
  static async create(device: GPUDevice, first?: SceneFeatures): Promise<WavefrontFramePass> {
    const rgb = await sceneKernelSet(device, {}, first);
    const args = await Promise.all(ARGS_ENTRIES.map((entryPoint) => ComputeKernel.create(device, { module: MODULE, entryPoint })));
    const argsKernels = Object.fromEntries(ARGS_ENTRIES.map((e, i) => [e, args[i]!])) as Record<ArgsEntry, ComputeKernel>;
    return new WavefrontFramePass(device, rgb, argsKernels, new UniformParams(device, PATH_TRACE_MODULE), new UniformParams(device, 'passes/path-trace-frame', 'frame'));
  }

  /** Compiles every kernel's variant for a scene with these features, in RGB or spectral mode. */
  async prepare(features: SceneFeatures, spectral = false): Promise<void> {
    const set = spectral ? (this.spectral ??= kernelSet(this.device, spectralConstants(true))) : this.rgb;
    await Promise.all(SCENE_ENTRIES.map((e) => set[e].prepare(features)));
  }

  /** Compiles every scene kernel specialised to a frozen scene, asynchronously; they are not used until useSpecialised. */
  async compileSpecialised(s: SceneSpecialisation): Promise<Record<SceneEntry, ComputeKernel>> {
    const compiled = await Promise.all(SCENE_ENTRIES.map((entryPoint) => compileSpecialised(this.device, { module: MODULE, entryPoint }, s)));
    return Object.fromEntries(SCENE_ENTRIES.map((e, i) => [e, compiled[i]!.kernel])) as Record<SceneEntry, ComputeKernel>;
  }

  /** Frames over `scene` use these kernels from now on; undefined goes back to the generic variants. */
  useSpecialised(active?: { readonly scene: SceneResources; readonly kernels: Readonly<Record<SceneEntry, ComputeKernel>> }): void {
    this.active = active;
  }

  /** Whether frames over `scene` run specialised kernels. */
  isSpecialised(scene: SceneResources): boolean {
    return this.active?.scene === scene;
  }

  /**
   * Writes the parameters now (queue.writeBuffer): submit before encoding again. With a timer, the
   * whole path tracing is one timed pass, 'path trace (wavefront)'; with `breakdown` too, each stage
   * is a timed pass of its own ('wavefront generate', 'wavefront extend 0', 'wavefront shade 0',
   * 'wavefront shadows 0', …, 'wavefront finish'; a sample after the first adds ' s<n>'), whose sum
   * is a little more than the single pass (a pass boundary is a full barrier).
   */
  encode(encoder: GPUCommandEncoder, { scene, view, previousCamera, target, dispatch: d, timer, breakdown = false }: WavefrontFrame): void {
    if (d.tile.x !== 0 || d.tile.y !== 0 || d.tile.width !== view.width || d.tile.height !== view.height) {
      throw new Error('WavefrontFramePass traces the whole image: its path slots are the pixels');
    }
    this.params.write(pathTraceParams(d));
    this.frame.write({ previous_camera: cameraUniform(previousCamera, view.width / view.height) });
    const state = this.ensureState(view.width * view.height);
    while (this.samples.length < d.samples) {
      const u = new UniformParams(this.device, MODULE, 'wavefront');
      u.write({ sample: this.samples.length });
      this.samples.push(u);
    }
    const set = d.spectral ? this.spectral : this.rgb;
    if (!set) throw new Error('WavefrontFramePass: prepare(features, true) before a spectral frame');
    // Specialised kernels are compiled in RGB: spectral frames use the generic spectral variants.
    const active = !d.spectral && this.active?.scene === scene ? this.active.kernels : undefined;
    const kernel = (e: SceneEntry) => active?.[e] ?? set[e].get(scene.features);
    const groups = (k: ComputeKernel, sample: number): Record<number, GPUBindGroup> => ({
      0: cached(this.sceneGroups, k, scene, () => k.bindGroup(0, scene.bindings)),
      1: cached(this.viewGroups, k, view, () => k.bindGroup(1, { view: view.buffer })),
      2: this.targetGroup(k, target, sample, state),
    });
    const argsGroups = (k: ComputeKernel): Record<number, GPUBindGroup> => ({ 2: this.targetGroup(k, target, 0, state) });

    // The counters start at zero (parity 0: generate pushes onto half 1, which queue_args then makes current).
    encoder.clearBuffer(state.queues, 0, QUEUE_HEADER_BYTES);
    const begin = (label: string) => encoder.beginComputePass({ label, ...(timer ? { timestampWrites: timer.timestampWrites(label) } : {}) });
    let pass = begin(breakdown && timer ? 'wavefront generate' : 'path trace (wavefront)');
    // Ends the pass and starts the next stage's, when each stage is timed on its own.
    const stage = (label: string, s: number) => {
      if (!breakdown || !timer) return;
      pass.end();
      pass = begin(s > 0 ? `${label} s${s}` : label);
    };
    const [gx, gy] = pixelGroups(view.width, view.height);
    const [generate, extend, shade, shadowLight, shadowTorch, finish] = SCENE_ENTRIES.map(kernel) as [ComputeKernel, ComputeKernel, ComputeKernel, ComputeKernel, ComputeKernel, ComputeKernel];
    const { wavefront_queue_args: queueArgs, wavefront_shadow_args: shadowArgs } = this.argsKernels;
    for (let s = 0; s < d.samples; s++) {
      if (s > 0) stage('wavefront generate', s);
      generate.dispatch(pass, groups(generate, s), gx, gy);
      // Bounce b extends the paths with b scattering events so far; every path ends by bounce maxBounces.
      for (let b = 0; b <= d.maxBounces; b++) {
        stage(`wavefront extend ${b}`, s);
        queueArgs.dispatch(pass, argsGroups(queueArgs), 1);
        // Generate traced the camera rays.
        if (b > 0) extend.dispatchIndirect(pass, groups(extend, 0), state.args, ARGS_OFFSET.extend);
        stage(`wavefront shade ${b}`, s);
        // Shade resumes the sample's random stream: it reads which sample this is.
        shade.dispatchIndirect(pass, groups(shade, s), state.args, ARGS_OFFSET.extend);
        stage(`wavefront shadows ${b}`, s);
        shadowArgs.dispatch(pass, argsGroups(shadowArgs), 1);
        shadowLight.dispatchIndirect(pass, groups(shadowLight, 0), state.args, ARGS_OFFSET.light);
        // Without a torch its queue stays empty.
        if (d.torch) shadowTorch.dispatchIndirect(pass, groups(shadowTorch, 0), state.args, ARGS_OFFSET.torch);
      }
      stage('wavefront finish', s);
      finish.dispatch(pass, groups(finish, s), gx, gy);
    }
    pass.end();
  }

  /** Bytes the wavefront's own buffers hold now (0 before the first frame). */
  get allocatedBytes(): number {
    const s = this.state;
    return s ? s.paths.size + s.queues.size + s.args.size : 0;
  }

  destroy(): void {
    this.destroyState();
    this.params.destroy();
    this.frame.destroy();
    for (const u of this.samples) u.destroy();
  }

  private targetGroup(k: ComputeKernel, target: FrameTarget, sample: number, state: StateBuffers): GPUBindGroup {
    let perKernel = this.targetGroups.get(k);
    if (!perKernel) this.targetGroups.set(k, (perKernel = new WeakMap()));
    let perTarget = perKernel.get(target.surface);
    if (!perTarget) perKernel.set(target.surface, (perTarget = new Map()));
    let group = perTarget.get(sample);
    if (!group) {
      const resources: Record<string, NamedResource> = {
        params: this.params.buffer, frame: this.frame.buffer, frame_scratch: target.scratch, surface_records: target.surface, frame_records: target.frameRecords,
        ray_counters: target.rayCounters, paths: state.paths, queues: state.queues, wavefront: this.samples[sample]!.buffer, indirect_args: state.args,
      };
      perTarget.set(sample, (group = k.bindGroup(2, resources)));
    }
    return group;
  }

  private ensureState(pixels: number): StateBuffers {
    if (this.state?.pixels === pixels) return this.state;
    this.destroyState();
    const limits = this.device.limits;
    const pathBytes = pixels * (wavefrontBytesPerPixel() - 8);
    const queueBytes = QUEUE_HEADER_BYTES + pixels * 8;
    const largest = Math.max(pathBytes, queueBytes);
    if (largest > limits.maxStorageBufferBindingSize || largest > limits.maxBufferSize) {
      throw new LanternError(`the wavefront path tracer's state for ${pixels} pixels needs ${(largest / 2 ** 20).toFixed(0)} MiB in one buffer, more than this GPU binds`, "Use --integrator megakernel, or a smaller image");
    }
    const storage = (label: string, size: number, extra = 0) => this.device.createBuffer({ label, size, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST | extra });
    this.state = {
      pixels,
      paths: storage('wavefront paths', pathBytes),
      queues: storage('wavefront queues', queueBytes),
      args: storage('wavefront indirect arguments', 36, GPUBufferUsage.INDIRECT),
    };
    this.targetGroups = new WeakMap();
    return this.state;
  }

  private destroyState(): void {
    if (!this.state) return;
    this.state.paths.destroy();
    this.state.queues.destroy();
    this.state.args.destroy();
    this.state = undefined;
  }
}

function kernelSet(device: GPUDevice, extra: Record<string, number>): Record<SceneEntry, SceneKernels> {
  const constants = { ...extra };
  return Object.fromEntries(SCENE_ENTRIES.map((entryPoint) => [entryPoint, new SceneKernels(device, { module: MODULE, entryPoint }, TRACING_FEATURES, constants)])) as Record<SceneEntry, SceneKernels>;
}

/** The RGB set with the variants of `first` (default: a plain scene) compiled, so that WGSL errors surface at creation. */
async function sceneKernelSet(device: GPUDevice, extra: Record<string, number>, first: SceneFeatures = PLAIN_SCENE): Promise<Record<SceneEntry, SceneKernels>> {
  const set = kernelSet(device, extra);
  await Promise.all(SCENE_ENTRIES.map((e) => set[e].prepare(first)));
  return set;
}
