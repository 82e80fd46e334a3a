/**
 * The page's render loop around the shared Renderer. It acquires the GPU on the first Play, then runs
 * one frame per animation frame, with at most one frame in flight, so a slow GPU (or SwiftShader)
 * never piles up work. Each frame:
 *
 *   camera input and the world's time (frame-clock.ts) → samples (path trace) → tone map + present →
 *   ray counters and pass timings read back
 *
 * It owns everything the page must survive: a canvas resize, a tab in the background (no frames
 * while hidden), a lost GPU device (a new device, the scene uploaded again, the view restored), and
 * scene switches (the Renderer destroys what the old scene held; the GPU resource count shows it).
 *
 * Live editing: select(x, y) picks the object under a canvas point (one primary ray, Renderer.pick)
 * and outlines it; editMaterial(index, edit) changes a material in place, applied before the next
 * frame (edits arriving faster than frames are merged); focusAt(x, y) sets the lens's focus
 * distance to the picked depth. The edits are kept for links (viewParams) and survive a lost device.
 *
 * Beside it: viewer-frames (the frame loop: plan, chunks, present, measure), viewer-device (the GPU
 * acquired and its losses), viewer-edits, viewer-scene, viewer-output, viewer-types (public types).
 */
import { LanternError } from '../errors.ts';
import type { GpuContext } from '../gpu/device.ts';
import type { CompileProgress } from '../gpu/pipeline-compiles.ts';
import { checkSceneFits } from '../gpu/scene-limits.ts';
import type { GpuTimer } from '../gpu/timestamps.ts';
import type { PickResult, Renderer } from '../renderer/renderer.ts';
import { ChunkSizer, describeFixedScale, FrameBudget } from './frame-budget.ts';
import { editMaterials, withPreparedEnvironment } from '../renderer/prepare.ts';
import type { MaterialEdit } from '../scene/material-edit.ts';
import type { MaterialOverride } from './material-link.ts';
import type { DebugLegend } from '../renderer/debug-legend.ts';
import { ESTIMATE_SETTINGS, type RenderSettings } from '../renderer/settings.ts';
import { newlyCompiled, recipeFor } from '../renderer/recipes/recipe.ts';
import type { CameraController, MoveMode } from './camera-controller.ts';
import { playFrame } from './frame-clock.ts';
import type { LoadedScene } from './scene-request.ts';
import type { Environment } from '../scene/environment.ts';
import { lensProblem } from '../scene/lens.ts';
import { World } from '../world/world.ts';
import type { Camera, ThinLens } from '../scene/types.ts';
import type { ViewParams } from './view-params.ts';
import { DeviceLosses, MAX_DEVICE_LOSSES_PER_MINUTE, openDevice, PipelineLog } from './viewer-device.ts';
import { imagePoint, MaterialEdits, overrideProblem } from './viewer-edits.ts';
import { ViewerFrames } from './viewer-frames.ts';
import { exrOf, imageOf, pngOf, viewParamsOf } from './viewer-output.ts';
import { defaultFocus, NO_ENVIRONMENT, sceneController } from './viewer-scene.ts';
import type { BackendChoice } from './backend-choice.ts';
import { WebGl2Frames } from './viewer-webgl2.ts';
import type { WebGl2Tracer } from '../webgl2/webgl2-tracer.ts';
import { accumulationEstimate } from '../renderer/image-readback.ts';
import { DEFAULT_VIEWER_SETTINGS, describeError, idleInput, type BudgetState, type FrameProgress, type SceneView, type ViewerInput, type ViewerSettings, type ViewerState, type ViewerStats } from './viewer-types.ts';

// The viewer's types and defaults (viewer-types.ts), for the page's modules that import the Viewer.

export interface ViewerHooks {
  /** Anything shown changed (state, stats, scene). */
  onChange(viewer: Viewer): void;
  /** A message for the user; 'error' stays until the next message. */
  onMessage(text: string, kind: 'info' | 'warning' | 'error'): void;
}

export class Viewer {
  state: ViewerState = 'idle';
  /** Why the viewer stopped, when state is 'failed'. */
  failure: unknown;
  settings: ViewerSettings = DEFAULT_VIEWER_SETTINGS;
  /** Where movement input comes from (the page's keyboard and mouse; tests may replace it). */
  input: ViewerInput = idleInput();

