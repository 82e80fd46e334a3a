/**
 * The Renderer: the one facade the browser page, the CLI and the tests share. It holds the scene on
 * the GPU (renderer/scene-residency.ts), the camera, the settings and the image (renderer/image.ts),
 * and renders what recipeFor (renderer/recipes/recipe.ts) says a frame is:
 *
 *   accumulate / beginAccumulate   the progressive recipe: samples added to the exact estimate
 *   renderFrame / beginFrame       the real-time chain, the hybrid recipe, or a debug view alone
 *   present / readImage / read*    exposure, tone map, debug view, selection outline (renderer/image-output.ts)
 *
 * compile() compiles what the settings' recipe runs before its first frame. Every method that changes
 * the estimate (scene, camera, size, an estimate setting) restarts accumulation; the frame recipes'
 * histories survive camera moves (reprojected). Live editing: pick, setSelection, updateMaterials.
 */
import { LanternError } from '../errors.ts';
import type { GpuContext } from '../gpu/device.ts';
import { readBuffer } from '../gpu/readback.ts';
import { readAccumulation, readLinear, readRayCounts, type Accumulation, type LinearImage, type RayCounts } from './image-readback.ts';
import type { SceneResources } from '../gpu/scene-resources.ts';
import type { GpuTimer } from '../gpu/timestamps.ts';
import type { Tile } from '../passes/path-trace-pass.ts';
import { PresentPass } from '../passes/present-pass.ts';
import type { SelectedRange } from '../passes/selection-outline-pass.ts';
import { ImageOutput, type ShownImage } from './image-output.ts';
import { TraceRaysPass } from '../passes/trace-rays-pass.ts';
import { emptySceneUpdate, type SceneUpdate } from '../scene/dynamics.ts';
import type { TileCullingStats } from './tile-culled.ts';
import type { MaterialEdit } from '../scene/material-edit.ts';
import { TonemapPass } from '../passes/tonemap-pass.ts';
import type { ExposureReading } from '../passes/exposure-pass.ts';
import { exposureChoice, type ExposureChoice } from './exposure.ts';
import { lensProblem } from '../scene/lens.ts';
import type { Camera, Scene } from '../scene/types.ts';
import { debugLegend, type DebugLegend } from './debug-legend.ts';
import type { DebugViews } from './recipes/debug.ts';
import { ProgressiveRecipe } from './recipes/progressive.ts';
import { frameContext, wholeImage, type FrameContext } from './frame.ts';
import { ImageEstimate, type ImageTargets } from './image.ts';
import { pickPixel, type PickResult } from './pick.ts';
import { type GeometryUpdate, prepareScene, withAccel, withPreparedEnvironment, type PreparedScene } from './prepare.ts';
import type { Environment } from '../scene/environment.ts';
import type { Mat4 } from '../math/mat4.ts';
import { DEFAULT_SETTINGS, ESTIMATE_SETTINGS, validateSettings, type Integrator, type RenderSettings } from './settings.ts';
import { ViewUniform } from '../gpu/view.ts';
import { SceneResidency } from './scene-residency.ts';
import type { SceneFeatures } from '../gpu/pack/scene-pack.ts';
import type { SplitFrame } from './split-frame.ts';
import { FrameRequests } from './frame-requests.ts';
import { RendererKernels } from './renderer-kernels.ts';

export type { Accumulation, LinearImage, RayCounts } from './image-readback.ts';
export type { PickResult } from './pick.ts';

export class Renderer extends RendererKernels {
  /** The scene on the GPU, kept in step with the world (renderer/scene-residency.ts). */
  private readonly residency: SceneResidency;
  /** The image's targets and the progressive estimate in them. */
  private readonly image: ImageEstimate;
  private cameraValue?: Camera;
  private settingsValue: RenderSettings = DEFAULT_SETTINGS;
  /** Counts resetHistory() calls: a split frame begun before one is given up (SplitFrame.valid). */
  private historyResets = 0;
  /** What is rendered on request, and what was rendered last (renderer/frame-requests.ts). */
  private readonly requests: FrameRequests;
  private tracePass?: Promise<TraceRaysPass>;
  /** What a traced image becomes: exposure, tone map, debug view, selection outline, present. */
  private readonly output: ImageOutput;

