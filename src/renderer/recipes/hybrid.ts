/**
 * The hybrid frame recipe (Renderer.renderFrame with settings.recipe = 'hybrid'):
 *
 *   raster (visibility + depth, Halton (2, 3) jitter) → resolve (guide, motion) → shade (emission,
 *   direct light: light samples with shadow rays + a BSDF ray, MIS; diffuse weight) → reflect → GI at gi_scale (+ à-trous ×k on
 *   the GI target) → compose (joint bilateral upsampling of GI) → TAA → the output the tone mapper reads
 *
 * The raster pass decides what each pixel sees; every other pass reconstructs the exact ray hit
 * from it (hybrid/visibility.wgsl), so surfaces, materials, lights, textures and alpha tests are the
 * path tracer's own. The Hybrid owns the per-pixel buffers, the GI target at its scale, the TAA
 * history (ping-ponged) and the previous camera (motion vectors). docs/hybrid.md says what the
 * recipe gets right and what it cannot see.
 */
import { LanternError } from '../../errors.ts';
import type { SceneFeatures } from '../../gpu/pack/scene-pack.ts';
import type { GpuTimer } from '../../gpu/timestamps.ts';
import { cameraUniform, ViewUniform } from '../../gpu/view.ts';
import {
  ATROUS_SCRATCH_BYTES, ATROUS_SLOPES_SLOT, EXACT_WEIGHT_ITERATIONS, PAIR_BYTES, PING_PONG, atrousWeightsSlot, createAtrousPass, denoiseAtrousParams, denoiseSlopesParams, denoiseWeightsParams, structSize,
} from '../../passes/denoise-passes.ts';
import { HybridRasterPass, DEPTH_FORMAT, VISIBILITY_FORMAT, type RasterDraw } from '../../passes/hybrid-raster-pass.ts';
import { ImagePass } from '../../passes/image-pass.ts';
import { HybridTracePass, type HybridTraced } from '../../passes/hybrid-trace-pass.ts';
import { pathTraceParams } from '../../passes/path-trace-pass.ts';
import { UniformParams, type UniformValues } from '../../passes/uniform-params.ts';
import type { Camera } from '../../scene/types.ts';
import type { PreparedScene } from '../prepare.ts';
import { pathDispatch, type FrameContext } from '../frame.ts';
import type { FrameRecipe, RecipeFrame } from './frame-recipe.ts';

const MODULE = 'passes/hybrid';
const VEC4_BYTES = 16;
/** Frames of the jitter sequence before it repeats. */
const JITTER_PERIOD = 16;
/** TAA's smallest blend of the current frame: the history is never more than 1 / this frames long. */
const TAA_MIN_BLEND = 0.1;
/** The near plane as a fraction of the scene's size. */
const NEAR_FRACTION = 1e-5;
/** À-trous iterations on the GI target (steps 1, 2, 4: the GI texels are already a block apart). */
const GI_FILTER_ITERATIONS = 3;
/** The GI filter's timer labels: its slopes, its weight sums before iteration i, iteration i (0-based). */
const giFilterLabel = (iteration: number | 'slopes'): string => (iteration === 'slopes' ? 'a-trous GI slopes' : `a-trous GI ${iteration + 1}`);

/** The radical inverse of i in `base` (Halton's sequence), in [0, 1). */
export function radicalInverse(i: number, base: number): number {
  let f = 1, r = 0;
  for (let n = i; n > 0; n = Math.floor(n / base)) {
    f /= base;
    r += f * (n % base);
  }
  return r;
}

/** The subpixel offset of frame `frame` (pixels, in [−0.5, 0.5)²): Halton (2, 3), from its first point on. */
export function haltonJitter(frame: number): [number, number] {
  const i = (frame % JITTER_PERIOD) + 1;
  return [radicalInverse(i, 2) - 0.5, radicalInverse(i, 3) - 0.5];
}