  private loaded?: LoadedScene;
  private controllerValue?: CameraController;
  /** What moves in the scene (doors, lifts, ...), or undefined for a frozen scene. */
  private world?: World;
  private gpu?: GpuContext;
  private renderer?: Renderer;
  private context?: GPUCanvasContext;
  private timer?: GpuTimer;
  private settingsQueue: Promise<void> = Promise.resolve();
  /** What lights every scene instead of its own (the panel's Environment folder, a link's sky); undefined: the scene's own. */
  private environmentOverride?: Environment;
  /** The loaded scene's own environment, for going back to it. */
  private sceneEnvironment?: Environment;
  private readonly losses = new DeviceLosses();
  /** The device's pipeline compiles: the batch as last reported, every pipeline requested. */
  private readonly pipelineLog = new PipelineLog();
  /** What a settings change under way compiles for ('the hybrid recipe'), while it waits; frames go on with the settings before it. */
  private compilingForValue?: string;
  private disposed = false;
  /** What a click selected (the part of an instance of one material), until Esc, an empty click or another scene. */
  private selectionValue?: PickResult;
  /** Every material edit since the scene loaded, and those not applied yet. */
  private readonly edits = new MaterialEdits();
  /** Chooses the scale and samples per frame from measured frames, until the user fixes the resolution (made at start). */
  private budgetValue?: FrameBudget;
  /** Whether the user fixed the resolution (the panel's scale, a `scale=` link parameter): the budget is then off. */
  private scaleFixed = false;
  /** The frame under way, its chunks, and what the frames measured (rates, legend, the first frame's wait). */
  private readonly frames = new ViewerFrames({
    renderer: () => this.renderer,
    context: () => this.context,
    timer: () => this.timer,
    settings: () => this.settings,
    samplesPerFrame: () => this.samplesPerFrame(),
    budget: () => (this.scaleFixed ? undefined : this.budgetValue),
    delayMs: () => this.frameDelayMs,
    playing: () => this.state === 'playing',
    hasScene: () => this.loaded !== undefined,
    restartClock: () => this.input.restartClock(performance.now()),
    applyBudget: () => this.applyBudget(),
    advance: (renderer) => this.advance(renderer),
    fail: (error) => this.fail(error),
    changed: () => this.hooks.onChange(this),
  });
  /** Test hook (window.lantern.delayFrames): milliseconds each frame waits after its GPU work, a deterministically slow adapter. */
  frameDelayMs = 0;
  /** The backend the page chose (backend-choice.ts), set before the first Play: WebGPU, or WebGL2 with its reason. */
  backend: BackendChoice = { kind: 'webgpu' };
  /** The WebGL2 backend's frames and tracer (backend 'webgl2' only). */
  readonly webgl2 = new WebGl2Frames({
    playing: () => this.state === 'playing',
    advance: (tracer) => this.advanceWebGl2(tracer),
    samplesPerFrame: () => this.settings.samplesPerFrame,
    accumulate: () => this.settings.accumulate,
    fail: (error) => this.fail(error),
    changed: () => this.hooks.onChange(this),
  });

  constructor(
    private readonly canvas: HTMLCanvasElement,
    private readonly hooks: ViewerHooks,
  ) {
    document.addEventListener('visibilitychange', () => {
      // Hidden tabs get no frames; coming back resumes where it was, and the time hidden is not
      // played (a frame asked for before hiding runs only now: its time starts here).
      if (!document.hidden) this.input.restartClock(performance.now());
      if (!document.hidden && this.state === 'playing') {
        if (this.backend.kind === 'webgl2') this.webgl2.loop();
        else this.frames.loop();
      }
      this.hooks.onChange(this);
    });
  }

  get controller(): CameraController | undefined {
    return this.controllerValue;
  }

  /**
   * The use key (E, or Space when walking): opens the door or starts the lift in front of the
   * camera (world/movers.ts). True when something answered; it moves in the following frames.
   */
  use(): boolean {
    const c = this.controllerValue;
    if (!c || !this.world) return false;
    const camera = c.camera();
    return this.world.use({ position: camera.position, forward: camera.forward, walking: c.mode === 'walk' });
  }

  get scene(): LoadedScene | undefined {
    return this.loaded;
  }

  /** The current debug view's legend (label and colour scale), while one is shown. */
  get legend(): DebugLegend | undefined {
    return this.settings.render.debugView === 'none' ? undefined : this.frames.legend;
  }

  /** Depth of the scene's deepest BVH node (the wireframe depth's upper bound). */
  get bvhMaxDepth(): number {
    return this.loaded?.prepared.bvh.stats.maxDepth ?? 0;
  }