  private constructor(
    readonly gpu: GpuContext,
    private readonly view: ViewUniform,
    progressive: ProgressiveRecipe | undefined,
    tonemap: TonemapPass,
    present?: PresentPass,
  ) {
    super(gpu.device, progressive);
    this.image = new ImageEstimate(gpu.device);
    this.output = new ImageOutput(gpu.device, tonemap, present);
    this.residency = new SceneResidency(gpu.device, {
      compile: (features) => Promise.all([this.recipes.prepare(features), this.output.selection.prepare(features)]),
      tileCulling: () => this.settingsValue.tileCulling,
      cameraPosition: () => this.cameraValue?.position,
      uploaded: () => this.invalidateSpecialisation(),
      geometryChanged: () => this.output.selection.markStale(),
      edited: () => {
        this.invalidateSpecialisation();
        this.resetAccumulation();
      },
      restarted: () => this.resetAccumulation(),
    });
    this.requests = new FrameRequests(this, this.image, this.recipes, this.residency, {
      settings: () => this.settingsValue,
      frame: (timer) => this.frame(timer),
      targets: () => this.ready().targets,
    });
  }

  private get prepared(): PreparedScene | undefined {
    return this.residency.prepared;
  }
  protected get resources(): SceneResources | undefined {
    return this.residency.resources;
  }

  /**
   * Compiles the progressive path tracer and the tone mapper, side by side. `features`: those of the
   * scene setScene will get, where known (maybe still a promise): that scene's variant alone compiles,
   * and setScene awaits it; without, a plain scene's. `presentation`: the canvas's format, for the
   * present pass. `progressive: false`: the path tracer is compiled only when compile() is asked for
   * a progressive render (a front end that knows what it runs: the CLI's frame mode, debug views and
   * ray benchmarks never accumulate).
   */
  static async create(gpu: GpuContext, options: { readonly features?: SceneFeatures | Promise<SceneFeatures>; readonly presentation?: GPUTextureFormat; readonly progressive?: boolean } = {}): Promise<Renderer> {
    const { device } = gpu;
    // The small passes first: they compile while the path tracer is reflected and its scene awaited.
    const [tonemap, present, progressive, features] = await Promise.all([
      TonemapPass.create(device),
      options.presentation ? PresentPass.create(device, options.presentation) : undefined,
      options.progressive === false ? undefined : ProgressiveRecipe.create(device, options.features),
      options.features,
    ]);
    const renderer = new Renderer(gpu, new ViewUniform(device), progressive, tonemap, present);
    renderer.expectedFeatures = features;
    return renderer;
  }

  get device(): GPUDevice {
    return this.gpu.device;
  }
  get sampleCount(): number {
    return this.image.samples;
  }
  get settings(): RenderSettings {
    return this.settingsValue;
  }
  get camera(): Camera | undefined {
    return this.cameraValue;
  }
  get width(): number {
    return this.image.targets?.width ?? 0;
  }
  get height(): number {
    return this.image.targets?.height ?? 0;
  }
  get scene(): PreparedScene | undefined {
    return this.prepared;
  }

  /** Uploads a scene (prepared here unless given prepared) and frees the previous one. Uses its camera. */
  async setScene(scene: Scene | PreparedScene): Promise<PreparedScene> {
    const accel = this.settingsValue.accel;
    const prepared = withAccel('packed' in scene ? scene : prepareScene(scene, undefined, { accel }), accel);
    // A scene exposed automatically (a game map) compiles the exposure pass beside its path tracer.
    const exposure = exposureChoice(prepared.scene, 0, this.settingsValue).kind === 'auto' ? this.output.exposure.compile() : undefined;
    await Promise.all([this.residency.upload(prepared), exposure]);
    void this.setSelection(undefined);
    // Another scene: the eye starts adapted to it, not to the last one.
    this.output.exposure.snap();
    this.setCamera(prepared.scene.camera);
    return prepared;
  }

  /**
   * Lights the scene with another environment (a sky, an HDR map, none) without preparing it again
   * (the environment, light table and scene info packed anew). The camera keeps its pose, with the
   * exposure change the sky brings (scene/environment-override.ts). Restarts accumulation.
   */
  async setEnvironment(environment: Environment): Promise<PreparedScene> {
    if (!this.prepared) throw new Error('Renderer: setScene() before setEnvironment()');
    const before = this.prepared.scene.camera.exposureStops ?? 0;
    const prepared = withPreparedEnvironment(this.prepared, environment);
    await this.residency.upload(prepared);
    const shift = (prepared.scene.camera.exposureStops ?? 0) - before;
    if (this.cameraValue) this.setCamera({ ...this.cameraValue, exposureStops: (this.cameraValue.exposureStops ?? 0) + shift });
    this.resetAccumulation();
    return prepared;
  }