/** Pixels per GI texel along each axis for a buffer scale (0.5 → blocks of 2 × 2). */
export const giBlock = (scale: number): number => Math.max(1, Math.round(1 / scale));

/** The GI target's size for an image and a buffer scale. */
export function giSize(width: number, height: number, scale: number): [number, number] {
  const block = giBlock(scale);
  return [Math.ceil(width / block), Math.ceil(height / block)];
}

const drawsOf = new WeakMap<PreparedScene, RasterDraw[]>();

/** The draws of the raster pass: the static world's primitives, then each moving instance's mesh (made once per prepared scene). */
export function rasterDraws(prepared: PreparedScene): RasterDraw[] {
  let known = drawsOf.get(prepared);
  if (!known) drawsOf.set(prepared, (known = makeRasterDraws(prepared)));
  return known;
}

function makeRasterDraws(prepared: PreparedScene): RasterDraw[] {
  const draws: RasterDraw[] = [{ first: 0, count: prepared.bvh.triIndices.length, instance: 0 }];
  const levels = prepared.levels;
  if (!levels) return draws;
  levels.dynamic.forEach((sceneInstance, k) => {
    const mesh = prepared.scene.instances[sceneInstance]!.mesh;
    const part = prepared.packed.layout.meshes.get(mesh);
    if (part) draws.push({ first: part.leafBase, count: part.leafCount, instance: k + 1 });
  });
  return draws;
}

interface Buffers {
  readonly width: number;
  readonly height: number;
  readonly giWidth: number;
  readonly giHeight: number;
  readonly visibility: GPUTexture;
  readonly depth: GPUTexture;
  readonly visibilityView: GPUTextureView;
  readonly depthView: GPUTextureView;
  readonly guide: GPUBuffer;
  readonly motion: GPUBuffer;
  readonly lit: GPUBuffer;
  readonly diffuseWeight: GPUBuffer;
  /** The GI target and the à-trous filter's other half of it (illumination pairs, passes/hybrid). */
  readonly gi: GPUBuffer;
  readonly giPairs: GPUBuffer;
  /** The surface records the GI texels were traced from (SurfaceTexel). */
  readonly giGuide: GPUBuffer;
  /** The à-trous filter's depth slopes and weight sums for the GI target. */
  readonly giFilterScratch: GPUBuffer;
  /** The GI filter's bind groups, made as first used (giFilterGroups). */
  readonly giFilterGroups: Map<string, Record<number, GPUBindGroup>>;
  readonly composed: GPUBuffer;
  readonly histories: readonly [GPUBuffer, GPUBuffer];
  readonly output: GPUBuffer;
  readonly giView: ViewUniform;
  /** The renderer's ray counters the kernels' bind groups hold. */
  readonly rayCounters: GPUBuffer;
}

export class HybridRecipe implements FrameRecipe {
  private buffers?: Buffers;
  private previousCamera?: Camera;
  private frameIndex = 0;
  private parity = 0;
  private historyValid = false;

  private constructor(
    private readonly device: GPUDevice,
    private readonly raster: HybridRasterPass,
    private readonly traced: Readonly<Record<HybridTraced, HybridTracePass>>,
    private readonly compose: ImagePass<UniformValues>,
    private readonly taa: ImagePass<UniformValues>,
    private readonly atrous: ImagePass<UniformValues>,
    private readonly params: UniformParams<UniformValues>,
    private readonly hybridParams: UniformParams<UniformValues>,
  ) {}

  /** `first`: the features of the scene to be rendered, where known (its tracing variants compile instead of a plain scene's). */
  static async create(device: GPUDevice, first?: SceneFeatures): Promise<HybridRecipe> {
    const [raster, resolve, shade, reflect, gi, compose, taa, atrous] = await Promise.all([
      HybridRasterPass.create(device, first),
      HybridTracePass.create(device, 'resolve', first),
      HybridTracePass.create(device, 'shade', first),
      HybridTracePass.create(device, 'reflect', first),
      HybridTracePass.create(device, 'gi', first),
      ImagePass.create(device, 'passes/hybrid-compose', 'hybrid_compose', 'compose'),
      ImagePass.create(device, 'passes/hybrid-compose', 'hybrid_taa', 'taa'),
      createAtrousPass(device, 'a-trous (GI)'),
    ]);
    return new HybridRecipe(device, raster, { resolve, shade, reflect, gi }, compose, taa, atrous, new UniformParams(device, 'passes/path-trace'), new UniformParams(device, MODULE, 'hybrid'));
  }