  get stats(): ViewerStats {
    const packed = this.loaded?.prepared.packed.counts;
    const tracer = this.webgl2.tracer;
    if (this.backend.kind === 'webgl2') {
      return {
        samples: tracer?.sampleCount ?? 0,
        display: 'progressive',
        framesPerSecond: this.webgl2.framesPerSecond,
        frameMs: this.webgl2.frameMs,
        gpuPasses: [],
        raysPerSecond: 0,
        width: tracer?.width ?? 0,
        height: tracer?.height ?? 0,
        triangles: packed?.triangles ?? 0,
        bvhNodes: this.loaded ? this.loaded.prepared.bvh.stats.nodeCount : 0,
        sceneName: this.loaded?.prepared.scene.name ?? '',
        adapter: tracer?.renderer.ctx.rendererName ?? '',
        gpuResources: { buffers: 0, textures: 0, bytes: 0 },
        kernel: 'generic',
        firstFrameMs: this.webgl2.firstFrameMs,
        budget: this.budgetText(),
      };
    }
    return {
      ...this.frames.readings(this.samplesPerFrame()),
      width: this.renderer?.width ?? 0,
      height: this.renderer?.height ?? 0,
      triangles: packed?.triangles ?? 0,
      bvhNodes: this.loaded ? this.loaded.prepared.bvh.stats.nodeCount : 0,
      sceneName: this.loaded?.prepared.scene.name ?? '',
      adapter: this.gpu?.adapterName ?? '',
      gpuResources: this.gpu?.resources.count ?? { buffers: 0, textures: 0, bytes: 0 },
      kernel: this.renderer?.kernel ?? 'generic',
      firstFrameMs: this.frames.firstFrameMs,
      budget: this.budgetText(),
    };
  }

  /**
   * The budget's account. `short`: for the status line, without the last frame's time (so it changes
   * only with the choice), and empty with the budget off (the fixed scale shows in the image size):
   * the header wraps, and a longer line changes the canvas's size and aspect, and with it the image.
   */
  budgetText(short = false): string {
    // The WebGL2 frames keep the scale they were given: no budget measures them.
    if (this.scaleFixed || this.backend.kind === 'webgl2') return short ? '' : describeFixedScale(this.settings.scale);
    if (!this.budgetValue) return 'budget: measuring the GPU at the first frames';
    return this.budgetValue.describe(!short);
  }

  /**
   * The pipeline compiles of the viewer's device: the batch under way (done < needed) or the last one.
   * Start-up, a scene whose variants are new, a recipe switched to, ReSTIR and the wavefront
   * integrator in the background all compile in batches; the page shows what it waits for.
   */
  get compiles(): CompileProgress | undefined {
    return this.pipelineLog.compiles;
  }

  /** Every pipeline requested on the current device (label and override constants), in request order: what a page compiled. */
  get pipelines(): readonly string[] {
    return this.pipelineLog.pipelines;
  }

  /** What the settings change under way compiles for ('the hybrid recipe'), while the frames go on with the previous settings. */
  get compilingFor(): string | undefined {
    return this.compilingForValue;
  }

  /** Whether the viewer has been played and waits for its first frame on screen (the GPU starting, pipelines compiling, the frame). */
  get awaitingFirstFrame(): boolean {
    if (this.backend.kind === 'webgl2') return this.webgl2.playedAt !== undefined && this.webgl2.firstFrameMs === undefined && (this.state === 'starting' || this.state === 'playing');
    return this.frames.playedAt !== undefined && this.frames.firstFrameMs === undefined && (this.state === 'starting' || this.state === 'playing');
  }

  /** The frame budget: on or off, the scale that renders (its choice, or the user's), its one-line account. */
  get budget(): BudgetState {
    return { on: !this.scaleFixed, scale: this.settings.scale, samplesPerFrame: this.samplesPerFrame(), text: this.budgetText() };
  }

  /** How far the frame under way has got (undefined between frames). */
  get frameProgress(): FrameProgress | undefined {
    return this.frames.progress(this.state !== 'playing');
  }

  /** Hands the resolution back to the frame budget (the user had fixed it); a link then carries no scale. */
  async useFrameBudget(): Promise<void> {
    if (!this.scaleFixed) return;
    this.scaleFixed = false;
    await this.resizeRenderer();
    this.hooks.onChange(this);
  }

  /** The samples per frame in use: the budget's choice (never below the user's) while it is on. */
  private samplesPerFrame(): number {
    return !this.scaleFixed && this.budgetValue ? this.budgetValue.choice.samplesPerFrame : this.settings.samplesPerFrame;
  }

  /** Starts (acquiring the GPU on first use) or resumes. */
  async play(): Promise<void> {
    if (this.state === 'playing' || this.state === 'starting' || this.state === 'failed') return;
    if (this.backend.kind === 'webgl2') {
      if (!this.webgl2.tracer) {
        this.webgl2.playedAt ??= performance.now();
        this.setState('starting');
        await this.startWebGl2();
      }
      this.setState('playing');
      this.webgl2.loop();
      return;
    }
    if (!this.renderer) {
      this.frames.playedAt ??= performance.now();
      this.setState('starting');
      await this.start();
    }
    this.setState('playing');
    this.frames.loop();
  }