  /**
   * Moves instances (new world-from-object transforms by instance id) without rebuilding the scene
   * (see applySceneUpdate). Restarts accumulation.
   */
  updateInstances(moves: ReadonlyMap<number, Mat4>): PreparedScene {
    return this.applySceneUpdate({ ...emptySceneUpdate(), instances: new Map([...moves].map(([id, worldFromObject]) => [id, { worldFromObject }])) });
  }

  /**
   * One step of a moving world (world/world.ts), applied in place (renderer/scene-residency.ts):
   * nothing is rebuilt. Restarts accumulation; returns the updated scene (keep it to upload again
   * after a lost device).
   */
  applySceneUpdate(update: SceneUpdate): PreparedScene {
    return this.residency.apply(update);
  }

  /** CPU milliseconds of the last geometry update: bottom-level refits, the top-level build, packing. */
  get lastUpdateMs(): GeometryUpdate['ms'] | undefined {
    return this.residency.lastUpdateMs;
  }

  /**
   * Edits materials by index (scene/material-edit.ts), their records and the light table rewritten in
   * place: no texture upload, no BVH build, no pipeline compile. Restarts accumulation; returns the
   * edited scene (keep it to upload again after a lost device).
   */
  updateMaterials(edits: ReadonlyMap<number, MaterialEdit>): PreparedScene {
    return this.residency.updateMaterials(edits);
  }

  /**
   * What the primary ray through pixel (x, y) of the image hits (its centre; the lens centre's ray for
   * a thin lens), traced on the GPU by the scene's own traversal (alpha tests included), or null for
   * a miss. Pixels count from the top-left corner of the rendered image.
   */
  async pick(x: number, y: number): Promise<PickResult | null> {
    const frame = this.frame();
    this.tracePass ??= TraceRaysPass.create(this.device, frame.prepared.packed.features);
    return pickPixel(frame, await this.tracePass, x, y);
  }

  /** Outlines one material's part of an instance (what a pick returns) in what present() draws, or nothing (undefined); never in the estimate. */
  async setSelection(selected: { readonly instanceIndex: number; readonly material: number } | undefined): Promise<void> {
    if (selected !== undefined && !this.prepared) throw new Error('Renderer: setScene() before setSelection()');
    await this.output.selection.set(this.prepared!, selected);
  }

  /** The selection (source triangle range and material), if any. */
  get selection(): SelectedRange | undefined {
    return this.output.selection.range;
  }

  /**
   * Sets the camera (restarts accumulation; the real-time history is reprojected). `camera.lens` gives
   * depth of field: `setCamera({ ...renderer.camera, lens: { apertureRadius, focusDistance } })`;
   * no lens, or an aperture of 0, is a pinhole. A lens with a negative aperture or a focus distance
   * ≤ 0 is refused (LanternError).
   */
  setCamera(camera: Camera): void {
    const problem = camera.lens && lensProblem(camera.lens);
    if (problem) throw new LanternError(problem, 'Give an aperture radius ≥ 0 and a focus distance > 0 (scene units)');
    this.cameraValue = camera;
    this.residency.swapTile(camera.position);
    this.updateView();
  }

  /** What tile culling costs and saves, while it is on. */
  get tileCullingStats(): TileCullingStats | undefined {
    return this.residency.tileCullingStats;
  }

  /**
   * Resolves once the scene is traced as the settings say: through the structure the `accel` setting
   * names, by kernels compiled for the `sampler` setting (rejects if building or compiling failed).
   */
  accelSettled(): Promise<void> {
    return Promise.all([this.residency.accelSettled(), this.recipes.samplersSettled()]).then(() => undefined);
  }