  /** Compiles the variants a scene with these features needs (RGB always: spectral mode is the path tracers'). */
  async prepare(features: SceneFeatures): Promise<void> {
    await Promise.all([this.raster.prepare(features), ...Object.values(this.traced).map((k) => k.prepare(features))]);
  }

  /** The recipe's linear output of the last frame (vec4f per pixel), if a frame was rendered. */
  get output(): GPUBuffer | undefined {
    return this.buffers?.output;
  }

  /** Forgets the TAA history and the previous camera. */
  resetHistory(): void {
    this.historyValid = false;
    this.previousCamera = undefined;
  }

  /** The hybrid's output is always a lit image (its debug views are the debug recipe's). */
  showsRawValues(): boolean {
    return false;
  }

  /** Begins a frame: one sample per pixel, traced whole (no bands), recorded in the one band's encoder. */
  begin(frame: FrameContext): RecipeFrame {
    return { splittable: false, band: (encoder) => this.encodeFrame(encoder, frame), finish: () => {}, abandon: () => {} };
  }

  /** Records one hybrid frame into `encoder` (parameters are written now: submit before the next frame). */
  private encodeFrame(encoder: GPUCommandEncoder, r: FrameContext): void {
    const s = r.settings;
    const h = s.hybrid;
    const b = this.ensureBuffers(r.view, r.camera, h.giScale, r.targets.rayCounters);
    b.giView.update(r.camera, b.giWidth, b.giHeight);
    this.parity ^= 1;
    const jitter = haltonJitter(this.frameIndex);
    const previousCamera = this.previousCamera ?? r.camera;
    const aspect = r.view.width / r.view.height;
    this.raster.encode(encoder, { scene: r.scene, view: r.view, visibility: b.visibilityView, depth: b.depthView, draws: rasterDraws(r.prepared), jitter, near: Math.max(2 * r.sceneSize * NEAR_FRACTION, 1e-6), timer: r.timer });

    const tile = { x: 0, y: 0, width: b.width, height: b.height };
    this.params.write(pathTraceParams(pathDispatch(r, 'real-time', tile, this.frameIndex, 1)));
    this.hybridParams.write({
      previous_camera: cameraUniform(previousCamera, aspect),
      jitter,
      gi_size: [b.giWidth, b.giHeight],
      gi_scale: 1 / giBlock(h.giScale),
      frame_index: this.frameIndex,
      light_samples: h.lightSamples,
      gi_bounces: h.giBounces,
      gi_samples: h.giSamples,
      reflections: h.reflections ? 1 : 0,
      reflection_bounces: h.reflectionBounces,
    });
    // The kernels cache group 2 by `key`: made anew with the buffers, which are made anew when the counters change.
    const targets = {
      key: b.guide,
      resources: () => ({
        params: this.params.buffer, hybrid: this.hybridParams.buffer, ray_counters: r.targets.rayCounters, visibility: b.visibilityView,
        guide: b.guide, motion: b.motion, lit: b.lit, diffuse_weight: b.diffuseWeight, gi: b.gi, gi_guide: b.giGuide,
      }),
    };
    const traced = { scene: r.scene, view: r.view, targets, tile, timer: r.timer };
    this.traced.resolve.encode(encoder, traced);
    this.traced.shade.encode(encoder, traced);
    if (h.reflections && r.scene.features.generalMaterials && s.maxBounces > 0) this.traced.reflect.encode(encoder, traced);
    const useGi = s.maxBounces > 0 && h.giBounces > 0;
    if (useGi) {
      this.traced.gi.encode(encoder, { ...traced, tile: { x: 0, y: 0, width: b.giWidth, height: b.giHeight } });
      if (h.giFilter) this.encodeGiFilter(encoder, b, r.timer);
    }

    const composeValues = { gi_size: [b.giWidth, b.giHeight], gi_scale: 1 / giBlock(h.giScale), use_gi: useGi ? 1 : 0, min_blend: h.taa ? TAA_MIN_BLEND : 1, use_history: this.historyValid ? 1 : 0 };
    this.compose.write(composeValues);
    this.taa.write(composeValues);
    const previousHistory = b.histories[1 - this.parity]!, history = b.histories[this.parity]!;
    const imageResources = { guide: b.guide, lit: b.lit, diffuse_weight: b.diffuseWeight, gi: b.gi, gi_guide: b.giGuide, composed: b.composed, motion: b.motion, previous_history: previousHistory, history, output: b.output };
    this.compose.encode(encoder, { groups: this.compose.bindGroups(r.view, imageResources), width: b.width, height: b.height, timer: r.timer });
    this.taa.encode(encoder, { groups: this.taa.bindGroups(r.view, imageResources), width: b.width, height: b.height, timer: r.timer, label: 'TAA' });

    this.frameIndex = (this.frameIndex + 1) >>> 0;
    this.previousCamera = r.camera;
    this.historyValid = true;
  }

