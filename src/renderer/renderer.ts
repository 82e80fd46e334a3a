/**
 * The Renderer: one object shared by the browser page, the CLI and the tests. It owns the GPU state
 * of a scene and an image and runs the frame recipe
 *
 *   path trace (adds samples to the float32 accumulation) → tone map (8-bit sRGB) → present | read back
 *
 * Facade: setScene, setCamera, updateSettings, resize, accumulate, present, read*. Every method that
 * changes the estimate (scene, camera, size, bounces, light sampling, seed) restarts accumulation.
 * With a debug view set (settings.debugView), present and readImage show it as settings.debugLayout
 * asks (renderer/debug-views.ts); enableDebugViews() compiles its pipelines.
 *
 * Real time (after enableRealTime): renderFrame(spp) runs the denoiser's frame recipe (renderer/
 * denoiser.ts) instead; present and readImage then show its output until the next accumulate().
 */
import { boundsDiagonal } from '../bvh/stats.ts';
import { LanternError } from '../errors.ts';
import type { GpuContext } from '../gpu/device.ts';
import { withErrorScope } from '../gpu/device.ts';
import { readBuffer, readTexture4x8 } from '../gpu/readback.ts';
import { SceneResources, writeTriangleAttributes } from '../gpu/scene-resources.ts';
import type { GpuTimer } from '../gpu/timestamps.ts';
import { PathTracePass, type Tile } from '../passes/path-trace-pass.ts';
import { PresentPass } from '../passes/present-pass.ts';
import { TonemapPass } from '../passes/tonemap-pass.ts';
import type { Camera, Scene } from '../scene/types.ts';
import { debugLegend, type DebugLegend } from './debug-legend.ts';
import { DebugViews } from './debug-views.ts';
import { Denoiser } from './denoiser.ts';
import { moveInstances, MOVED_BUFFERS, prepareScene, withPreparedEnvironment, type PreparedScene } from './prepare.ts';
import type { Environment } from '../scene/environment.ts';
import type { Mat4 } from '../math/mat4.ts';
import { DEFAULT_SETTINGS, effectiveTorch, ESTIMATE_SETTINGS, validateSettings, type RenderSettings } from './settings.ts';
import { ViewUniform } from '../gpu/view.ts';

/** Bytes per pixel of the accumulation buffer (one vec4f). */
const ACCUMULATION_BYTES_PER_PIXEL = 16;
/** An image side beyond this is refused even where the GPU would allow it. */
export const MAX_IMAGE_SIDE = 16384;

export interface RayCounts {
  readonly extension: number;
  readonly shadow: number;
}

export interface Accumulation {
  readonly width: number;
  readonly height: number;
  readonly samples: number;
  /** Mean radiance, 3 floats per pixel, row-major, top row first. */
  readonly radiance: Float32Array;
  /** Per-pixel sample variance of luminance (unbiased), 1 float per pixel. */
  readonly luminanceVariance: Float32Array;
}

/** Linear radiance of a real-time frame. */
export interface LinearImage {
  readonly width: number;
  readonly height: number;
  /** 3 floats per pixel, row-major, top row first. */
  readonly radiance: Float32Array;
}

interface ImageTargets {
  readonly width: number;
  readonly height: number;
  readonly accumulation: GPUBuffer;
  readonly rayCounters: GPUBuffer;
  readonly output: GPUTexture;
}

export class Renderer {
  private prepared?: PreparedScene;
  private resources?: SceneResources;
  private targets?: ImageTargets;
  private cameraValue?: Camera;
  private settingsValue: RenderSettings = DEFAULT_SETTINGS;
  private samples = 0;
  private epoch = 0;
  private denoiser?: Denoiser;
  /** Whether the spectral variants are compiled for each scene (enableSpectral). */
  private spectralEnabled = false;
  /** What present() and readImage() show: the progressive estimate or the last real-time frame. */
  private shown: 'accumulation' | 'frame' = 'accumulation';