  /** Applies changed settings; those that change the estimate restart accumulation. */
  updateSettings(changes: Partial<RenderSettings>): void {
    const before = this.settingsValue;
    const next = validateSettings({ ...this.settingsValue, ...changes });
    const restart = ESTIMATE_SETTINGS.some((k) => next[k] !== this.settingsValue[k]);
    const culling = next.tileCulling !== this.settingsValue.tileCulling;
    const accel = next.accel !== this.settingsValue.accel;
    this.settingsValue = next;
    if (next.sampler !== before.sampler) this.recipes.useSamplers(next.sampler);
    if (culling) this.residency.configureTileCulling();
    // What the new settings add to the recipes compiled (the wavefront integrator, ReSTIR) compiles in the background.
    this.recipes.follow(next);
    // Another acceleration structure for the static world: built and uploaded in the background
    // (frames trace the current one meanwhile); accelSettled() waits for it.
    if (accel) this.residency.switchAccel(() => this.settingsValue.accel);
    // Automatic exposure asked for: compiled in the background; present() shows the scene's exposure
    // until it is ready, readImage() waits for it (and reports a failure).
    if (this.exposureChoice.kind === 'auto') this.output.exposure.compile().catch(() => undefined);
    if (restart) {
      // Bounces and light sampling are inlined into specialised kernels; every estimate setting counts as an edit.
      this.invalidateSpecialisation();
      this.resetAccumulation();
    }
  }

  /** Sets the image size, checked against the GPU's limits. */
  async resize(width: number, height: number): Promise<void> {
    if (await this.image.resize(width, height)) this.updateView();
  }

  /** Counts resetAccumulation() calls (the ray counters restart with each): callers tell fresh counts from running ones. */
  get accumulationEpoch(): number {
    return this.image.epoch;
  }

  /**
   * Discards every accumulated sample and the ray counts (the next frame starts a new estimate).
   * `firstSample`: the global index of the new estimate's first sample (default 0), so that an
   * estimate of samples [s0, s1) of the one sequence can be rendered alone (a farm's shard).
   */
  resetAccumulation(firstSample = 0): void {
    this.image.restart(firstSample);
  }

  /**
   * Replaces the estimate by per-pixel sums (a vec4f per pixel, Σ radiance and Σ luminance², top row
   * first: what readAccumulationSums gives) of `samples` samples, e.g. shards merged on the CPU;
   * readImage and readAccumulation then show it as if traced here.
   */
  loadAccumulation(sums: Float32Array, samples: number): void {
    this.ready();
    this.image.load(sums, samples);
    this.requests.shown = 'accumulation';
  }

  /**
   * What the recipes' passes are given for a frame (renderer/frame.ts): the scene, the view and the
   * camera, the settings, the image's targets, the torch the settings leave, the scene's size. Passes
   * outside the recipes (the traversal benchmark) take it too.
   */
  frame(timer?: GpuTimer): FrameContext {
    const { resources, targets } = this.ready();
    const camera = this.cameraValue;
    if (!camera) throw new Error('Renderer: setCamera() before rendering');
    return frameContext({ device: this.device, scene: resources, prepared: this.prepared!, view: this.view, camera, settings: this.settingsValue, targets }, timer);
  }

  /**
   * Adds `samples` paths per pixel over `tiles` (default: the whole image), one submit per tile so
   * that no single submit runs long enough to trip a GPU watchdog. Returns without waiting. With a
   * timer, each tile's pass is timed and the timestamps are resolved with the last tile.
   */
  accumulate(samples: number, tiles: readonly Tile[] = [wholeImage(this)], timer?: GpuTimer): void {
    this.requests.accumulate(samples, tiles, timer);
  }

  /**
   * Adds `samples` paths per pixel as a SplitFrame of row bands (the viewer's; the CLI's long renders
   * use accumulate with DispatchPlanner's tiles). The samples count once the last band is submitted;
   * an estimate reset meanwhile gives the frame up.
   */
  beginAccumulate(samples: number, timer?: GpuTimer): SplitFrame {
    return this.requests.beginAccumulate(samples, timer);
  }

  /**
   * The path tracing of one real-time frame alone (RealTimeRecipe.encodeTraceOnly: no filter, no
   * ReSTIR, the history kept), `samples` paths per pixel with the random streams of frame
   * `sampleIndex`; `breakdown` times the wavefront's stages apart. For timing and comparing the two
   * integrators (bench, readFrameTrace). Returns which traced.
   */
  traceFrame(samples: number, options: { readonly sampleIndex?: number; readonly timer?: GpuTimer; readonly breakdown?: boolean } = {}): Integrator {
    return this.requests.traceFrame(samples, options);
  }