  pause(): void {
    if (this.state === 'playing') this.setState('paused');
  }

  /**
   * Shows a loaded scene; before the first Play only remembers it (no GPU work). The torch keeps
   * only on/off: its other settings belong to the previous scene.
   */
  setScene(loaded: LoadedScene, view: SceneView = {}): Promise<void> {
    // In line with settings and environment changes, so that an environment upload still under way
    // cannot land on top of the new scene.
    return this.enqueue(() => this.applyScene(loaded, view));
  }

  private async applyScene(given: LoadedScene, view: SceneView): Promise<void> {
    const loaded = this.environmentOverride ? { ...given, prepared: withPreparedEnvironment(given.prepared, this.environmentOverride) } : given;
    // A scene too large for this GPU is refused before anything of the shown one changes (the page keeps it).
    if (this.renderer) checkSceneFits(loaded.prepared.packed, this.renderer.device.limits, loaded.prepared.scene.name);
    this.sceneEnvironment = given.prepared.scene.environment;
    const controller = sceneController(loaded.prepared, view);
    // Torch colour, intensity and range set for the last scene mean nothing in this one's units:
    // only on/off carries over.
    this.settings = { ...this.settings, render: { ...this.settings.render, torch: { enabled: this.settings.render.torch.enabled } } };
    const tracer = this.webgl2.tracer;
    if (tracer) {
      tracer.updateSettings(this.settings.render);
      await this.webgl2.compilingWhile('the WebGL2 path tracer', () => tracer.setScene(loaded.prepared));
      tracer.setCamera(this.cameraOf(controller));
    }
    if (this.renderer) {
      this.renderer.updateSettings(this.settings.render);
      await this.renderer.setScene(loaded.prepared);
      // The controller starts from this scene's camera, exposure included.
      this.renderer.setCamera(controller.camera());
      this.renderer.resetHistory();
    }
    this.frames.realTimeFrames = 0;
    this.loaded = loaded;
    this.controllerValue = controller;
    this.world = World.of(loaded.prepared.scene);
    this.selectionValue = undefined;
    this.edits.clear();
    this.frames.resetRates();
    this.hooks.onChange(this);
  }

  /** Applies settings; whatever changes the estimate restarts accumulation. */
  updateSettings(changes: Partial<Omit<ViewerSettings, 'render'>> & { render?: Partial<RenderSettings> }): Promise<void> {
    return this.enqueue(() => this.applySettings(changes));
  }

  /** The environment that replaces every scene's own, or undefined while scenes keep theirs. */
  get environment(): Environment | undefined {
    return this.environmentOverride;
  }

  /**
   * Relights the current scene (and the ones loaded after it) without reloading it: the scene is
   * packed again around the same BVH and the image restarts. `undefined` goes back to the scene's own.
   * A slider sends many changes: each waits its turn, and those overtaken by a later one do nothing.
   */
  setEnvironment(environment: Environment | undefined): Promise<void> {
    this.environmentOverride = environment;
    return this.enqueue(() => this.applyEnvironment());
  }

  private async applyEnvironment(): Promise<void> {
    const loaded = this.loaded;
    if (!loaded) return;
    const wanted = this.environmentOverride ?? this.sceneEnvironment ?? NO_ENVIRONMENT;
    if ((loaded.prepared.scene.environment ?? NO_ENVIRONMENT) === wanted) return;
    const prepared = this.renderer ? await this.renderer.setEnvironment(wanted) : withPreparedEnvironment(loaded.prepared, wanted);
    this.loaded = { ...loaded, prepared };
    this.frames.realTimeFrames = 0;
    if (this.renderer) {
      // The sky moves the exposure by the daylight stops: the camera takes the scene's new exposure.
      if (this.controllerValue) this.renderer.setCamera(this.cameraOf(this.controllerValue));
      this.renderer.resetHistory();
    }
    this.hooks.onChange(this);
  }

  /** What is selected (a pick: instance, material, primitive, hit point), if anything. */
  get selection(): PickResult | undefined {
    return this.selectionValue;
  }

  /** The pick under a canvas point (CSS pixels), in line with other changes; undefined before Play or off the image. */
  pickAt(x: number, y: number): Promise<PickResult | null | undefined> {
    return this.enqueue(() => this.pickNow(x, y));
  }

  private async pickNow(x: number, y: number): Promise<PickResult | null | undefined> {
    const p = imagePoint(this.canvas, this.renderer, x, y);
    if (!p || !this.renderer || !this.loaded) return undefined;
    return this.renderer.pick(p[0], p[1]);
  }

