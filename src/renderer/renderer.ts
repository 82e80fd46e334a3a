/**
 * The Renderer: one object shared by the browser page, the CLI and the tests. It owns the GPU state
 * of a scene and an image and runs the frame recipe
 *
 *   path trace (adds samples to the float32 accumulation) → tone map (8-bit sRGB) → present | read back
 *
 * Facade: setScene, setCamera, updateSettings, resize, accumulate, present, read*. Every method that
 * changes the estimate (scene, camera, size, bounces, light sampling, seed) restarts accumulation.
 * With a debug view set (settings.debugView), present and readImage show it as settings.debugLayout
 * asks (renderer/debug-views.ts).
 *
 * Frames: renderFrame(spp) runs the frame recipe the settings choose (renderer/recipes/recipe.ts
 * recipeFor: the real-time chain of renderer/denoiser.ts, the hybrid recipe, or a debug view alone);
 * present and readImage then show its output until the next accumulate(). compile() compiles what
 * the settings' recipe runs, before its first frame.
 *
 * Live editing: pick(x, y) traces one primary ray through a pixel (the scene's own traversal);
 * setSelection(instance) outlines an object in what present() draws (never in the estimate);
 * updateMaterials(edits) rewrites material records (and the light table for emission) in place.
 */
import { boundsDiagonal } from '../bvh/stats.ts';
import { LanternError } from '../errors.ts';
import type { GpuContext } from '../gpu/device.ts';
import { withErrorScope } from '../gpu/device.ts';
import { timedStage } from '../gpu/stage-log.ts';
import { createBufferWithData, readBuffer, readTexture4x8 } from '../gpu/readback.ts';
import { SceneResources, writeTriangleAttributes } from '../gpu/scene-resources.ts';
import { packInstances } from '../gpu/pack/scene-pack.ts';
import type { GpuTimer } from '../gpu/timestamps.ts';
import type { Tile, TracingKernels } from '../passes/path-trace-pass.ts';
import { PresentPass } from '../passes/present-pass.ts';
import { SelectionOutlinePass, type SelectedRange } from '../passes/selection-outline-pass.ts';
import { packRays, rayBufferStrides, TraceRaysPass, unpackHits } from '../passes/trace-rays-pass.ts';
import { dot, type Vec3 } from '../math/vec3.ts';
import { emptySceneUpdate, isEmptyUpdate, type SceneUpdate } from '../scene/dynamics.ts';
import { defaultTileCulling } from '../scene/tile-culling.ts';
import { TILE_SWAP_BUFFERS, TileCulledScenes, type TileCullingStats } from './tile-culled.ts';
import type { MaterialEdit } from '../scene/material-edit.ts';
import { TonemapPass } from '../passes/tonemap-pass.ts';
import { ExposurePass, type ExposureReading } from '../passes/exposure-pass.ts';
import { adaptationKeep, exposureChoice, type ExposureChoice } from './exposure.ts';
import { lensProblem } from '../scene/lens.ts';
import type { Camera, Scene } from '../scene/types.ts';
import { debugLegend, type DebugLegend } from './debug-legend.ts';
import { DebugViews } from './recipes/debug.ts';
import { RealTimeRecipe, type DenoiserBufferSize, type FrameTrace } from './recipes/real-time.ts';
import { HybridRecipe } from './recipes/hybrid.ts';
import { ProgressiveRecipe } from './recipes/progressive.ts';
import type { FrameRecipe, RecipeFrame } from './recipes/frame-recipe.ts';
import { wholeImage, type FrameContext, type ImageTargets } from './frame.ts';
import { accelOf, editMaterials, LIGHT_BUFFERS, updateGeometry, type BufferWrite, type GeometryUpdate, prepareScene, withAccel, withPreparedEnvironment, type PreparedScene } from './prepare.ts';
import type { Environment } from '../scene/environment.ts';
import type { Mat4 } from '../math/mat4.ts';
import { DEFAULT_SETTINGS, effectiveTorch, ESTIMATE_SETTINGS, validateSettings, type Integrator, type RenderSettings } from './settings.ts';
import { primaryRay, ViewUniform } from '../gpu/view.ts';
import type { SpecialiseOptions } from '../gpu/specialisation.ts';
import { SpecialisationSchedule, type KernelKind, type SpecialisationReport } from './specialisation-schedule.ts';
import { SceneResidency } from './scene-residency.ts';
import { resolveSampler, type Sampler } from '../passes/variants.ts';
import type { SceneFeatures } from '../gpu/pack/scene-pack.ts';
import { SplitFrame } from './split-frame.ts';
import { recipeCompiles, recipeFor, type RecipeIntent } from './recipes/recipe.ts';

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

/** What one primary ray through a pixel hit (Renderer.pick). */
export interface PickResult {
  /** Distance from the camera along the ray (scene units). */
  readonly distance: number;
  /** Distance along the camera's forward axis: what a thin lens's focusDistance measures. */
  readonly depth: number;
  /** World-space hit point. */
  readonly position: Vec3;
  /** Index into Scene.instances, and that instance's id. */
  readonly instanceIndex: number;
  readonly instanceId: number;
  /** Index into Scene.materials. */
  readonly material: number;
  /** Source primitive index (scene/triangles.ts order). */
  readonly primitive: number;
}