  /**
   * One frame of the recipe the settings choose (recipeFor, frames asked for), in one submit: the
   * real-time chain, the hybrid recipe, or a debug view alone (nothing traced). The history survives
   * setCamera (reprojected) and setScene; resize or resetHistory() drop it. With a timer, every pass
   * is timed. present(), readImage() and readFrame() show the result.
   */
  renderFrame(samples: number, timer?: GpuTimer): void {
    const frame = this.beginFrame(samples, timer);
    frame.submitChunk(frame.height);
  }

  /**
   * One frame (renderFrame) as a SplitFrame: the tracing in row bands submitted one at a time (the
   * page answers input between them), the filters with the last; it adds up to exactly renderFrame's.
   * The wavefront integrator and the hybrid recipe trace whole frames (one band).
   */
  beginFrame(samples: number, timer?: GpuTimer): SplitFrame {
    return this.requests.beginFrame(samples, timer);
  }

  /** What SplitFrame checks before each band: the estimate, the history and the scene are those the frame began with. */
  frameGeneration(): string {
    return `${this.image.epoch} ${this.historyResets} ${this.residency.uploads}`;
  }

  /** Submits an encoder (SplitFrame's bands). */
  submit(encoder: GPUCommandEncoder): void {
    this.device.queue.submit([encoder.finish()]);
  }

  /** The targets in use (SplitFrame checks that a resize has not replaced them). */
  currentTargets(): object | undefined {
    return this.image.targets;
  }

  /**
   * Chooses what present() and readImage() show: the progressive estimate or the last real-time frame
   * (by default, whichever was rendered last). The viewer renders both while a still view converges.
   */
  show(image: 'accumulation' | 'frame'): void {
    this.requests.show(image);
  }

  /**
   * The real-time chain's next frame draws the random streams of samples `sampleIndex` on, as frame
   * f of a sequence at spp samples a frame does (f·spp) when every frame before it was rendered.
   * Exact only for frames that keep no history (no temporal pass, filter or ReSTIR, a manual
   * exposure): `render --frames` then renders the listed frames alone. `previousCamera`: the
   * camera of the sequence's frame before (undefined before its first), as that frame would have left it.
   */
  seekFrameSamples(sampleIndex: number, previousCamera: Camera | undefined): void {
    if (!this.recipes.realTime) throw new Error('Renderer: compile() the real-time chain before seekFrameSamples()');
    this.recipes.realTime.seek(sampleIndex, previousCamera);
  }

  /** Drops the real-time history: the next frame starts from its own samples. */
  resetHistory(): void {
    this.historyResets++;
    this.recipes.resetHistory();
  }

  /** The linear radiance of the last real-time frame (before tone mapping; a debug view if one is chosen). */
  async readFrame(): Promise<LinearImage> {
    const { targets } = this.ready();
    const output = this.requests.lastFrame?.output;
    if (!output) throw new Error('Renderer: renderFrame() before readFrame()');
    return readLinear(this.device, output, targets);
  }

  /** Tone-maps the current estimate and draws it onto `target` (a canvas texture); with a timer, times both passes. */
  present(target: GPUTexture, timer?: GpuTimer): void {
    this.output.present(target, this.shownImage(), timer);
  }

  /** Compiles the present pipeline for targets of `format` (a canvas's; browser only: the CLI never draws to a surface). */
  async setPresentationFormat(format: GPUTextureFormat): Promise<void> {
    await this.output.setPresentationFormat(format);
  }

  /**
   * The tone-mapped sRGB image, RGBA8 row-major, top row first; with a debug view, composed with it.
   * With a timer, the exposure and tone map passes are timed (resolved here; read them after).
   */
  async readImage(timer?: GpuTimer): Promise<Uint8Array> {
    if (this.settingsValue.debugView !== 'none') await this.recipes.compileDebugViews();
    return this.output.readImage(this.shownImage(), timer);
  }

  /**
   * The debug view's raw values, 4 floats per pixel, row-major, top row first (what each view holds:
   * shaders/passes/debug-view.wgsl), e.g. x = BVH nodes visited for 'heat-nodes'.
   */
  async readDebugValues(): Promise<Float32Array> {
    return (await this.renderDebugView()).readValues();
  }