  /** Selects what lies under a canvas point (CSS pixels); empty space deselects. Pick and selection are one change, so no scene switch comes between. */
  select(x: number, y: number): Promise<PickResult | undefined> {
    return this.enqueue(async () => {
      const pick = await this.pickNow(x, y);
      if (pick === undefined) return undefined;
      await this.applySelection(pick ?? undefined);
      return pick ?? undefined;
    });
  }

  deselect(): Promise<void> {
    return this.enqueue(() => this.applySelection(undefined));
  }

  private async applySelection(pick: PickResult | undefined): Promise<void> {
    this.selectionValue = pick;
    await this.renderer?.setSelection(pick ? { instanceIndex: pick.instanceIndex, material: pick.material } : undefined);
    this.hooks.onChange(this);
  }

  /**
   * Focuses the lens on what lies under a canvas point: the focus distance becomes the picked depth
   * along forward (setFocusDistance: a pinhole gets a closed lens that keeps it for when the aperture
   * opens). Returns the depth, or undefined for empty space or before Play.
   */
  focusAt(x: number, y: number): Promise<number | undefined> {
    return this.enqueue(async () => {
      const pick = await this.pickNow(x, y);
      if (!pick || !this.controllerValue || !(pick.depth > 0)) return undefined;
      this.setFocusDistance(pick.depth);
      return pick.depth;
    });
  }

  /**
   * Edits a material (by index into the scene's materials) in place: applied before the next frame
   * with a buffer write (Renderer.updateMaterials), restarting the image. Edits arriving faster are
   * merged. A field the material's kind lacks or a value out of range is a LanternError.
   */
  editMaterial(index: number, edit: MaterialEdit): Promise<void> {
    const problem = this.edits.add(this.loaded?.prepared.scene.materials, index, edit);
    if (problem) return Promise.reject(problem);
    return this.enqueue(() => this.applyPendingEdits());
  }

  /**
   * Applies the material edits a link carries (after its scene has loaded); returns what could not
   * be applied, in words (a material index the scene lacks, another name at that index, a field the
   * kind lacks), for the page's warning line.
   */
  async applyMaterialOverrides(overrides: readonly MaterialOverride[]): Promise<string[]> {
    const problems: string[] = [];
    const materials = this.loaded?.prepared.scene.materials ?? [];
    for (const o of overrides) {
      const problem = overrideProblem(materials, o);
      if (problem) problems.push(`material edit ${o.index} (${o.name}): ${problem}`);
      else await this.editMaterial(o.index, o.edit);
    }
    return problems;
  }

  /** The material edits made since the scene loaded, for links. */
  get materialOverrides(): MaterialOverride[] {
    return this.edits.overrides(this.loaded?.prepared.scene.materials ?? []);
  }

  private async applyPendingEdits(): Promise<void> {
    const loaded = this.loaded;
    const edits = loaded && this.edits.takePending();
    if (!loaded || !edits) return;
    const prepared = this.renderer ? this.renderer.updateMaterials(edits) : editMaterials(loaded.prepared, edits).prepared;
    this.loaded = { ...loaded, prepared };
    this.frames.realTimeFrames = 0;
    this.renderer?.resetHistory();
    this.hooks.onChange(this);
  }

  /** One change at a time, in order: a change may wait for pipelines to compile or a scene to upload. */
  private enqueue<T>(change: () => Promise<T>): Promise<T> {
    const next = this.settingsQueue.then(change);
    this.settingsQueue = next.then(
      () => {},
      () => {},
    );
    return next;
  }

  /** The controller's camera with the current scene's exposure (which an environment change may move). */
  private cameraOf(controller: CameraController): Camera {
    const camera = controller.camera();
    const exposureStops = this.loaded?.prepared.scene.camera.exposureStops;
    return exposureStops === undefined ? camera : { ...camera, exposureStops };
  }