  destroy(): void {
    this.destroyBuffers();
    this.raster.destroy();
    for (const p of [...Object.values(this.traced), this.compose, this.taa, this.atrous, this.params, this.hybridParams]) p.destroy();
  }

  /**
   * The real-time chain's à-trous filter (passes/denoise-atrous) on the GI target, guided by the
   * surfaces the GI texels were traced from: the depth slopes, then GI_FILTER_ITERATIONS iterations
   * between the two GI buffers (the first EXACT_WEIGHT_ITERATIONS after their weight sums), as the
   * chain runs it; the result ends in `gi`.
   */
  private encodeGiFilter(encoder: GPUCommandEncoder, b: Buffers, timer?: GpuTimer): void {
    const filter = this.atrous;
    const run = (i: number, slot: number, label: string) => filter.encode(encoder, { groups: this.giFilterGroups(b, i, slot), width: b.giWidth, height: b.giHeight, timer, label });
    filter.write(denoiseSlopesParams(), ATROUS_SLOPES_SLOT);
    run(0, ATROUS_SLOPES_SLOT, giFilterLabel('slopes'));
    for (let i = 0; i < GI_FILTER_ITERATIONS; i++) {
      if (i < EXACT_WEIGHT_ITERATIONS) {
        filter.write(denoiseWeightsParams(i, PING_PONG, GI_FILTER_ITERATIONS), atrousWeightsSlot(i));
        run(i, atrousWeightsSlot(i), `${giFilterLabel(i)} weights`);
      }
      filter.write(denoiseAtrousParams(i, PING_PONG, GI_FILTER_ITERATIONS), i);
      run(i, i, giFilterLabel(i));
    }
    // An odd number of iterations ends in the other buffer: copy it back where compose reads.
    if (GI_FILTER_ITERATIONS % 2 === 1) encoder.copyBufferToBuffer(b.giPairs, 0, b.gi, 0, b.gi.size);
  }

  /** The GI filter's bind groups for iteration i's direction (the two GI buffers swap every iteration) and a parameter slot, made once per buffers. */
  private giFilterGroups(b: Buffers, i: number, slot: number): Record<number, GPUBindGroup> {
    const key = `${i % 2}/${slot}`;
    let groups = b.giFilterGroups.get(key);
    if (!groups) {
      const pairs = [b.gi, b.giPairs] as const;
      // frame_records is read by the chain's output mode alone, which the GI filter never runs: bound to the guide (both read-only).
      const resources = { surface_records: b.giGuide, frame_records: b.giGuide, source_words: pairs[i % 2]!, other_words: pairs[(i + 1) % 2]!, filter_scratch: b.giFilterScratch };
      b.giFilterGroups.set(key, (groups = this.atrous.bindGroups(b.giView, resources, slot)));
    }
    return groups;
  }