  /** What the current debug view shows, with the numbers and colours of its scale (draw it as legendGradientCss()). */
  async debugLegend(): Promise<DebugLegend> {
    const { resources } = this.ready();
    const settings = this.settingsValue;
    if (settings.debugView === 'none') return debugLegend(settings, { maxDepth: this.bvhMaxDepth, maxLeafSize: 0, imageMax: 0 });
    return (await this.renderDebugView()).legend(settings, this.prepared!, resources);
  }

  /** Depth of the deepest node of the scene's BVH (root = 0): the wireframe depth's upper bound. */
  get bvhMaxDepth(): number {
    return this.prepared?.bvh.stats.maxDepth ?? 0;
  }

  /** The linear radiance estimate and its per-pixel luminance variance. */
  async readAccumulation(): Promise<Accumulation> {
    return readAccumulation(this.device, this.ready().targets, this.image.samples);
  }

  /** The accumulation buffer as it is: a vec4f per pixel (Σ radiance, Σ luminance²) over sampleCount samples, not divided. */
  async readAccumulationSums(): Promise<Float32Array> {
    return new Float32Array(await readBuffer(this.device, this.ready().targets.accumulation));
  }

  /** Rays traced since accumulation last restarted: extension (closest hit) and shadow (any hit). */
  async readRayCounts(): Promise<RayCounts> {
    return readRayCounts(this.device, this.ready().targets);
  }

  /** Resolves when the GPU has finished everything submitted so far. */
  finish(): Promise<void> {
    return this.device.queue.onSubmittedWorkDone();
  }

  /** Frees every GPU resource this renderer created (the device stays). */
  destroy(): void {
    this.setIdleSpecialisation(undefined);
    this.invalidateSpecialisation();
    this.residency.destroy();
    this.image.destroy();
    this.view.destroy();
    this.recipes.destroy();
    this.output.destroy();
    void this.tracePass?.then((p) => p.destroy());
  }

  /**
   * How the image is exposed now (renderer/exposure.ts exposureChoice): the exposure setting, or where
   * it is left to the scene, the scene's kind (automatic for the game maps).
   */
  get exposureChoice(): ExposureChoice {
    return exposureChoice(this.prepared?.scene, this.cameraValue?.exposureStops ?? 0, this.settingsValue);
  }

  /**
   * Lets the automatic exposure adapt by `seconds` more at the next readImage() (a frame sequence's
   * time between frames; present() adapts by the wall clock by itself). The first image of a scene
   * takes its target exposure at once.
   */
  advanceExposure(seconds: number): void {
    this.output.exposure.advance(seconds);
  }

  /** The automatic exposure as the last tone map left it: the image's log-average luminance (log2) and the exposure (stops). */
  readExposure(): Promise<ExposureReading> {
    return this.output.exposure.read();
  }

  /** What present() and readImage() show now: the estimate or the last frame, as the settings expose it. */
  private shownImage(): ShownImage {
    const { resources, targets } = this.ready();
    const { shown, lastFrame } = this.requests;
    const frame = shown === 'frame' ? lastFrame?.output : undefined;
    return {
      targets, view: this.view, settings: this.settingsValue,
      radiance: frame ?? targets.accumulation,
      sampleCount: frame ? 1 : this.image.samples,
      raw: frame !== undefined && lastFrame!.showsRawValues({ settings: this.settingsValue }),
      exposure: this.exposureChoice,
      sceneStops: this.cameraValue?.exposureStops ?? 0,
      scene: { prepared: this.prepared!, resources },
      debugViews: this.recipes.debugViews,
    };
  }

  /** Runs the current debug view once (a debug view must be set) and waits for it. */
  private async renderDebugView(): Promise<DebugViews> {
    if (this.settingsValue.debugView === 'none') throw new Error("Renderer: set a debugView other than 'none' first");
    const views = await this.recipes.compileDebugViews();
    await this.output.renderDebugView(this.shownImage());
    return views;
  }

  private ready(): { resources: SceneResources; targets: ImageTargets } {
    if (!this.resources) throw new Error('Renderer: setScene() first');
    if (!this.image.targets) throw new Error('Renderer: resize() first');
    return { resources: this.resources, targets: this.image.targets };
  }

  private updateView(): void {
    if (this.cameraValue && this.image.targets) this.view.update(this.cameraValue, this.image.targets.width, this.image.targets.height);
    this.output.selection.markStale();
    this.resetAccumulation();
  }
}