  private async applySettings(changes: Partial<Omit<ViewerSettings, 'render'>> & { render?: Partial<RenderSettings> }): Promise<void> {
    const before = this.settings;
    const render = { ...before.render, ...changes.render };
    const next = { ...before, ...changes, render };
    // Compile what the new settings need before the frame loop sees them: until then frames go on
    // with the settings as they were, so the image keeps coming (the page says what compiles).
    this.compilingForValue = this.renderer ? newlyCompiled(before.render, render) : undefined;
    if (this.compilingForValue) this.hooks.onChange(this);
    try {
      await this.renderer?.compile(render);
    } finally {
      this.compilingForValue = undefined;
    }
    this.settings = next;
    // A scale given (the panel, a link) fixes the resolution: the budget is off from then on.
    const fixing = changes.scale !== undefined && !this.scaleFixed;
    if (fixing) this.scaleFixed = true;
    this.frames.legendAt = 0;
    const restart = ESTIMATE_SETTINGS.some((k) => render[k] !== before.render[k]) || recipeFor(render) !== recipeFor(before.render);
    if (restart) this.frames.realTimeFrames = 0;
    const tracer = this.webgl2.tracer;
    if (tracer) {
      tracer.updateSettings(render);
      if (next.scale !== before.scale || fixing) await this.resizeRenderer();
      if (next.accumulate !== before.accumulate || next.samplesPerFrame !== before.samplesPerFrame) tracer.resetAccumulation();
      this.hooks.onChange(this);
      return;
    }
    if (!this.renderer) return;
    this.renderer.updateSettings(render);
    if (restart) this.renderer.resetHistory();
    if (next.scale !== before.scale || fixing) await this.resizeRenderer();
    if (next.samplesPerFrame !== before.samplesPerFrame) this.budgetValue?.setBaseSamples(next.samplesPerFrame);
    if (next.accumulate !== before.accumulate || next.samplesPerFrame !== before.samplesPerFrame) this.renderer.resetAccumulation();
    this.hooks.onChange(this);
  }

  /** The camera's thin lens (undefined: a pinhole). */
  get lens(): ThinLens | undefined {
    return this.controllerValue?.lens;
  }

  /**
   * Sets the camera's thin lens (undefined: a pinhole; an aperture of 0 is a pinhole that keeps its
   * focus distance). The image restarts, the real-time history too (a refocus changes every pixel).
   * Throws a LanternError for a negative aperture or a focus distance ≤ 0.
   */
  setLens(lens: ThinLens | undefined): void {
    const c = this.controllerValue;
    if (!c) return;
    const problem = lens && lensProblem(lens);
    if (problem) throw new LanternError(problem);
    c.lens = lens;
    this.frames.realTimeFrames = 0;
    this.webgl2.tracer?.setCamera(this.cameraOf(c));
    if (this.renderer) {
      this.renderer.setCamera(this.cameraOf(c));
      this.renderer.resetHistory();
    }
    this.hooks.onChange(this);
  }

  /**
   * Focuses at `depth` scene units along the viewing direction, keeping the aperture (a pinhole
   * gets a closed lens that remembers the distance for when the aperture opens). Click-to-focus:
   * `viewer.setFocusDistance(pick.depth)` with the picked point's depth along forward.
   */
  setFocusDistance(depth: number): void {
    this.setLens({ apertureRadius: this.lens?.apertureRadius ?? 0, focusDistance: depth });
  }

  /** Where a lens opened without a focus distance focuses: the depth at the image centre (CPU BVH), else half the scene's size. */
  defaultFocusDistance(): number | undefined {
    const c = this.controllerValue;
    return this.loaded && c ? defaultFocus(this.loaded.prepared, c.camera()) : undefined;
  }

  setFieldOfView(degrees: number): void {
    if (!this.controllerValue) return;
    this.controllerValue.vfovDegrees = degrees;
    this.renderer?.setCamera(this.cameraOf(this.controllerValue));
    this.webgl2.tracer?.setCamera(this.cameraOf(this.controllerValue));
  }

  setMoveMode(mode: MoveMode): boolean {
    const ok = this.controllerValue?.setMode(mode) ?? false;
    if (ok && this.controllerValue) this.renderer?.setCamera(this.cameraOf(this.controllerValue));
    if (ok && this.controllerValue) this.webgl2.tracer?.setCamera(this.cameraOf(this.controllerValue));
    return ok;
  }

  /** The canvas's new size in device pixels (the page watches its layout). */
  async resizeCanvas(width: number, height: number): Promise<void> {
    if (this.canvas.width === width && this.canvas.height === height) return;
    this.canvas.width = width;
    this.canvas.height = height;
    this.budgetValue?.resizeCanvas(width, height);
    await this.resizeRenderer();
  }

  /** The tone-mapped image as PNG bytes. */
  async screenshotPng(): Promise<Uint8Array> {
    await this.frameComplete();
    return pngOf(this.requireRenderer());
  }

  /** The tone-mapped image (RGBA8, what a screenshot holds) with the sample count at the moment it was read (the test hook). */
  async readImage(): Promise<{ samples: number; width: number; height: number; rgba: number[] }> {
    const tracer = this.webgl2.tracer;
    if (tracer) return { samples: tracer.sampleCount, width: tracer.width, height: tracer.height, rgba: Array.from(tracer.readImage()) };
    await this.frameComplete();
    return imageOf(this.requireRenderer(), this.stats.samples);
  }