export class Renderer {
  /** The scene on the GPU, kept in step with the world (renderer/scene-residency.ts). */
  private readonly residency: SceneResidency;
  private targets?: ImageTargets;
  private cameraValue?: Camera;
  private settingsValue: RenderSettings = DEFAULT_SETTINGS;
  private samples = 0;
  private epoch = 0;
  /** Counts resetHistory() calls: a split frame begun before one is given up (SplitFrame.valid). */
  private historyResets = 0;
  /** The real-time recipe (compiled by compile() for its settings). */
  private realTime?: RealTimeRecipe;
  /** The hybrid recipe (compiled by compile() for its settings). */
  private hybrid?: HybridRecipe;
  /** The recipe of the last frame (whose output present and readFrame show). */
  private lastFrame?: FrameRecipe;
  /** Whether the spectral variants are compiled for each scene (compile() with settings.spectral). */
  private spectralEnabled = false;
  /** What present() and readImage() show: the progressive estimate or the last real-time frame. */
  private shown: 'accumulation' | 'frame' = 'accumulation';
  /** When the tracing kernels are specialised to the scene (requestSpecialisation, the idle policy). */
  private readonly specialising = new SpecialisationSchedule({
    current: () => (this.prepared && this.resources ? { prepared: this.prepared, resources: this.resources, settings: this.settingsValue } : undefined),
    kernels: () => ({ sets: [this.progressive.kernels, ...(this.realTime ? [this.realTime.frameKernels] : [])], ...(this.realTime?.wavefrontPass ? { wavefront: this.realTime.wavefrontPass } : {}) }),
  });
  private tracePass?: Promise<TraceRaysPass>;
  private selectionPass?: SelectionOutlinePass;
  /** The selected instance's source triangles, outlined by present(). */
  private selectionRange?: SelectedRange;
  /** Whether the selection mask must be traced again (view, size, scene or selection changed). */
  private selectionStale = true;
  /** Whether the adapted exposure holds this scene's (false: the next tone map snaps to its target). */
  private exposureAdapted = false;
  /** Seconds of adaptation readImage() applies next (advanceExposure). */
  private pendingExposureSeconds = 0;
  /** When present() last adapted the exposure (performance.now()): the viewer adapts on the wall clock. */
  private lastPresentMs?: number;
  /** The automatic exposure's kernels, compiled the first time an image is exposed automatically (compileAutoExposure). */
  private exposure?: ExposurePass;
  private exposureCompile?: Promise<ExposurePass>;
  private destroyed = false;

  private constructor(
    readonly gpu: GpuContext,
    private readonly view: ViewUniform,
    private readonly progressive: ProgressiveRecipe,
    private readonly tonemap: TonemapPass,
    private presentPass?: PresentPass,
    private debugViews?: DebugViews,
  ) {
    this.residency = new SceneResidency(gpu.device, {
      compile: (features) => Promise.all([
        this.progressive.prepare(features), this.realTime?.prepare(features), this.hybrid?.prepare(features), this.debugViews?.prepare(features), this.selectionPass?.prepare(features),
        ...(this.spectralEnabled ? [this.progressive.prepare(features, true), this.realTime?.prepare(features, true)] : []),
      ]),
      tileCulling: () => this.settingsValue.tileCulling,
      cameraPosition: () => this.cameraValue?.position,
      uploaded: () => this.invalidateSpecialisation(),
      geometryChanged: () => (this.selectionStale = true),
      edited: () => {
        this.invalidateSpecialisation();
        this.resetAccumulation();
      },
      restarted: () => this.resetAccumulation(),
    });
  }

  private get prepared(): PreparedScene | undefined {
    return this.residency.prepared;
  }
  private get resources(): SceneResources | undefined {
    return this.residency.resources;
  }

  /**
   * Compiles the path tracer and the tone mapper, side by side. `features`: those of the scene that
   * setScene will get (PackedScene.features), where the caller knows them: the path tracer variant
   * for that scene alone starts compiling, and setScene awaits it (and reports its errors). Without,
   * a plain scene's variant is compiled here, so errors show at once, and setScene compiles the
   * scene's. `features` may be a promise (a scene still loading elsewhere): the path tracer is
   * reflected meanwhile, and the tone mapper compiled. `presentation`: the canvas's format, for the
   * browser's present pass (setPresentationFormat), compiled alongside.
   */
  static async create(gpu: GpuContext, options: { readonly features?: SceneFeatures | Promise<SceneFeatures>; readonly presentation?: GPUTextureFormat } = {}): Promise<Renderer> {
    const { device } = gpu;
    // The small passes first: they compile while the path tracer is reflected and its scene awaited.
    const [tonemap, present, progressive, features] = await Promise.all([
      TonemapPass.create(device),
      options.presentation ? PresentPass.create(device, options.presentation) : undefined,
      ProgressiveRecipe.create(device, options.features),
      options.features,
    ]);
    const renderer = new Renderer(gpu, new ViewUniform(device), progressive, tonemap, present);
    renderer.expectedFeatures = features;
    return renderer;
  }

  /** The features of the scene setScene will get, as Renderer.create was told, until one is set. */
  private expectedFeatures?: SceneFeatures;