  private constructor(
    readonly gpu: GpuContext,
    private readonly view: ViewUniform,
    private readonly pathTrace: PathTracePass,
    private readonly tonemap: TonemapPass,
    private presentPass?: PresentPass,
    private debugViews?: DebugViews,
  ) {}

  static async create(gpu: GpuContext): Promise<Renderer> {
    const { device } = gpu;
    const [pathTrace, tonemap] = await Promise.all([PathTracePass.create(device), TonemapPass.create(device)]);
    return new Renderer(gpu, new ViewUniform(device), pathTrace, tonemap);
  }

  get device(): GPUDevice {
    return this.gpu.device;
  }
  get sampleCount(): number {
    return this.samples;
  }
  get settings(): RenderSettings {
    return this.settingsValue;
  }
  get camera(): Camera | undefined {
    return this.cameraValue;
  }
  get width(): number {
    return this.targets?.width ?? 0;
  }
  get height(): number {
    return this.targets?.height ?? 0;
  }
  get scene(): PreparedScene | undefined {
    return this.prepared;
  }
  /** Bytes of GPU memory held for the scene. */
  get sceneBytes(): number {
    return this.resources?.byteSize ?? 0;
  }

  /** Uploads a scene (prepared here unless given prepared) and frees the previous one. Uses its camera. */
  async setScene(scene: Scene | PreparedScene): Promise<PreparedScene> {
    const prepared = 'packed' in scene ? scene : prepareScene(scene);
    await this.upload(prepared);
    this.setCamera(prepared.scene.camera);
    return prepared;
  }

  /**
   * Lights the scene with another environment (a sky, an HDR map, none) without preparing it again:
   * the environment, the light table and the scene info are packed anew and the scene's GPU resources
   * replaced. The camera is kept, with the exposure change the sky brings (scene/environment-override.ts).
   * Restarts accumulation.
   */
  async setEnvironment(environment: Environment): Promise<PreparedScene> {
    if (!this.prepared) throw new Error('Renderer: setScene() before setEnvironment()');
    const before = this.prepared.scene.camera.exposureStops ?? 0;
    const prepared = withPreparedEnvironment(this.prepared, environment);
    await this.upload(prepared);
    const shift = (prepared.scene.camera.exposureStops ?? 0) - before;
    if (this.cameraValue) this.setCamera({ ...this.cameraValue, exposureStops: (this.cameraValue.exposureStops ?? 0) + shift });
    this.resetAccumulation();
    return prepared;
  }

  /** Compiles what the scene needs, then uploads it and frees the previous one (a failure leaves the old scene). */
  private async upload(prepared: PreparedScene): Promise<void> {
    const features = prepared.packed.features;
    await Promise.all([
      this.pathTrace.prepare(features), this.denoiser?.prepare(features), this.debugViews?.prepare(features),
      ...(this.spectralEnabled ? [this.pathTrace.prepare(features, true), this.denoiser?.prepare(features, true)] : []),
    ]);
    const resources = await SceneResources.upload(this.device, prepared.packed, prepared.scene.name);
    this.resources?.destroy();
    this.resources = resources;
    this.prepared = prepared;
  }

  /**
   * Moves instances (new world-from-object transforms by instance id) without rebuilding the scene:
   * the BVH is refitted and the geometry buffers are rewritten in place (renderer/prepare.ts
   * moveInstances). Restarts accumulation.
   */
  updateInstances(moves: ReadonlyMap<number, Mat4>): PreparedScene {
    const resources = this.resources;
    if (!resources || !this.prepared) throw new Error('Renderer: setScene() before updateInstances()');
    const prepared = moveInstances(this.prepared, moves);
    for (const name of MOVED_BUFFERS) this.device.queue.writeBuffer(resources.buffers[name], 0, prepared.packed[name]);
    writeTriangleAttributes(this.device, resources.triangleAttributes, prepared.packed.triangleAttributes);
    this.prepared = prepared;
    this.resetAccumulation();
    return prepared;
  }

  setCamera(camera: Camera): void {
    this.cameraValue = camera;
    this.updateView();
  }