  /**
   * The progressive estimate's mean radiance (RGB floats a pixel, top row first) with its sample
   * count, read at one moment: the test hook's way to compare the backends' images.
   */
  async readRadiance(): Promise<{ samples: number; width: number; height: number; rgb: number[] }> {
    const tracer = this.webgl2.tracer;
    if (tracer) {
      const a = accumulationEstimate(tracer.readAccumulation(), tracer.width, tracer.height, tracer.sampleCount);
      return { samples: a.samples, width: a.width, height: a.height, rgb: Array.from(a.radiance) };
    }
    await this.frameComplete();
    const a = await this.requireRenderer().readAccumulation();
    return { samples: a.samples, width: a.width, height: a.height, rgb: Array.from(a.radiance) };
  }

  /** The linear radiance (the estimate, or the denoised frame) as EXR bytes: float32 RGB, before exposure and tone mapping. */
  async radianceExr(): Promise<Uint8Array> {
    await this.frameComplete();
    return exrOf(this.requireRenderer(), this.frames.displaying === 'frame' && this.frames.realTimeFrames > 0);
  }

  /** The camera and settings as URL parameters (the page adds the scene's location). */
  viewParams(): ViewParams {
    const materials = this.edits.size > 0 ? this.materialOverrides : undefined;
    return viewParamsOf({ controller: this.controllerValue, settings: this.settings, scaleFixed: this.scaleFixed, environment: this.environmentOverride, materials });
  }

  /** Shows an error and stops; the page stays usable for reading the message and choosing again. */
  fail(error: unknown): void {
    console.error(error);
    this.failure = error;
    this.setState('failed');
    this.hooks.onMessage(describeError(error), 'error');
  }

  /** Test hook: loses the GPU device the way a driver reset would. */
  simulateDeviceLoss(): void {
    if (!this.gpu) return;
    this.losses.expect();
    this.gpu.device.destroy();
  }

  destroy(): void {
    this.disposed = true;
    this.timer?.destroy();
    this.renderer?.destroy();
    this.gpu?.device.destroy();
    this.webgl2.tracer?.destroy();
  }

  /** Opens WebGL2 (viewer-webgl2.ts) and fills it: the size, the scene (compiling the tracer), the camera. */
  private async startWebGl2(): Promise<void> {
    const tracer = await this.webgl2.open(this.canvas, this.settings.render);
    await this.resizeRenderer();
    const loaded = this.loaded;
    if (loaded) await this.webgl2.compilingWhile('the WebGL2 path tracer', () => tracer.setScene(loaded.prepared));
    if (this.controllerValue) tracer.setCamera(this.cameraOf(this.controllerValue));
  }

  /** Before a WebGL2 frame: camera input moved through the frame's time. The world does not play there (its updates are WebGPU uploads). */
  private advanceWebGl2(tracer: WebGl2Tracer): void {
    const c = this.controllerValue;
    if (!c || !this.loaded) return;
    const [lx, ly] = this.input.takeLook();
    if (lx !== 0 || ly !== 0) c.look(lx, ly);
    const played = playFrame(c, undefined, this.input.takeHeld(performance.now()), false);
    if (played.moved || lx !== 0 || ly !== 0) tracer.setCamera(this.cameraOf(c));
  }

  /** Acquires the GPU (viewer-device.ts openDevice), then fills it: the budget for its adapter, the size, the scene, the camera, the selection. */
  private async start(): Promise<void> {
    const { gpu, context, renderer, timer, displayHz, adapter } = await openDevice(this.canvas, () => ({ render: this.settings.render, loaded: this.loaded }), this.pipelineLog, () => this.hooks.onChange(this));
    this.frames.realTimeFrames = 0;
    renderer.updateSettings(this.settings.render);
    this.gpu = gpu;
    this.context = context;
    this.renderer = renderer;
    this.timer = timer;
    this.budgetValue = new FrameBudget({ adapter, displayHz, canvasWidth: Math.max(1, this.canvas.width), canvasHeight: Math.max(1, this.canvas.height), baseSamples: this.settings.samplesPerFrame });
    this.frames.chunks = new ChunkSizer(adapter);
    this.frames.current = undefined;
    await this.resizeRenderer();
    if (this.loaded) await renderer.setScene(this.loaded.prepared);
    if (this.controllerValue) renderer.setCamera(this.cameraOf(this.controllerValue));
    const selected = this.selectionValue;
    if (selected) await renderer.setSelection({ instanceIndex: selected.instanceIndex, material: selected.material });
    void gpu.lost.then((info) => this.onDeviceLost(gpu, info));
  }