  private ensureBuffers(view: ViewUniform, camera: Camera, scale: number, rayCounters: GPUBuffer): Buffers {
    const { width, height } = view;
    const [giWidth, giHeight] = giSize(width, height, scale);
    const b0 = this.buffers;
    if (b0 && b0.width === width && b0.height === height && b0.giWidth === giWidth && b0.giHeight === giHeight && b0.rayCounters === rayCounters) return b0;
    this.destroyBuffers();
    this.resetHistory();
    const pixels = width * height, giTexels = giWidth * giHeight;
    const limits = this.device.limits;
    if (pixels * VEC4_BYTES > limits.maxStorageBufferBindingSize || width > limits.maxTextureDimension2D || height > limits.maxTextureDimension2D) {
      throw new LanternError(`image ${width}×${height} is too large for the hybrid recipe on this GPU`);
    }
    const make = (label: string, size: number) => this.device.createBuffer({ label, size, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC | GPUBufferUsage.COPY_DST });
    const texture = (label: string, format: GPUTextureFormat) => this.device.createTexture({ label, size: [width, height], format, usage: GPUTextureUsage.RENDER_ATTACHMENT | GPUTextureUsage.TEXTURE_BINDING });
    const visibility = texture('visibility', VISIBILITY_FORMAT);
    const depth = texture('depth', DEPTH_FORMAT);
    const giView = new ViewUniform(this.device);
    giView.update(camera, giWidth, giHeight);
    this.buffers = {
      width, height, giWidth, giHeight, visibility, depth, giView, rayCounters,
      visibilityView: visibility.createView(),
      depthView: depth.createView(),
      guide: make('hybrid guide', pixels * VEC4_BYTES),
      motion: make('hybrid motion', pixels * VEC4_BYTES),
      lit: make('hybrid lit', pixels * VEC4_BYTES),
      diffuseWeight: make('hybrid diffuse weight', pixels * VEC4_BYTES),
      gi: make('hybrid GI', giTexels * PAIR_BYTES),
      giPairs: make('hybrid GI (filter)', giTexels * PAIR_BYTES),
      giGuide: make('hybrid GI guide', giTexels * structSize('SurfaceTexel')),
      giFilterScratch: make('hybrid GI filter scratch', giTexels * ATROUS_SCRATCH_BYTES),
      giFilterGroups: new Map(),
      composed: make('hybrid composed', pixels * VEC4_BYTES),
      histories: [make('TAA history 0', pixels * VEC4_BYTES), make('TAA history 1', pixels * VEC4_BYTES)],
      output: make('hybrid output', pixels * VEC4_BYTES),
    };
    return this.buffers;
  }

  private destroyBuffers(): void {
    const b = this.buffers;
    if (!b) return;
    b.visibility.destroy();
    b.depth.destroy();
    b.giView.destroy();
    for (const buffer of [b.guide, b.motion, b.lit, b.diffuseWeight, b.gi, b.giPairs, b.giGuide, b.giFilterScratch, b.composed, ...b.histories, b.output]) buffer.destroy();
    this.buffers = undefined;
  }
}

/** Bytes per pixel the hybrid recipe holds at a GI scale (docs/hybrid.md's memory line). */
export function hybridBytesPerPixel(scale: number): number {
  const block = giBlock(scale);
  // guide, motion, lit, diffuse weight, composed, two histories, output; visibility (8) and depth (4);
  // per GI texel (a block): two illumination pairs, the surface record, the à-trous filter's scratch.
  return 8 * VEC4_BYTES + 8 + 4 + (2 * PAIR_BYTES + structSize('SurfaceTexel') + ATROUS_SCRATCH_BYTES) / (block * block);
}