  /** Applies changed settings; those that change the estimate restart accumulation. */
  updateSettings(changes: Partial<RenderSettings>): void {
    const next = validateSettings({ ...this.settingsValue, ...changes });
    const restart = ESTIMATE_SETTINGS.some((k) => next[k] !== this.settingsValue[k]);
    this.settingsValue = next;
    if (restart) this.resetAccumulation();
  }

  /** Sets the image size, checked against the GPU's limits. */
  async resize(width: number, height: number): Promise<void> {
    checkImageSize(width, height, this.device.limits);
    if (this.targets && this.targets.width === width && this.targets.height === height) return;
    const device = this.device;
    const targets = await withErrorScope(device, `a ${width}×${height} image`, () => ({
      width,
      height,
      accumulation: device.createBuffer({
        label: 'accumulation',
        size: width * height * ACCUMULATION_BYTES_PER_PIXEL,
        usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC | GPUBufferUsage.COPY_DST,
      }),
      rayCounters: device.createBuffer({ label: 'ray counters', size: 16, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC | GPUBufferUsage.COPY_DST }),
      output: device.createTexture({
        label: 'tone-mapped image',
        size: [width, height],
        format: 'rgba8unorm',
        usage: GPUTextureUsage.STORAGE_BINDING | GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_SRC,
      }),
    }));
    this.destroyTargets();
    this.targets = targets;
    this.updateView();
  }

  /** Counts resetAccumulation() calls (the ray counters restart with each): callers tell fresh counts from running ones. */
  get accumulationEpoch(): number {
    return this.epoch;
  }

  /** Discards every accumulated sample and the ray counts (the next frame starts a new estimate). */
  resetAccumulation(): void {
    this.samples = 0;
    this.epoch++;
    if (!this.targets) return;
    const encoder = this.device.createCommandEncoder({ label: 'reset accumulation' });
    encoder.clearBuffer(this.targets.accumulation);
    encoder.clearBuffer(this.targets.rayCounters);
    this.device.queue.submit([encoder.finish()]);
  }

  /** The whole image as one tile. */
  fullImage(): Tile {
    return { x: 0, y: 0, width: this.width, height: this.height };
  }

  /**
   * Adds `samples` paths per pixel over `tiles` (default: the whole image), one submit per tile so
   * that no single submit runs long enough to trip a GPU watchdog. Returns without waiting. With a
   * timer, each tile's pass is timed and the timestamps are resolved with the last tile.
   */
  accumulate(samples: number, tiles: readonly Tile[] = [this.fullImage()], timer?: GpuTimer): void {
    const { resources, targets } = this.ready();
    if (!Number.isInteger(samples) || samples < 1) throw new LanternError(`samples per dispatch must be a positive whole number, not ${samples}`);
    const s = this.settingsValue;
    if (s.spectral && !this.spectralEnabled) throw new Error('Renderer: enableSpectral() before rendering with settings.spectral');
    const torch = effectiveTorch(this.prepared?.scene, s.torch);
    tiles.forEach((tile, i) => {
      const encoder = this.device.createCommandEncoder({ label: 'path trace' });
      const dispatch = { tile, sampleIndex: this.samples, samples, maxBounces: s.maxBounces, seed: s.seed, lightSampling: s.lightSampling, torch, spectral: s.spectral };
      this.pathTrace.encode(encoder, resources, this.view, targets, dispatch, timer);
      if (timer && i === tiles.length - 1) timer.resolve(encoder);
      this.device.queue.submit([encoder.finish()]);
    });
    this.samples += samples;
    this.shown = 'accumulation';
  }

  /**
   * Compiles the spectral variants of the path tracers (settings.spectral) for this and every later
   * scene. RGB rendering never compiles them; call this before rendering with `spectral` on.
   */
  async enableSpectral(): Promise<void> {
    this.spectralEnabled = true;
    if (!this.prepared) return;
    const features = this.prepared.packed.features;
    await Promise.all([this.pathTrace.prepare(features, true), this.denoiser?.prepare(features, true)]);
  }