  private async onDeviceLost(gpu: GpuContext, info: GPUDeviceLostInfo): Promise<void> {
    if (this.disposed || gpu !== this.gpu) return;
    const losses = this.losses.count(info);
    if (losses === undefined) return;
    this.renderer = undefined;
    this.timer = undefined;
    this.gpu = undefined;
    this.context?.unconfigure();
    const wasRunning = this.state === 'playing' || this.state === 'paused';
    const resume = this.state === 'playing';
    if (!wasRunning) return;
    if (losses > MAX_DEVICE_LOSSES_PER_MINUTE) {
      this.fail(new LanternError(`the GPU device was lost ${losses} times in a minute (${info.message || info.reason})`, 'Reload the page; check the GPU driver if it keeps happening'));
      return;
    }
    this.hooks.onMessage(`The GPU device was lost (${info.message || info.reason}); recreating it…`, 'warning');
    this.setState('starting');
    try {
      await this.start();
    } catch (e) {
      this.fail(e);
      return;
    }
    this.hooks.onMessage('Recovered from a lost GPU device: the scene was uploaded again and rendering goes on.', 'info');
    this.setState(resume ? 'playing' : 'paused');
    if (resume) this.frames.loop();
  }

  private async resizeRenderer(): Promise<void> {
    const tracer = this.webgl2.tracer;
    if (tracer) {
      const w = Math.max(1, Math.round(this.canvas.width * this.settings.scale));
      const h = Math.max(1, Math.round(this.canvas.height * this.settings.scale));
      tracer.resize(w, h);
      if (this.controllerValue) tracer.setCamera(this.cameraOf(this.controllerValue));
      return;
    }
    if (!this.renderer) return;
    // settings.scale says what renders (budget.scale, the panel's resolution); a link carries it only once the user fixes it.
    if (!this.scaleFixed && this.budgetValue) this.settings = { ...this.settings, scale: this.budgetValue.choice.scale };
    const scale = this.settings.scale;
    const w = Math.max(1, Math.round(this.canvas.width * scale));
    const h = Math.max(1, Math.round(this.canvas.height * scale));
    await this.renderer.resize(w, h);
    this.frames.realTimeFrames = 0;
    if (this.controllerValue) this.renderer.setCamera(this.cameraOf(this.controllerValue));
  }

  private requireRenderer(): Renderer {
    if (!this.renderer || !this.loaded) throw new LanternError('nothing has been rendered yet', 'Press Play first');
    return this.renderer;
  }

  private setState(state: ViewerState): void {
    this.state = state;
    this.hooks.onChange(this);
  }

  /** Whether the loaded scene has anything that moves (the panel shows the animate switch for it). */
  get moving(): boolean {
    return this.world !== undefined;
  }

  /** Seconds the loaded scene's world has played (window.lantern.worldSeconds; 0 for a scene where nothing moves). */
  get worldSeconds(): number {
    return this.world?.seconds ?? 0;
  }

  /** Applies the budget's choice of scale (a resize: between frames only). */
  private async applyBudget(): Promise<void> {
    const renderer = this.renderer;
    if (this.scaleFixed || !this.budgetValue || !renderer) return;
    const { scale } = this.budgetValue.choice;
    if (this.settings.scale !== scale) this.settings = { ...this.settings, scale };
    const w = Math.max(1, Math.round(this.canvas.width * scale)), h = Math.max(1, Math.round(this.canvas.height * scale));
    if (w !== renderer.width || h !== renderer.height) await this.resizeRenderer();
  }

  /** Before a frame is planned (ViewerFrames.plan): camera input and the world moved through the frame's time. */
  private advance(renderer: Renderer): void {
    const c = this.controllerValue;
    if (c && this.loaded) {
      const [lx, ly] = this.input.takeLook();
      if (lx !== 0 || ly !== 0) c.look(lx, ly);
      // The time since the last frame, however long it took (the held spans cover it, idle time
      // included): held keys move the camera by it and the world plays it (0 while animation is off:
      // billboards still turn), in turns (frame-clock.ts).
      const played = playFrame(c, this.world, this.input.takeHeld(performance.now()), this.settings.animate);
      if (played.moved || lx !== 0 || ly !== 0) renderer.setCamera(this.cameraOf(c));
      // Kept, so that a lost device is refilled with the scene as it is now.
      if (played.update) this.loaded = { ...this.loaded, prepared: renderer.applySceneUpdate(played.update) };
    }
  }

  /** Waits until the image is a whole frame (ViewerFrames.whole): screenshots and readImage call it. */
  private frameComplete(): Promise<void> {
    return this.frames.whole(() => this.state === 'playing' && this.frames.looping && !document.hidden);
  }
}