  /** The features of the scene (or of the one about to be set): what a recipe enabled now compiles for first. */
  private get sceneFeatures(): SceneFeatures | undefined {
    return this.prepared?.packed.features ?? this.expectedFeatures;
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
    const accel = this.settingsValue.accel;
    const prepared = withAccel('packed' in scene ? scene : prepareScene(scene, undefined, { accel }), accel);
    // A scene exposed automatically (a game map) compiles the exposure pass beside its path tracer.
    const exposure = exposureChoice(prepared.scene, 0, this.settingsValue).kind === 'auto' ? this.compileAutoExposure() : undefined;
    await Promise.all([this.residency.upload(prepared), exposure]);
    void this.setSelection(undefined);
    // Another scene: the eye starts adapted to it, not to the last one.
    this.exposureAdapted = false;
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
   * One step of a moving world (world/world.ts): instances moved or changed material, meshes morphed,
   * materials animated. Nothing is rebuilt: geometry is refitted and its buffers rewritten in place
   * (renderer/prepare.ts updateGeometry), materials repacked (updateMaterials). Restarts
   * accumulation; returns the updated scene (keep it to upload again after a lost device).
   * `walkHeights` is the viewer's business.
   */
  applySceneUpdate(update: SceneUpdate): PreparedScene {
    return this.residency.apply(update);
  }

  /** CPU milliseconds of the last geometry update: bottom-level refits, the top-level build, packing. */
  get lastUpdateMs(): GeometryUpdate['ms'] | undefined {
    return this.residency.lastUpdateMs;
  }

  /**
   * Edits materials by index (scene/material-edit.ts: colour, roughness, metallic, IOR, transmission,
   * emission) without rebuilding anything: the edited records are packed again and the materials
   * buffer rewritten; an emission edit also packs the light table again (renderer/prepare.ts
   * editMaterials) and rewrites it, reallocating the light-slot buffer alone where it grew (an
   * emitter appeared). No texture upload, no BVH build, no pipeline compile. Restarts accumulation;
   * returns the edited scene (keep it to upload again after a lost device).
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
    const { resources, targets } = this.ready();
    const camera = this.cameraValue;
    const prepared = this.prepared!;
    if (!camera) throw new Error('Renderer: setCamera() before pick()');
    if (!(x >= 0 && x < targets.width && y >= 0 && y < targets.height)) throw new LanternError(`pixel (${x}, ${y}) is outside the ${targets.width}×${targets.height} image`);
    const ray = primaryRay(camera, targets.width, targets.height, Math.floor(x) + 0.5, Math.floor(y) + 0.5);
    this.tracePass ??= TraceRaysPass.create(this.device, prepared.packed.features);
    const pass = await this.tracePass;
    const device = this.device;
    const rays = createBufferWithData(device, 'pick ray', packRays([ray]), GPUBufferUsage.STORAGE);
    const hits = device.createBuffer({ label: 'pick hit', size: unpackHitsSize(), usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC });
    try {
      const encoder = device.createCommandEncoder({ label: 'pick' });
      pass.encode(encoder, await pass.bind(resources, rays, hits, 1), undefined, 'pick');
      device.queue.submit([encoder.finish()]);
      const hit = unpackHits(await readBuffer(device, hits), 1)[0]!;
      if (hit.triangle === NO_PRIMITIVE || hit.triangle >= prepared.triangles.count) return null;
      const instanceIndex = prepared.triangles.instanceIds[hit.triangle]!;
      const { origin, direction } = ray;
      return {
        distance: hit.t,
        depth: hit.t * dot(direction, cameraForward(camera)),
        position: [origin[0] + hit.t * direction[0], origin[1] + hit.t * direction[1], origin[2] + hit.t * direction[2]],
        instanceIndex,
        instanceId: prepared.scene.instances[instanceIndex]!.id,
        material: prepared.triangles.materialIds[hit.triangle]!,
        primitive: hit.triangle,
      };
    } finally {
      rays.destroy();
      hits.destroy();
    }
  }

  /**
   * Outlines the part of an instance (index into Scene.instances) made of one material (what a pick
   * returns; the part a material edit there changes) in what present() draws, or nothing
   * (undefined). The estimate and readImage() are untouched. Compiles the outline's pipelines on
   * first use.
   */
  async setSelection(selected: { readonly instanceIndex: number; readonly material: number } | undefined): Promise<void> {
    if (selected === undefined) {
      this.selectionRange = undefined;
      this.selectionPass?.destroyTargets();
      return;
    }
    const prepared = this.prepared;
    if (!prepared) throw new Error('Renderer: setScene() before setSelection()');
    const triangles = prepared.triangles;
    const { instanceIndex, material } = selected;
    if (!(material >= 0 && material < prepared.scene.materials.length)) throw new LanternError(`scene '${prepared.scene.name}' has no material ${material}`);
    if (!Number.isInteger(instanceIndex) || instanceIndex < 0 || instanceIndex >= triangles.instanceFirstTriangle.length) {
      throw new LanternError(`scene '${prepared.scene.name}' has no instance ${instanceIndex}`);
    }
    if (!this.selectionPass) {
      const pass = await SelectionOutlinePass.create(this.device, prepared.packed.features);
      this.selectionPass ??= pass;
    }
    await this.selectionPass.prepare(prepared.packed.features);
    // The instance's triangles are contiguous in the flattened list (scene/triangles.ts).
    const first = triangles.instanceFirstTriangle[instanceIndex]!;
    const end = triangles.instanceFirstTriangle[instanceIndex + 1] ?? triangles.count;
    this.selectionRange = { first, end, material };
    this.selectionStale = true;
  }

  /** The selection (source triangle range and material), if any. */
  get selection(): SelectedRange | undefined {
    return this.selectionRange;
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

  private accelPending: Promise<void> = Promise.resolve();
  /** The path tracers' kernels for the sampler setting, compiling after a change (useSamplers). */
  private samplerPending: Promise<void> = Promise.resolve();

  /**
   * Resolves once the scene is traced as the settings say: through the structure the `accel` setting
   * names, by kernels compiled for the `sampler` setting (rejects if building or compiling failed).
   */
  accelSettled(): Promise<void> {
    return Promise.all([this.accelPending, this.samplerPending]).then(() => undefined);
  }

  /**
   * Compiles the path tracers for the samplers the settings resolve to, where they are compiled for
   * others (a PCG kernel holds no Sobol code: lib/random.wgsl SAMPLER). Until they are ready, samples
   * and frames are traced with the old ones (unbiased, but the old sampler's): renders that want the
   * new sampler's estimate alone await accelSettled() first, as renderProgressive and the CLI do.
   */
  private useSamplers(): void {
    const s = this.settingsValue;
    const wanted: [TracingKernels, Sampler][] = [[this.progressive.kernels, resolveSampler(s.sampler, 'progressive')]];
    if (this.realTime) wanted.push([this.realTime.frameKernels, resolveSampler(s.sampler, 'real-time')]);
    const switching = wanted.filter(([k, sampler]) => k.sampler !== sampler);
    if (switching.length === 0) return;
    const done = Promise.all(switching.map(([k, sampler]) => k.useSampler(sampler))).then(() => undefined);
    this.samplerPending = this.samplerPending.catch(() => undefined).then(() => done);
    this.samplerPending.catch(() => undefined); // the error is accelSettled()'s to report
  }

  /** Applies changed settings; those that change the estimate restart accumulation. */
  updateSettings(changes: Partial<RenderSettings>): void {
    const before = this.settingsValue;
    const next = validateSettings({ ...this.settingsValue, ...changes });
    const restart = ESTIMATE_SETTINGS.some((k) => next[k] !== this.settingsValue[k]);
    const culling = next.tileCulling !== this.settingsValue.tileCulling;
    const accel = next.accel !== this.settingsValue.accel;
    this.settingsValue = next;
    if (next.sampler !== before.sampler) this.useSamplers();
    if (culling) this.residency.configureTileCulling();
    // The wavefront frame path tracer is compiled in the background; frames use the megakernel until it is ready.
    if (next.integrator === 'wavefront' && this.realTime) this.compileWavefront().catch((e: unknown) => (this.wavefrontError = e));
    // So are the ReSTIR passes; frames take one light sample per bounce until they are ready.
    if (next.restir && this.realTime) this.realTime.enableRestir().catch((e: unknown) => (this.restirError = e));
    // Another acceleration structure for the static world: built and uploaded in the background
    // (frames trace the current one meanwhile); accelSettled() waits for it.
    if (accel && this.prepared) {
      // One switch at a time, each to the accel set by then (a quick bvh → grid → bvh ends on the BVH).
      this.accelPending = this.accelPending
        .catch(() => undefined)
        .then(() => (this.prepared && accelOf(this.prepared) !== this.settingsValue.accel ? this.residency.upload(withAccel(this.prepared, this.settingsValue.accel)) : undefined));
      this.accelPending.catch(() => undefined); // the error is accelSettled()'s to report
    }
    // Automatic exposure asked for: compiled in the background; present() shows the scene's exposure
    // until it is ready, readImage() waits for it (and reports a failure).
    if (this.exposureChoice.kind === 'auto') this.compileAutoExposure().catch(() => undefined);
    if (restart) {
      // Bounces and light sampling are inlined into specialised kernels; every estimate setting counts as an edit.
      this.invalidateSpecialisation();
      this.resetAccumulation();
    }
  }

  /**
   * Which kernels accumulate() and renderFrame() run now. Generic until requestSpecialisation's
   * compile is ready; every edit (scene, environment, instances, materials, an estimate setting)
   * goes back to generic at once. Camera moves, resizes and display settings keep the kernel.
   */
  get kernel(): KernelKind {
    return this.specialising.kernel;
  }

  /** Which kernels the wavefront frame path tracer runs now: generic until specialised with the others (requestSpecialisation). */
  get wavefrontKernel(): KernelKind {
    return this.specialising.wavefrontKernel;
  }

  /** What the specialised kernels in use were compiled for, and how long that took. */
  get specialisation(): SpecialisationReport | undefined {
    return this.specialising.report;
  }

  /** The error of the last automatic (idle) specialisation, if it failed; rendering stays generic. */
  get specialisationError(): unknown {
    return this.specialising.error;
  }

  /**
   * Compiles the tracing kernels specialised to the scene and settings as they are now
   * (renderer/specialisation-schedule.ts, gpu/specialisation.ts), asynchronously: frames keep
   * rendering with the generic kernels until the compile is ready, then the next one uses them.
   * Accumulation continues, since both compute the same estimator. Resolves with the report once
   * switched, or undefined when an edit came first (the result is dropped), and at once with
   * undefined in spectral mode (specialised kernels are RGB) and for scenes with moving instances
   * (nothing there is frozen). Calling it again while a compile runs waits for that one.
   */
  requestSpecialisation(options: SpecialiseOptions = {}): Promise<SpecialisationReport | undefined> {
    return this.specialising.request(options);
  }

  /**
   * Goes back to the generic kernels at once and drops any compile under way; with an idle delay set
   * (setIdleSpecialisation), restarts its timer. Every method that edits the scene or an estimate
   * setting calls it; so must any new one.
   */
  invalidateSpecialisation(): void {
    this.specialising.invalidate();
  }

  /**
   * The idle policy shared by the front ends: specialise once the scene has gone `idleMs` without an
   * edit (the viewer uses 1000); undefined turns it off (the default). A failed compile is kept in
   * specialisationError and rendering stays generic.
   */
  setIdleSpecialisation(idleMs: number | undefined): void {
    this.specialising.setIdle(idleMs);
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
    return wholeImage(this);
  }

  /**
   * What the recipes' passes are given for a frame (renderer/frame.ts): the scene, the view and the
   * camera, the settings, the image's targets, the torch the settings leave, the scene's size.
   */
  private frameContext(timer?: GpuTimer): FrameContext {
    const { resources, targets } = this.ready();
    const camera = this.cameraValue;
    if (!camera) throw new Error('Renderer: setCamera() before rendering');
    const torch = effectiveTorch(this.prepared!.scene, this.settingsValue.torch);
    return {
      device: this.device, scene: resources, prepared: this.prepared!, view: this.view, camera, settings: this.settingsValue, targets, sceneSize: this.sceneSize(),
      ...(torch ? { torch } : {}), ...(timer ? { timer } : {}),
    };
  }

  /**
   * Adds `samples` paths per pixel over `tiles` (default: the whole image), one submit per tile so
   * that no single submit runs long enough to trip a GPU watchdog. Returns without waiting. With a
   * timer, each tile's pass is timed and the timestamps are resolved with the last tile.
   */
  accumulate(samples: number, tiles: readonly Tile[] = [this.fullImage()], timer?: GpuTimer): void {
    this.checkSamples(samples, 'dispatch');
    const frame = this.frameContext(timer);
    tiles.forEach((tile, i) => {
      const encoder = this.device.createCommandEncoder({ label: 'path trace' });
      this.progressive.encode(encoder, frame, tile, this.samples, samples);
      if (timer && i === tiles.length - 1) timer.resolve(encoder);
      this.device.queue.submit([encoder.finish()]);
    });
    this.samples += samples;
    this.shown = 'accumulation';
  }

  /**
   * Adds `samples` paths per pixel as a sequence of row bands, each submitted by SplitFrame.submitChunk
   * (the viewer awaits each; the CLI's long renders use accumulate with DispatchPlanner's tiles). The
   * samples count once the last band is submitted; an estimate reset meanwhile gives the frame up
   * (the reset cleared what its bands added).
   */
  beginAccumulate(samples: number, timer?: GpuTimer): SplitFrame {
    this.checkSamples(samples, 'dispatch');
    const work = this.progressive.begin(this.frameContext(timer), samples, this.samples);
    return this.split(work, samples, 'path trace', () => {
      this.samples += samples;
      this.shown = 'accumulation';
    });
  }

  /** Samples must be a positive whole number, and spectral paths (where they are traced: not by the hybrid recipe) compiled. */
  private checkSamples(samples: number, per: 'dispatch' | 'frame', tracesSpectral = true): void {
    this.ready();
    if (!Number.isInteger(samples) || samples < 1) throw new LanternError(`samples per ${per} must be a positive whole number, not ${samples}`);
    if (tracesSpectral && this.settingsValue.spectral && !this.spectralEnabled) throw new Error('Renderer: compile() before rendering with settings.spectral');
  }

  /** A SplitFrame driving a recipe's frame; `done` runs after the recipe's own once the last band is submitted. */
  private split(work: RecipeFrame, samples: number, label: string, done: () => void): SplitFrame {
    const { targets } = this.ready();
    return new SplitFrame(this, targets, samples, work.splittable, {
      band: (encoder, tile) => work.band(encoder, tile),
      finish: (encoder) => work.finish(encoder),
      done: () => {
        work.done();
        done();
      },
      abandon: () => work.abandon(),
    }, label);
  }

  /**
   * Compiles what the recipe of the settings (with `changes`; renderer/recipes/recipe.ts) runs, for
   * this and every later scene: the real-time chain with the wavefront integrator and ReSTIR where
   * asked, the hybrid recipe, the debug views, the spectral variants. Call it before the first frame
   * or sample of a recipe; nothing is compiled twice, and the progressive path tracer and the tone
   * mapper are compiled by create(). `intent.frames`: frames are asked for even with every filter
   * of the real-time chain off (the CLI's --frames).
   */
  async compile(changes: Partial<RenderSettings> = {}, intent: RecipeIntent = {}): Promise<void> {
    const wants = recipeCompiles({ ...this.settingsValue, ...changes }, intent);
    await Promise.all([wants.debugViews ? this.compileDebugViews() : undefined, wants.spectral ? this.compileSpectral() : undefined, wants.hybrid ? this.compileHybrid() : undefined]);
    if (wants.realTime) await this.compileRealTime(wants);
  }

  /** Compiles the spectral variants of the path tracers (settings.spectral) for this and every later scene; RGB rendering never compiles them. */
  private async compileSpectral(): Promise<void> {
    this.spectralEnabled = true;
    if (!this.prepared) return;
    const features = this.prepared.packed.features;
    await Promise.all([this.progressive.prepare(features, true), this.realTime?.prepare(features, true)]);
  }

  /** Compiles the real-time frame passes (path tracer with G-buffer, temporal, à-trous, output; the wavefront one and ReSTIR's where asked). */
  private async compileRealTime(wants: { readonly wavefront: boolean; readonly restir: boolean }): Promise<void> {
    const created = !this.realTime;
    this.realTime ??= await RealTimeRecipe.create(this.device, this.sceneFeatures);
    if (this.prepared) await Promise.all([this.realTime.prepare(this.prepared.packed.features), this.spectralEnabled ? this.realTime.prepare(this.prepared.packed.features, true) : undefined]);
    if (created) this.useSamplers();
    if (wants.wavefront) await this.compileWavefront();
    if (wants.restir) await this.compileRestir();
    await this.samplerPending;
    // Specialised kernels are compiled for every tracing pass at once (a compile under way lacks the
    // frame kernel): specialise again with it.
    if (created) this.invalidateSpecialisation();
  }

  /** The error of the last background compile of the wavefront path tracer, if it failed (frames stay on the megakernel). */
  wavefrontError?: unknown;
  /** The error of the last background compile of the ReSTIR passes, if it failed (frames keep one light sample per bounce). */
  restirError?: unknown;

  /** Compiles the ReSTIR passes (settings.restir) into the real-time chain. Until they are ready, frames run without them. */
  private async compileRestir(): Promise<void> {
    await this.realTime!.enableRestir();
    this.restirError = undefined;
  }

  /** Compiles the wavefront frame path tracer (settings.integrator = 'wavefront') into the real-time chain. Until it is ready, frames are traced by the megakernel. */
  private async compileWavefront(): Promise<void> {
    if (!this.realTime) throw new Error('Renderer: the real-time chain before its wavefront integrator');
    const created = !this.realTime.wavefrontPass;
    await this.realTime.enableWavefront();
    this.wavefrontError = undefined;
    // Specialised kernels are compiled for every tracing pass at once (one under way lacks the wavefront's): specialise again with it.
    if (created) this.invalidateSpecialisation();
  }

  /** Compiles the hybrid recipe's passes (raster, resolve, shade, GI, compose, TAA) for this and every later scene. */
  private async compileHybrid(): Promise<void> {
    this.hybrid ??= await HybridRecipe.create(this.device, this.sceneFeatures);
    if (this.prepared) await this.hybrid.prepare(this.prepared.packed.features);
  }

  /** Which path tracer traced the last real-time frame (settings.integrator, or the megakernel while the wavefront compiles). */
  get frameIntegrator(): Integrator {
    return this.realTime?.frameIntegrator ?? 'megakernel';
  }

  /** Bytes per pixel of the real-time denoising chain's buffers, each and in all (RealTimeRecipe.bufferSizes; empty until a frame). */
  get denoiserMemory(): { readonly bytesPerPixel: number; readonly buffers: readonly DenoiserBufferSize[] } {
    return { bytesPerPixel: this.realTime?.bytesPerPixel() ?? 0, buffers: this.realTime?.bufferSizes() ?? [] };
  }

  /** Bytes the wavefront path tracer's own buffers hold (path state and queues; 0 until it traced a frame). */
  get wavefrontBytes(): number {
    return this.realTime?.wavefrontAllocatedBytes ?? 0;
  }

  /**
   * The path tracing of one real-time frame alone, by settings.integrator: `samples` paths per pixel
   * with the random streams of frame `sampleIndex` (default 0), no filter, the history kept. With a
   * timer its passes are timed ('frame G-buffer', 'frame emission' and 'path trace (frame)' for the
   * megakernel; 'frame G-buffer', 'frame emission' and 'path trace (wavefront)' for the wavefront);
   * `breakdown` times the wavefront's stages apart instead (WavefrontFramePass.encode names them).
   * ReSTIR does not run here (RealTimeRecipe.encodeTraceOnly); renderFrame times its passes.
   * For timing the two integrators (bench) and comparing them (readFrameTrace). Returns which traced.
   */
  traceFrame(samples: number, options: { readonly sampleIndex?: number; readonly timer?: GpuTimer; readonly breakdown?: boolean } = {}): Integrator {
    if (!this.realTime) throw new Error('Renderer: compile() the real-time chain before traceFrame()');
    this.checkSamples(samples, 'frame');
    this.residency.settleBeforeFrame();
    const encoder = this.device.createCommandEncoder({ label: 'real-time frame path tracing' });
    const integrator = this.realTime.encodeTraceOnly(encoder, this.frameContext(options.timer), samples, options.sampleIndex ?? 0, options.breakdown ?? false);
    options.timer?.resolve(encoder);
    this.device.queue.submit([encoder.finish()]);
    return integrator;
  }

  /**
   * The raw output of the last traceFrame: demodulated radiance, G-buffer, guide, albedo, emission
   * (after renderFrame the radiance words hold the frame's output instead: the chain reuses them).
   * traceFrame overwrites the shown frame's output likewise.
   */
  readFrameTrace(): Promise<FrameTrace> {
    if (!this.realTime) throw new Error('Renderer: compile() the real-time chain before readFrameTrace()');
    return this.realTime.readTrace();
  }

  /**
   * One frame of the recipe the settings choose (renderer/recipes/recipe.ts recipeFor, frames asked
   * for): the real-time chain (`samples` paths per pixel, then temporal accumulation and the spatial
   * filter), the hybrid recipe, or a debug view alone (nothing traced), in one submit. The history
   * survives setCamera (it is reprojected) and setScene (changed pixels fail the G-buffer tests);
   * resize or resetHistory() drop it. With a timer, every pass is timed. present(), readImage() and
   * readFrame() show the result.
   */
  renderFrame(samples: number, timer?: GpuTimer): void {
    const frame = this.beginFrame(samples, timer);
    frame.submitChunk(frame.height);
  }

  /**
   * One frame (renderFrame) as a sequence of submissions: the path tracing in row bands, each
   * submitted by SplitFrame.submitChunk, the filters with the last band. Awaiting finish() between
   * bands keeps every submission short, so the page answers input, Pause and settings between them;
   * the frame adds up to exactly renderFrame's. The wavefront integrator and the hybrid recipe trace
   * whole frames: their frames have one band (splittable false).
   */
  beginFrame(samples: number, timer?: GpuTimer): SplitFrame {
    const recipe = this.frameRecipe();
    this.checkSamples(samples, 'frame', recipe === this.realTime);
    // A debug view that replaces the image is drawn by present() and readImage(): nothing to trace.
    if (!recipe) return this.split({ splittable: false, band: () => {}, finish: () => {}, done: () => {}, abandon: () => {} }, samples, 'frame', () => {});
    this.residency.settleBeforeFrame();
    const frame = this.frameContext(timer);
    const work = recipe.begin(frame, samples);
    return this.split({ ...work, finish: (encoder) => {
      work.finish(encoder);
      timer?.resolve(encoder);
    } }, samples, recipe === this.hybrid ? 'hybrid frame' : 'real-time frame', () => {
      this.lastFrame = recipe;
      this.shown = 'frame';
      this.residency.frameDone();
    });
  }

  /** The recipe a frame runs now (undefined: a debug view alone), compiled. */
  private frameRecipe(): FrameRecipe | undefined {
    const recipe = recipeFor(this.settingsValue, { frames: true });
    if (recipe === 'debug') return undefined;
    const compiled = recipe === 'hybrid' ? this.hybrid : this.realTime;
    if (!compiled) throw new Error(`Renderer: compile() the ${recipe} recipe before renderFrame()`);
    return compiled;
  }

  /** What SplitFrame checks before each band: the estimate, the history and the scene are those the frame began with. */
  frameGeneration(): string {
    return `${this.epoch} ${this.historyResets} ${this.residency.uploads}`;
  }

  /** Submits an encoder (SplitFrame's bands). */
  submit(encoder: GPUCommandEncoder): void {
    this.device.queue.submit([encoder.finish()]);
  }

  /** The targets in use (SplitFrame checks that a resize has not replaced them). */
  currentTargets(): object | undefined {
    return this.targets;
  }

  /**
   * Chooses what present() and readImage() show: the progressive estimate or the last real-time frame
   * (by default, whichever was rendered last). The viewer renders both while a still view converges.
   */
  show(image: 'accumulation' | 'frame'): void {
    if (image === 'frame' && !this.lastFrame?.output) throw new Error('Renderer: renderFrame() before show(\'frame\')');
    this.shown = image;
  }

  /** Drops the real-time history: the next frame starts from its own samples. */
  resetHistory(): void {
    this.historyResets++;
    this.realTime?.resetHistory();
    this.hybrid?.resetHistory();
  }

  /** The linear radiance of the last real-time frame (before tone mapping; a debug view if one is chosen). */
  async readFrame(): Promise<LinearImage> {
    const { targets } = this.ready();
    const output = this.lastFrame?.output;
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
    if (!this.presentPass) throw new Error('Renderer: a presentation format (create or setPresentationFormat) before present()');
    const encoder = this.device.createCommandEncoder({ label: 'present' });
    // What is presented is seen in real time: the exposure adapts over the wall-clock time since the last present.
    const now = performance.now();
    const seconds = this.lastPresentMs === undefined ? 0 : (now - this.lastPresentMs) / 1000;
    this.lastPresentMs = now;
    this.encodeTonemap(encoder, targets, seconds, timer);
    let shown = this.encodeDebugView(encoder, targets);
    if (this.selectionRange && this.selectionPass && this.resources) {
      shown = this.selectionPass.encode(encoder, { scene: this.resources, view: this.view, selection: this.selectionRange, image: shown, traceMask: this.selectionStale });
      this.selectionStale = false;
    }
    this.presentPass.encode(encoder, shown, target, timer);
    timer?.resolve(encoder);
    this.device.queue.submit([encoder.finish()]);
  }

  /** Compiles the present pipeline for targets of `format` (a canvas's; browser only: the CLI never draws to a surface). */
  async setPresentationFormat(format: GPUTextureFormat): Promise<void> {
    if (this.presentPass?.format !== format) this.presentPass = await PresentPass.create(this.device, format);
  }

  /** Compiles the debug views' pipelines (readImage does it by itself; present needs it done first). */
  private async compileDebugViews(): Promise<void> {
    this.debugViews ??= await DebugViews.create(this.device, this.sceneFeatures);
    if (this.prepared) await this.debugViews.prepare(this.prepared.packed.features);
  }

  /**
   * The tone-mapped sRGB image, RGBA8 row-major, top row first; with a debug view, composed with it.
   * With a timer, the exposure and tone map passes are timed (resolved here; read them after).
   */
  async readImage(timer?: GpuTimer): Promise<Uint8Array> {
    const { targets } = this.ready();
    if (this.settingsValue.debugView !== 'none') await this.compileDebugViews();
    if (this.exposureChoice.kind === 'auto') await this.compileAutoExposure();
    const encoder = this.device.createCommandEncoder({ label: 'tone map for readback' });
    this.encodeTonemap(encoder, targets, this.pendingExposureSeconds, timer);
    this.pendingExposureSeconds = 0;
    timer?.resolve(encoder);
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
    this.setIdleSpecialisation(undefined);
    this.invalidateSpecialisation();
    this.residency.destroy();
    this.destroyTargets();
    this.view.destroy();
    this.realTime?.destroy();
    this.realTime = undefined;
    this.hybrid?.destroy();
    this.hybrid = undefined;
    this.progressive.destroy();
    this.tonemap.destroy();
    this.destroyed = true;
    this.exposure?.destroy();
    this.debugViews?.destroy();
    this.selectionPass?.destroy();
    void this.tracePass?.then((p) => p.destroy());
  }

  /** For passes outside the facade (benchmarks, tests): the scene's GPU resources and the view. */
  internals(): { resources: SceneResources; view: ViewUniform } {
    const { resources } = this.ready();
    return { resources, view: this.view };
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
    if (!(seconds >= 0) || !Number.isFinite(seconds)) throw new Error(`Renderer.advanceExposure: ${seconds} is not a duration in seconds`);
    this.pendingExposureSeconds += seconds;
  }

  /** The automatic exposure as the last tone map left it: the image's log-average luminance (log2) and the exposure (stops). */
  readExposure(): Promise<ExposureReading> {
    if (!this.exposure) throw new Error('Renderer: no image has been exposed automatically yet');
    return this.exposure.read();
  }

  /**
   * Compiles the automatic exposure's two kernels, once. Scenes and settings that never ask for
   * automatic exposure never compile them (start-up compiles only what the first image runs).
   */
  private compileAutoExposure(): Promise<ExposurePass> {
    this.exposureCompile ??= ExposurePass.create(this.device).then((pass) => {
      if (this.destroyed) pass.destroy();
      else this.exposure = pass;
      return pass;
    });
    return this.exposureCompile;
  }

  private encodeTonemap(encoder: GPUCommandEncoder, targets: ImageTargets, seconds: number, timer?: GpuTimer): void {
    const s = this.settingsValue;
    const frame = this.shown === 'frame' ? this.lastFrame?.output : undefined;
    // Debug views of a recipe are shown as computed: no exposure, no tone curve.
    const debug = frame !== undefined && this.lastFrame!.showsRawValues({ settings: s });
    const radiance = frame ?? targets.accumulation;
    const sampleCount = frame ? 1 : this.samples;
    let choice = this.exposureChoice;
    // Until its kernels are compiled (compileAutoExposure, under way), the image keeps the scene's own exposure.
    if (choice.kind === 'auto' && !this.exposure) choice = { kind: 'manual', stops: this.cameraValue?.exposureStops ?? 0 };
    const pass = this.exposure;
    let exposure: { exposureStops: number; autoExposure?: GPUBuffer };
    if (debug) exposure = { exposureStops: 0 };
    else if (choice.kind === 'manual') exposure = { exposureStops: choice.stops };
    // No samples yet: a black image, and nothing to adapt to.
    else if (sampleCount === 0) exposure = { exposureStops: 0 };
    else {
      const keep = this.exposureAdapted ? adaptationKeep(seconds, choice.adaptationSeconds) : 0;
      pass!.encode(encoder, this.view, radiance, targets.width, targets.height, { sampleCount, keep, compensationStops: choice.compensationStops }, timer);
      this.exposureAdapted = true;
      exposure = { exposureStops: 0, autoExposure: pass!.state };
    }
    // A manual exposure between automatic ones: the eye adapts afresh when automatic comes back.
    if (choice.kind === 'manual') this.exposureAdapted = false;
    this.tonemap.encode(encoder, this.view, radiance, targets.output, { ...exposure, toneMapper: debug ? 'linear' : s.toneMapper, sampleCount }, timer);
  }

  /** Encodes the debug view when one is set and returns the image to show: the composed one, or the tone-mapped one. */
  private encodeDebugView(encoder: GPUCommandEncoder, targets: ImageTargets): GPUTexture {
    const settings = this.settingsValue;
    if (settings.debugView === 'none') return targets.output;
    if (!this.debugViews) throw new Error('Renderer: compile() the debug views before showing one');
    return this.debugViews.encode(encoder, { prepared: this.prepared!, resources: this.resources!, view: this.view, image: targets.output, settings });
  }

  /** Runs the current debug view once (a debug view must be set) and waits for it. */
  private async renderDebugView(): Promise<void> {
    const { targets } = this.ready();
    if (this.settingsValue.debugView === 'none') throw new Error("Renderer: set a debugView other than 'none' first");
    await this.compileDebugViews();
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
    this.selectionStale = true;
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

/** A miss in a HitRecord (shaders/scene/types.wgsl NO_TRIANGLE). */
const NO_PRIMITIVE = 0xffffffff;

const unpackHitsSize = () => rayBufferStrides().hit;

function cameraForward(camera: Camera): Vec3 {
  const [x, y, z] = camera.forward;
  const len = Math.hypot(x, y, z);
  return [x / len, y / len, z / len];
}