  /** Compiles the real-time frame passes (path tracer with G-buffer, temporal, à-trous, output). */
  async enableRealTime(): Promise<void> {
    this.denoiser ??= await Denoiser.create(this.device);
    if (this.prepared) await Promise.all([this.denoiser.prepare(this.prepared.packed.features), this.spectralEnabled ? this.denoiser.prepare(this.prepared.packed.features, true) : undefined]);
  }

  /**
   * One real-time frame: `samples` paths per pixel, then temporal accumulation (settings.temporal)
   * and the spatial filter (settings.denoise), in one submit. The history survives setCamera (it is
   * reprojected) and setScene (changed pixels fail the G-buffer tests); resize or resetHistory()
   * drop it. With a timer, every pass is timed. present(), readImage() and readFrame() show the result.
   */
  renderFrame(samples: number, timer?: GpuTimer): void {
    const { resources, targets } = this.ready();
    if (!this.denoiser || !this.cameraValue) throw new Error('Renderer: enableRealTime() before renderFrame()');
    if (!Number.isInteger(samples) || samples < 1) throw new LanternError(`samples per frame must be a positive whole number, not ${samples}`);
    const s = this.settingsValue;
    if (s.spectral && !this.spectralEnabled) throw new Error('Renderer: enableSpectral() before rendering with settings.spectral');
    const torch = effectiveTorch(this.prepared?.scene, s.torch);
    const encoder = this.device.createCommandEncoder({ label: 'real-time frame' });
    this.denoiser.encodeFrame(encoder, {
      scene: resources,
      view: this.view,
      camera: this.cameraValue,
      settings: s,
      samples,
      rayCounters: targets.rayCounters,
      depthScale: this.sceneSize(),
      ...(torch ? { torch } : {}),
      ...(timer ? { timer } : {}),
    });
    timer?.resolve(encoder);
    this.device.queue.submit([encoder.finish()]);
    this.shown = 'frame';
  }

  /** Drops the real-time history: the next frame starts from its own samples. */
  resetHistory(): void {
    this.denoiser?.resetHistory();
  }

  /** The linear radiance of the last real-time frame (before tone mapping; a debug view if one is chosen). */
  async readFrame(): Promise<LinearImage> {
    const { targets } = this.ready();
    const output = this.denoiser?.output;
    if (!output) throw new Error('Renderer: renderFrame() before readFrame()');
    const raw = new Float32Array(await readBuffer(this.device, output));
    const n = targets.width * targets.height;
    const radiance = new Float32Array(n * 3);
    for (let i = 0; i < n; i++) for (let c = 0; c < 3; c++) radiance[i * 3 + c] = raw[i * 4 + c]!;
    return { width: targets.width, height: targets.height, radiance };
  }

  /** Tone-maps the current estimate and draws it onto `target` (a canvas texture); with a timer, times both passes. */
  present(target: GPUTexture, timer?: GpuTimer): void {
    const { targets } = this.ready();
    if (!this.presentPass) throw new Error('call enablePresentation() before present()');
    const encoder = this.device.createCommandEncoder({ label: 'present' });
    this.encodeTonemap(encoder, targets, timer);
    this.presentPass.encode(encoder, this.encodeDebugView(encoder, targets), target, timer);
    timer?.resolve(encoder);
    this.device.queue.submit([encoder.finish()]);
  }

  /** Compiles the present pipeline (browser only; the CLI never draws to a surface). */
  async enablePresentation(): Promise<void> {
    this.presentPass ??= await PresentPass.create(this.device);
  }

  /** Compiles the debug views' pipelines (readImage does it by itself; present needs it done first). */
  async enableDebugViews(): Promise<void> {
    this.debugViews ??= await DebugViews.create(this.device);
    if (this.prepared) await this.debugViews.prepare(this.prepared.packed.features);
  }

  /** The tone-mapped sRGB image, RGBA8 row-major, top row first; with a debug view, composed with it. */
  async readImage(): Promise<Uint8Array> {
    const { targets } = this.ready();
    if (this.settingsValue.debugView !== 'none') await this.enableDebugViews();
    const encoder = this.device.createCommandEncoder({ label: 'tone map for readback' });
    this.encodeTonemap(encoder, targets);
    const image = this.encodeDebugView(encoder, targets);
    this.device.queue.submit([encoder.finish()]);
    return readTexture4x8(this.device, image);
  }

  /**
   * The debug view's raw values, 4 floats per pixel, row-major, top row first (what each view holds:
   * shaders/passes/debug-view.wgsl), e.g. x = BVH nodes visited for 'heat-nodes'.
   */
  async readDebugValues(): Promise<Float32Array> {
    await this.renderDebugView();
    return this.debugViews!.readValues();
  }

  /** What the current debug view shows, with the numbers and colours of its scale (draw it as legendGradientCss()). */
  async debugLegend(): Promise<DebugLegend> {
    const { resources } = this.ready();
    const settings = this.settingsValue;
    if (settings.debugView === 'none') return debugLegend(settings, { maxDepth: this.bvhMaxDepth, maxLeafSize: 0, imageMax: 0 });
    await this.renderDebugView();
    return this.debugViews!.legend(this.settingsValue, this.prepared!, resources);
  }

  /** Depth of the deepest node of the scene's BVH (root = 0): the wireframe depth's upper bound. */
  get bvhMaxDepth(): number {
    return this.prepared?.bvh.stats.maxDepth ?? 0;
  }

  /** The linear radiance estimate and its per-pixel luminance variance. */
  async readAccumulation(): Promise<Accumulation> {
    const { targets } = this.ready();
    const raw = new Float32Array(await readBuffer(this.device, targets.accumulation));
    const n = targets.width * targets.height;
    const radiance = new Float32Array(n * 3);
    const luminanceVariance = new Float32Array(n);
    const samples = this.samples;
    const inv = samples > 0 ? 1 / samples : 0;
    for (let i = 0; i < n; i++) {
      const r = raw[i * 4]! * inv, g = raw[i * 4 + 1]! * inv, b = raw[i * 4 + 2]! * inv;
      radiance[i * 3] = r;
      radiance[i * 3 + 1] = g;
      radiance[i * 3 + 2] = b;
      if (samples > 1) {
        const mean = 0.2126 * r + 0.7152 * g + 0.0722 * b;
        luminanceVariance[i] = Math.max(0, (raw[i * 4 + 3]! - samples * mean * mean) / (samples - 1));
      }
    }
    return { width: targets.width, height: targets.height, samples, radiance, luminanceVariance };
  }

  /** Rays traced since accumulation last restarted: extension (closest hit) and shadow (any hit). */
  async readRayCounts(): Promise<RayCounts> {
    const { targets } = this.ready();
    const w = new Uint32Array(await readBuffer(this.device, targets.rayCounters));
    return { extension: w[0]! + w[1]! * 2 ** 32, shadow: w[2]! + w[3]! * 2 ** 32 };
  }

  /** Resolves when the GPU has finished everything submitted so far. */
  finish(): Promise<void> {
    return this.device.queue.onSubmittedWorkDone();
  }

  /** Frees every GPU resource this renderer created (the device stays). */
  destroy(): void {
    this.resources?.destroy();
    this.resources = undefined;
    this.destroyTargets();
    this.view.destroy();
    this.denoiser?.destroy();
    this.denoiser = undefined;
    this.pathTrace.destroy();
    this.tonemap.destroy();
    this.debugViews?.destroy();
  }

  /** For passes outside the facade (benchmarks, tests): the scene's GPU resources and the view. */
  internals(): { resources: SceneResources; view: ViewUniform } {
    const { resources } = this.ready();
    return { resources, view: this.view };
  }

  private encodeTonemap(encoder: GPUCommandEncoder, targets: ImageTargets, timer?: GpuTimer): void {
    const s = this.settingsValue;
    const frame = this.shown === 'frame' ? this.denoiser?.output : undefined;
    if (frame) {
      // Debug views are shown as computed: no exposure, no tone curve.
      const debug = s.denoiseView !== 'output';
      this.tonemap.encode(
        encoder,
        this.view,
        frame,
        targets.output,
        { exposureStops: debug ? 0 : (this.cameraValue?.exposureStops ?? 0) + s.exposureStops, toneMapper: debug ? 'linear' : s.toneMapper, sampleCount: 1 },
        timer,
      );
      return;
    }
    this.tonemap.encode(
      encoder,
      this.view,
      targets.accumulation,
      targets.output,
      { exposureStops: (this.cameraValue?.exposureStops ?? 0) + s.exposureStops, toneMapper: s.toneMapper, sampleCount: this.samples },
      timer,
    );
  }

  /** Encodes the debug view when one is set and returns the image to show: the composed one, or the tone-mapped one. */
  private encodeDebugView(encoder: GPUCommandEncoder, targets: ImageTargets): GPUTexture {
    const settings = this.settingsValue;
    if (settings.debugView === 'none') return targets.output;
    if (!this.debugViews) throw new Error('call enableDebugViews() before showing a debug view');
    return this.debugViews.encode(encoder, { prepared: this.prepared!, resources: this.resources!, view: this.view, image: targets.output, settings });
  }

  /** Runs the current debug view once (a debug view must be set) and waits for it. */
  private async renderDebugView(): Promise<void> {
    const { targets } = this.ready();
    if (this.settingsValue.debugView === 'none') throw new Error("Renderer: set a debugView other than 'none' first");
    await this.enableDebugViews();
    const encoder = this.device.createCommandEncoder({ label: 'debug view' });
    this.encodeDebugView(encoder, targets);
    this.device.queue.submit([encoder.finish()]);
    await this.finish();
  }

  /** Half the diagonal of the scene's bounds (the depth view's scale). */
  private sceneSize(): number {
    return this.prepared ? 0.5 * boundsDiagonal(this.prepared.bvh) || 1 : 1;
  }

  private ready(): { resources: SceneResources; targets: ImageTargets } {
    if (!this.resources) throw new Error('Renderer: setScene() first');
    if (!this.targets) throw new Error('Renderer: resize() first');
    return { resources: this.resources, targets: this.targets };
  }

  private updateView(): void {
    if (this.cameraValue && this.targets) this.view.update(this.cameraValue, this.targets.width, this.targets.height);
    this.resetAccumulation();
  }

  private destroyTargets(): void {
    if (!this.targets) return;
    this.targets.accumulation.destroy();
    this.targets.rayCounters.destroy();
    this.targets.output.destroy();
    this.targets = undefined;
  }
}

/** Throws a LanternError when an image of this size is not a sensible request or exceeds the GPU's limits. */
export function checkImageSize(width: number, height: number, limits: GPUSupportedLimits): void {
  for (const [name, v] of [['width', width], ['height', height]] as const) {
    if (!Number.isInteger(v) || v < 1) throw new LanternError(`image ${name} must be a whole number of pixels ≥ 1, not ${v}`);
  }
  const maxSide = Math.min(MAX_IMAGE_SIDE, limits.maxTextureDimension2D);
  if (width > maxSide || height > maxSide) {
    throw new LanternError(`image ${width}×${height} is too large: each side may be at most ${maxSide} pixels on this GPU`);
  }
  const bytes = width * height * ACCUMULATION_BYTES_PER_PIXEL;
  if (bytes > limits.maxStorageBufferBindingSize || bytes > limits.maxBufferSize) {
    const maxPixels = Math.floor(Math.min(limits.maxStorageBufferBindingSize, limits.maxBufferSize) / ACCUMULATION_BYTES_PER_PIXEL);
    throw new LanternError(`image ${width}×${height} is too large for this GPU: at most ${maxPixels} pixels fit one accumulation buffer`);
  }
}
