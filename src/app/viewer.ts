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
 */
import { boundsDiagonal } from '../bvh/stats.ts';
import { LanternError } from '../errors.ts';
import { acquireGpu, type GpuContext } from '../gpu/device.ts';
import { observeCompiles, setCompileConcurrency, type CompileProgress } from '../gpu/pipeline-compiles.ts';
import { checkSceneFits } from '../gpu/scene-limits.ts';
import type { ResourceCount } from '../gpu/resource-count.ts';
import { GpuTimer } from '../gpu/timestamps.ts';
import { encodeExr } from '../image/exr.ts';
import { encodePng } from '../image/png.ts';
import { Renderer, type PickResult } from '../renderer/renderer.ts';
import type { KernelKind } from '../renderer/specialisation-schedule.ts';
import type { SplitFrame } from '../renderer/split-frame.ts';
import { adapterKind, ChunkSizer, describeFixedScale, displayRateHz, FrameBudget } from './frame-budget.ts';
import { editMaterials } from '../renderer/prepare.ts';
import { materialEditProblem, mergeMaterialEdits, type MaterialEdit } from '../scene/material-edit.ts';
import type { MaterialOverride } from './material-link.ts';
import type { DebugLegend } from '../renderer/debug-legend.ts';
import { DEFAULT_SETTINGS, ESTIMATE_SETTINGS, type RenderSettings } from '../renderer/settings.ts';
import { isFrameRecipe, newlyCompiled, recipeFor } from '../renderer/recipes/recipe.ts';
import { CameraController, sceneSpeed, type HeldSpan, type MoveMode, type Pose } from './camera-controller.ts';
import { playFrame } from './frame-clock.ts';
import { KeyTimeline } from './key-timeline.ts';
import { linkOfEnvironment } from './environment-choice.ts';
import type { LoadedScene } from './scene-request.ts';
import { withPreparedEnvironment } from '../renderer/prepare.ts';
import type { Environment } from '../scene/environment.ts';
import { lensProblem } from '../scene/lens.ts';
import { World } from '../world/world.ts';
import type { Camera, ThinLens } from '../scene/types.ts';
import { centreFocusDistance } from '../renderer/focus.ts';
import { LINKED_RENDER_SETTINGS, type ViewParams } from './view-params.ts';
import { VIEWER_DEFAULTS } from './viewer-settings.ts';

/** A scene without an environment has this one (black), one object so that it compares equal to itself. */
const NO_ENVIRONMENT: Environment = Object.freeze({ kind: 'none' });

export type ViewerState = 'idle' | 'starting' | 'playing' | 'paused' | 'failed';

/** The page's own settings besides the render settings; their defaults and ranges are declared in VIEWER_SETTINGS (viewer-settings.ts). */
export interface ViewerSettings {
  /** Paths per pixel traced each frame. */
  readonly samplesPerFrame: number;
  /** Render resolution relative to the canvas's device pixels. */
  readonly scale: number;
  /** Keep adding frames into one estimate while the view is still (off: every frame stands alone). */
  readonly accumulate: boolean;
  /**
   * Play the scene's clock (Doom's animated textures and flickering lights, the dungeon's phantom,
   * doors in motion). Off, the world holds still and the image converges; billboards still turn
   * toward the camera and the use key still works (its doors move when the clock runs again).
   */
  readonly animate: boolean;
  /**
   * Converge when still: while a real-time recipe runs and neither the camera nor the world has changed
   * since the last frame, the exact progressive estimate accumulates beside the real-time frames and
   * takes over the display once it holds CONVERGE_HANDOFF_SAMPLES per pixel; the next move hands back.
   */
  readonly convergeWhenStill: boolean;
  readonly render: RenderSettings;
}

/** Samples per pixel the progressive estimate needs before it replaces a still view's denoised frame (about the denoiser's gain at 1 spp: docs/denoise.md). */
export const CONVERGE_HANDOFF_SAMPLES = 64;

/**
 * The real-time chain by default (temporal reprojection and the à-trous filter: renderer/recipes/real-time.ts),
 * converging progressively whenever the view holds still; turning the chain's switches off (temporal,
 * spatial, ReSTIR) gives plain progressive accumulation (renderer/recipes/recipe.ts recipeFor).
 */
export const DEFAULT_VIEWER_SETTINGS: ViewerSettings = Object.freeze({
  // From their entries in VIEWER_SETTINGS (viewer-settings.ts), where their ranges are too.
  samplesPerFrame: VIEWER_DEFAULTS.samplesPerFrame,
  scale: VIEWER_DEFAULTS.scale,
  accumulate: VIEWER_DEFAULTS.accumulate,
  animate: VIEWER_DEFAULTS.animate,
  convergeWhenStill: VIEWER_DEFAULTS.convergeWhenStill,
  render: DEFAULT_SETTINGS,
});

/**
 * Pipelines compiled at a time on the page: Chromium compiles them on its GPU process's thread pool
 * (max(3, cores - 1) foreground workers), and compiles filling it stop the page's frames
 * (gpu/pipeline-compiles.ts). One worker is left free.
 */
const pageCompileConcurrency = () => Math.max(2, (navigator.hardwareConcurrency || 2) - 2);

/** Milliseconds without an edit after which the scene's specialised kernels are compiled (Lantern issue #11). */
const SPECIALISE_AFTER_IDLE_MS = 1000;

/** Where movement comes from: the page's keyboard and mouse (Input); tests may replace it. */
export interface ViewerInput {
  /** Spans of held input since the last call, up to `now` (performance.now()). */
  takeHeld(now: number): HeldSpan[];
  /** Forgets held time before `now` (playing starts or resumes). */
  restartClock(now: number): void;
  /** Mouse movement since the last call, in pixels. */
  takeLook(): [number, number];
}

/** Input with no keys and no mouse, until the page gives its own: its spans still measure each frame's time (the world's clock). */
function idleInput(): ViewerInput {
  const keys = new KeyTimeline(performance.now());
  return { takeHeld: (now) => keys.take(now), restartClock: (now) => keys.restart(now), takeLook: () => [0, 0] };
}

export interface PassTime {
  readonly name: string;
  readonly ms: number;
}

/** What the canvas shows: a real-time frame, the progressive estimate of a still real-time view, or progressive rendering. */
export type ViewerDisplay = 'frame' | 'converged' | 'progressive';

export interface ViewerStats {
  /** Samples per pixel behind the image shown (real-time frames count their frames' samples). */
  readonly samples: number;
  readonly display: ViewerDisplay;
  readonly framesPerSecond: number;
  /** Wall-clock milliseconds between the last two frames. */
  readonly frameMs: number;
  /** GPU milliseconds of each pass of the last timed frame (empty without timestamp queries). */
  readonly gpuPasses: readonly PassTime[];
  readonly raysPerSecond: number;
  readonly width: number;
  readonly height: number;
  readonly triangles: number;
  readonly bvhNodes: number;
  readonly sceneName: string;
  readonly adapter: string;
  readonly gpuResources: ResourceCount;
  /** The tracing kernels in use: generic, or specialised to the scene once it has gone a second without edits. */
  readonly kernel: KernelKind;
  /**
   * Milliseconds from the first Play to the first frame done on the GPU: acquiring the GPU, compiling
   * what the first frame needs, uploading the scene, the frame itself. Undefined until then.
   */
  readonly firstFrameMs: number | undefined;
  /**
   * What the frame budget chose and why, one line: `budget: 0.35× (software adapter, 3 fps target;
   * last frame 310 ms)`, or `budget: off (resolution fixed at 0.5×)` once the user fixed the scale.
   */
  readonly budget: string;
}

/** The frame budget's state for tests (window.lantern.budget). */
export interface BudgetState {
  /** Whether the budget chooses the scale (false once the user fixed a resolution). */
  readonly on: boolean;
  readonly scale: number;
  readonly samplesPerFrame: number;
  readonly text: string;
}

/** The frame under way, for tests: how far its chunks have got (window.lantern.frame). */
export interface FrameProgress {
  /** Chunks submitted and their wall milliseconds (submit to onSubmittedWorkDone), summed. */
  readonly chunks: number;
  readonly busyMs: number;
  /** Pixels traced of the pixels the frame traces (all its parts: the real-time frame, and the estimate beside it). */
  readonly pixelsDone: number;
  readonly pixels: number;
  /** Whether a Pause left it suspended (it goes on at Play unless a change overtakes it). */
  readonly suspended: boolean;
}

/**
 * A frame of the viewer in progress: its parts (a real-time frame; the progressive estimate beside a
 * still view, or alone) begun one after another, each submitted in chunks; what the display shows
 * once they are all done.
 */
interface ViewerFrame {
  readonly renderer: Renderer;
  /** The renderer's frameGeneration when the frame was planned: a change since overtakes it. */
  readonly generation: string;
  readonly width: number;
  readonly height: number;
  readonly samples: number;
  readonly parts: (() => SplitFrame)[];
  current?: SplitFrame;
  readonly display: ViewerDisplay;
  /** After the last part: what the display shows (the real-time frame over the estimate beside it). */
  readonly after?: () => void;
  chunks: number;
  busyMs: number;
  pixelsDone: number;
  readonly pixels: number;
}

export interface ViewerHooks {
  /** Anything shown changed (state, stats, scene). */
  onChange(viewer: Viewer): void;
  /** A message for the user; 'error' stays until the next message. */
  onMessage(text: string, kind: 'info' | 'warning' | 'error'): void;
}

/** More losses than this within a minute and the viewer gives up instead of recreating the device. */
const MAX_DEVICE_LOSSES_PER_MINUTE = 3;
/** Frames over which frames per second and rays per second are averaged. */
const STATS_WINDOW = 30;
/** How often the debug view's legend is read back (its 'auto' maximum follows the image). */
const LEGEND_INTERVAL_MS = 400;

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
  private looping = false;
  private frames: { at: number; rays: number }[] = [];
  private gpuPasses: PassTime[] = [];
  private lastRayCount = 0;
  private lastEpoch = -1;
  private settingsQueue: Promise<void> = Promise.resolve();
  /** What lights every scene instead of its own (the panel's Environment folder, a link's sky); undefined: the scene's own. */
  private environmentOverride?: Environment;
  /** The loaded scene's own environment, for going back to it. */
  private sceneEnvironment?: Environment;
  private losses: number[] = [];
  /** When the first Play was pressed, until its first frame is done (then firstFrameMs holds the wait). */
  private playedAt?: number;
  private firstFrameMs?: number;
  /** The device's batch of pipeline compiles as last reported (gpu/pipeline-compiles.ts), under way or done. */
  private compilesValue?: CompileProgress;
  /** Every pipeline requested on the current device, by key (label and constants), in request order. */
  private pipelinesValue: string[] = [];
  /** What a settings change under way compiles for ('the hybrid recipe'), while it waits; frames go on with the settings before it. */
  private compilingForValue?: string;
  private legendValue?: DebugLegend;
  /** Real-time frames since the estimate last restarted (scene, settings, size). */
  private realTimeFrames = 0;
  /** What the last frame put on screen: a real-time frame, or the progressive estimate (progressive mode, or a still view converged). */
  private displaying: ViewerDisplay = 'progressive';
  private legendAt = 0;
  private expectingLoss = false;
  private disposed = false;
  /** What a click selected (the part of an instance of one material), until Esc, an empty click or another scene. */
  private selectionValue?: PickResult;
  /** Every material edit since the scene loaded, merged per material (what links carry). */
  private materialEdits = new Map<number, MaterialEdit>();
  /** Edits not yet applied (a slider sends many: they are merged and applied once, in order). */
  private pendingEdits = new Map<number, MaterialEdit>();
  /** Chooses the scale and samples per frame from measured frames, until the user fixes the resolution (made at start). */
  private budgetValue?: FrameBudget;
  /** Whether the user fixed the resolution (the panel's scale, a `scale=` link parameter): the budget is then off. */
  private scaleFixed = false;
  /** Sizes each submission of a frame's tracing from measured chunk times (made at start, for the adapter). */
  private chunks = new ChunkSizer();
  /** The frame under way (or suspended by Pause): its chunks go on at the next animation frame. */
  private frameValue?: ViewerFrame;
  /** Settles when the frame under way is done or stopped (readImage waits for it: a half-traced frame is no image). */
  private frameSettled: Promise<void> = Promise.resolve();
  /** When a chunk last told the page (hooks.onChange). */
  private changedAt = 0;
  /** Whether chunks were submitted since the last frame was presented (the real-time output is then half overwritten). */
  private imageDirty = false;
  /** Test hook (window.lantern.delayFrames): milliseconds each frame waits after its GPU work, a deterministically slow adapter. */
  frameDelayMs = 0;

  constructor(
    private readonly canvas: HTMLCanvasElement,
    private readonly hooks: ViewerHooks,
  ) {
    document.addEventListener('visibilitychange', () => {
      // Hidden tabs get no frames; coming back resumes where it was, and the time hidden is not
      // played (a frame asked for before hiding runs only now: its time starts here).
      if (!document.hidden) this.input.restartClock(performance.now());
      if (!document.hidden && this.state === 'playing') this.loop();
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
    return this.settings.render.debugView === 'none' ? undefined : this.legendValue;
  }

  /** Depth of the scene's deepest BVH node (the wireframe depth's upper bound). */
  get bvhMaxDepth(): number {
    return this.loaded?.prepared.bvh.stats.maxDepth ?? 0;
  }

  get stats(): ViewerStats {
    const f = this.frames;
    const span = f.length > 1 ? (f[f.length - 1]!.at - f[0]!.at) / 1000 : 0;
    const rays = f.slice(1).reduce((n, x) => n + x.rays, 0);
    const packed = this.loaded?.prepared.packed.counts;
    return {
      samples: this.displaying === 'frame' ? this.realTimeFrames * this.samplesPerFrame() : (this.renderer?.sampleCount ?? 0),
      display: this.displaying,
      framesPerSecond: span > 0 ? (f.length - 1) / span : 0,
      frameMs: f.length > 1 ? f[f.length - 1]!.at - f[f.length - 2]!.at : 0,
      gpuPasses: this.gpuPasses,
      raysPerSecond: span > 0 ? rays / span : 0,
      width: this.renderer?.width ?? 0,
      height: this.renderer?.height ?? 0,
      triangles: packed?.triangles ?? 0,
      bvhNodes: this.loaded ? this.loaded.prepared.bvh.stats.nodeCount : 0,
      sceneName: this.loaded?.prepared.scene.name ?? '',
      adapter: this.gpu?.adapterName ?? '',
      gpuResources: this.gpu?.resources.count ?? { buffers: 0, textures: 0, bytes: 0 },
      kernel: this.renderer?.kernel ?? 'generic',
      firstFrameMs: this.firstFrameMs,
      budget: this.budgetText(),
    };
  }

  /**
   * The budget's account. `short`: for the status line, without the last frame's time (so it changes
   * only with the choice), and empty with the budget off (the fixed scale shows in the image size):
   * the header wraps, and a longer line changes the canvas's size and aspect, and with it the image.
   */
  budgetText(short = false): string {
    if (this.scaleFixed) return short ? '' : describeFixedScale(this.settings.scale);
    if (!this.budgetValue) return 'budget: measuring the GPU at the first frames';
    return this.budgetValue.describe(!short);
  }

  /**
   * The pipeline compiles of the viewer's device: the batch under way (done < needed) or the last one.
   * Start-up, a scene whose variants are new, a recipe switched to, ReSTIR and the wavefront
   * integrator in the background all compile in batches; the page shows what it waits for.
   */
  get compiles(): CompileProgress | undefined {
    return this.compilesValue;
  }

  /** Every pipeline requested on the current device (label and override constants), in request order: what a page compiled. */
  get pipelines(): readonly string[] {
    return this.pipelinesValue;
  }

  /** What the settings change under way compiles for ('the hybrid recipe'), while the frames go on with the previous settings. */
  get compilingFor(): string | undefined {
    return this.compilingForValue;
  }

  /** Whether the viewer has been played and waits for its first frame on screen (the GPU starting, pipelines compiling, the frame). */
  get awaitingFirstFrame(): boolean {
    return this.playedAt !== undefined && this.firstFrameMs === undefined && (this.state === 'starting' || this.state === 'playing');
  }

  /** The frame budget: on or off, the scale that renders (its choice, or the user's), its one-line account. */
  get budget(): BudgetState {
    return { on: !this.scaleFixed, scale: this.settings.scale, samplesPerFrame: this.samplesPerFrame(), text: this.budgetText() };
  }

  /** How far the frame under way has got (undefined between frames). */
  get frameProgress(): FrameProgress | undefined {
    const f = this.frameValue;
    return f && { chunks: f.chunks, busyMs: f.busyMs, pixelsDone: f.pixelsDone, pixels: f.pixels, suspended: this.state !== 'playing' };
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
    if (!this.renderer) {
      this.playedAt ??= performance.now();
      this.setState('starting');
      await this.start();
    }
    this.setState('playing');
    this.loop();
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
    const { scene, bvh } = loaded.prepared;
    // The controller keeps its own heights of the walk map (doors and lifts change them).
    const controller = new CameraController(scene.camera, sceneSpeed(boundsDiagonal(bvh), scene.metersPerUnit, scene.walkMap), scene.walkMap);
    if (view.pose) controller.setPose(view.pose);
    if (view.fovDegrees !== undefined) controller.vfovDegrees = view.fovDegrees;
    controller.setMode(view.mode ?? (controller.canWalk ? 'walk' : 'fly'));
    if (view.apertureRadius !== undefined || view.focusDistance !== undefined) {
      // What the link leaves out comes from the scene's lens; a focus distance from neither, from the image centre.
      const focusDistance = view.focusDistance ?? controller.lens?.focusDistance ?? defaultFocus(loaded.prepared, controller.camera());
      controller.lens = { apertureRadius: view.apertureRadius ?? controller.lens?.apertureRadius ?? 0, focusDistance };
    }
    // Torch colour, intensity and range set for the last scene mean nothing in this one's units:
    // only on/off carries over.
    this.settings = { ...this.settings, render: { ...this.settings.render, torch: { enabled: this.settings.render.torch.enabled } } };
    if (this.renderer) {
      this.renderer.updateSettings(this.settings.render);
      await this.renderer.setScene(loaded.prepared);
      // The controller starts from this scene's camera, exposure included.
      this.renderer.setCamera(controller.camera());
      this.renderer.resetHistory();
    }
    this.realTimeFrames = 0;
    this.loaded = loaded;
    this.controllerValue = controller;
    this.world = World.of(scene);
    this.selectionValue = undefined;
    this.materialEdits = new Map();
    this.pendingEdits = new Map();
    this.frames = [];
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
    this.realTimeFrames = 0;
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

  /**
   * The render-image pixel under a canvas point given in CSS pixels from the canvas's top-left
   * corner (present() stretches the image over the canvas).
   */
  private imagePoint(x: number, y: number): [number, number] | undefined {
    const r = this.renderer;
    const w = this.canvas.clientWidth || this.canvas.width, h = this.canvas.clientHeight || this.canvas.height;
    if (!r || r.width === 0 || w === 0 || h === 0) return undefined;
    const px = Math.floor((x / w) * r.width), py = Math.floor((y / h) * r.height);
    return px >= 0 && px < r.width && py >= 0 && py < r.height ? [px, py] : undefined;
  }

  /** The pick under a canvas point (CSS pixels), in line with other changes; undefined before Play or off the image. */
  pickAt(x: number, y: number): Promise<PickResult | null | undefined> {
    return this.enqueue(() => this.pickNow(x, y));
  }

  private async pickNow(x: number, y: number): Promise<PickResult | null | undefined> {
    const p = this.imagePoint(x, y);
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
    const material = this.loaded?.prepared.scene.materials[index];
    if (!material) return Promise.reject(new LanternError(`the scene has no material ${index}`));
    const problem = materialEditProblem(material.kind, edit);
    if (problem) return Promise.reject(new LanternError(`cannot edit material '${material.name}': ${problem}`));
    this.pendingEdits.set(index, mergeMaterialEdits(this.pendingEdits.get(index) ?? {}, edit));
    this.materialEdits.set(index, mergeMaterialEdits(this.materialEdits.get(index) ?? {}, edit));
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
      const m = materials[o.index];
      const problem = !m ? `the scene has no material ${o.index}` : m.name !== o.name ? `material ${o.index} is '${m.name}', not '${o.name}'` : materialEditProblem(m.kind, o.edit);
      if (problem) problems.push(`material edit ${o.index} (${o.name}): ${problem}`);
      else await this.editMaterial(o.index, o.edit);
    }
    return problems;
  }

  /** The material edits made since the scene loaded, for links. */
  get materialOverrides(): MaterialOverride[] {
    const materials = this.loaded?.prepared.scene.materials ?? [];
    return [...this.materialEdits].filter(([i]) => materials[i]).map(([index, edit]) => ({ index, name: materials[index]!.name, edit }));
  }

  private async applyPendingEdits(): Promise<void> {
    const loaded = this.loaded;
    if (!loaded || this.pendingEdits.size === 0) return;
    const edits = this.pendingEdits;
    this.pendingEdits = new Map();
    const prepared = this.renderer ? this.renderer.updateMaterials(edits) : editMaterials(loaded.prepared, edits).prepared;
    this.loaded = { ...loaded, prepared };
    this.realTimeFrames = 0;
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
    this.legendAt = 0;
    const restart = ESTIMATE_SETTINGS.some((k) => render[k] !== before.render[k]) || recipeFor(render) !== recipeFor(before.render);
    if (restart) this.realTimeFrames = 0;
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
    this.realTimeFrames = 0;
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
  }

  setMoveMode(mode: MoveMode): boolean {
    const ok = this.controllerValue?.setMode(mode) ?? false;
    if (ok && this.controllerValue) this.renderer?.setCamera(this.cameraOf(this.controllerValue));
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
    const renderer = this.requireRenderer();
    return encodePng(renderer.width, renderer.height, await renderer.readImage());
  }

  /** The tone-mapped image (RGBA8, what a screenshot holds) with the sample count at the moment it was read (the test hook). */
  async readImage(): Promise<{ samples: number; width: number; height: number; rgba: number[] }> {
    await this.frameComplete();
    const renderer = this.requireRenderer();
    const samples = this.stats.samples;
    const rgba = await renderer.readImage();
    return { samples, width: renderer.width, height: renderer.height, rgba: Array.from(rgba) };
  }

  /** The linear radiance (the estimate, or the denoised frame) as EXR bytes: float32 RGB, before exposure and tone mapping. */
  async radianceExr(): Promise<Uint8Array> {
    await this.frameComplete();
    const renderer = this.requireRenderer();
    const { width, height, radiance } = this.displaying === 'frame' && this.realTimeFrames > 0 ? await renderer.readFrame() : await renderer.readAccumulation();
    return encodeExr(width, height, radiance);
  }

  /** The camera and settings as URL parameters (the page adds the scene's location). */
  viewParams(): ViewParams {
    const c = this.controllerValue;
    const s = this.settings;
    const t = s.render.torch;
    return {
      ...(c ? { pose: c.pose, fovDegrees: c.vfovDegrees, mode: c.mode } : {}),
      ...(c?.lens ? { apertureRadius: c.lens.apertureRadius, focusDistance: c.lens.focusDistance } : {}),
      samplesPerFrame: s.samplesPerFrame,
      // A link carries a scale only where the user fixed one: otherwise the budget of whoever opens it chooses.
      ...(this.scaleFixed ? { scale: s.scale } : {}),
      accumulate: s.accumulate,
      ...(s.animate ? {} : { animate: false }),
      ...(s.convergeWhenStill ? {} : { convergeWhenStill: false }),
      ...Object.fromEntries(LINKED_RENDER_SETTINGS.map((k) => [k, s.render[k]])),
      ...linkOfEnvironment(this.environmentOverride),
      ...(this.materialEdits.size > 0 ? { materials: this.materialOverrides } : {}),
      torch: { enabled: t.enabled, ...(t.color ? { color: [t.color[0], t.color[1], t.color[2]] } : {}), ...(t.intensity !== undefined ? { intensity: t.intensity } : {}), ...(t.range !== undefined ? { range: t.range } : {}) },
    };
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
    this.expectingLoss = true;
    this.gpu.device.destroy();
  }

  destroy(): void {
    this.disposed = true;
    this.timer?.destroy();
    this.renderer?.destroy();
    this.gpu?.device.destroy();
  }

  private async start(): Promise<void> {
    // The display's rate is measured while the GPU starts (requestAnimationFrame runs free then).
    const [gpu, displayHz] = await Promise.all([acquireGpu(navigator.gpu), measureDisplayRate()]);
    const context = this.canvas.getContext('webgpu');
    if (!context) throw new LanternError('the canvas has no WebGPU context', 'Reload the page; if it persists, the browser has WebGPU disabled');
    const format = navigator.gpu.getPreferredCanvasFormat();
    context.configure({ device: gpu.device, format, alphaMode: 'opaque' });
    // Every compile from here on is counted, so the page can say what it waits for.
    setCompileConcurrency(gpu.device, pageCompileConcurrency());
    this.pipelinesValue = [];
    observeCompiles(gpu.device, (progress) => {
      this.compilesValue = progress;
      for (const c of progress.compiles) if (!this.pipelinesValue.includes(c.key)) this.pipelinesValue.push(c.key);
      this.hooks.onChange(this);
    });
    // What the first frame needs and nothing more, compiled side by side: the path tracer for the
    // loaded scene alone (its upload overlaps the compile), the tone mapper and the present pass;
    // then whatever the settings ask for (debug views, a real-time recipe, spectral), together.
    const s = this.settings.render;
    const renderer = await Renderer.create(gpu, { presentation: format, ...(this.loaded ? { features: this.loaded.prepared.packed.features } : {}) });
    // The renderer's idle policy: kernels specialised to the scene once it has gone this long without an
    // edit. Not on SwiftShader (a CPU): compiling them there takes minutes of the CPU the page runs on.
    if (!/swiftshader/i.test(gpu.adapterName)) renderer.setIdleSpecialisation(SPECIALISE_AFTER_IDLE_MS);
    await renderer.compile(s);
    this.realTimeFrames = 0;
    renderer.updateSettings(this.settings.render);
    this.gpu = gpu;
    this.context = context;
    this.renderer = renderer;
    this.timer = gpu.hasTimestamps ? new GpuTimer(gpu.device) : undefined;
    // A new device may be another adapter (a lost GPU replaced by the fallback): the budget measures it afresh.
    const adapter = adapterKind({ name: gpu.adapterName, isFallbackAdapter: gpu.adapter.info.isFallbackAdapter });
    this.budgetValue = new FrameBudget({ adapter, displayHz, canvasWidth: Math.max(1, this.canvas.width), canvasHeight: Math.max(1, this.canvas.height), baseSamples: this.settings.samplesPerFrame });
    this.chunks = new ChunkSizer(adapter);
    this.frameValue = undefined;
    await this.resizeRenderer();
    if (this.loaded) await renderer.setScene(this.loaded.prepared);
    if (this.controllerValue) renderer.setCamera(this.cameraOf(this.controllerValue));
    const selected = this.selectionValue;
    if (selected) await renderer.setSelection({ instanceIndex: selected.instanceIndex, material: selected.material });
    void gpu.lost.then((info) => this.onDeviceLost(gpu, info));
  }

  private async onDeviceLost(gpu: GpuContext, info: GPUDeviceLostInfo): Promise<void> {
    if (this.disposed || gpu !== this.gpu) return;
    const simulated = this.expectingLoss;
    this.expectingLoss = false;
    if (info.reason === 'destroyed' && !simulated) return;
    const now = performance.now();
    this.losses = [...this.losses.filter((t) => now - t < 60_000), now];
    this.renderer = undefined;
    this.timer = undefined;
    this.gpu = undefined;
    this.context?.unconfigure();
    const wasRunning = this.state === 'playing' || this.state === 'paused';
    const resume = this.state === 'playing';
    if (!wasRunning) return;
    if (this.losses.length > MAX_DEVICE_LOSSES_PER_MINUTE) {
      this.fail(new LanternError(`the GPU device was lost ${this.losses.length} times in a minute (${info.message || info.reason})`, 'Reload the page; check the GPU driver if it keeps happening'));
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
    if (resume) this.loop();
  }

  private async resizeRenderer(): Promise<void> {
    if (!this.renderer) return;
    // settings.scale says what renders (budget.scale, the panel's resolution); a link carries it only once the user fixes it.
    if (!this.scaleFixed && this.budgetValue) this.settings = { ...this.settings, scale: this.budgetValue.choice.scale };
    const scale = this.settings.scale;
    const w = Math.max(1, Math.round(this.canvas.width * scale));
    const h = Math.max(1, Math.round(this.canvas.height * scale));
    await this.renderer.resize(w, h);
    this.realTimeFrames = 0;
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

  private loop(): void {
    if (this.looping) return;
    this.looping = true;
    // Keys held while paused or hidden move nothing, and the world does not play that time: the
    // frame's time (held spans, idle included) counts from here.
    this.input.restartClock(performance.now());
    const frame = async () => {
      const renderer = this.renderer;
      const context = this.context;
      if (this.state !== 'playing' || document.hidden || !renderer || !context || !this.loaded) {
        this.looping = false;
        this.frames = [];
        return;
      }
      try {
        await this.renderFrame(renderer, context);
      } catch (e) {
        this.looping = false;
        // A frame cut short by a lost device is the loss handler's business, not a failure.
        if (renderer !== this.renderer || (await lostSoon(renderer.gpu))) return;
        this.fail(e);
        return;
      }
      this.hooks.onChange(this);
      requestAnimationFrame(frame);
    };
    requestAnimationFrame(frame);
  }

  /** Whether the loaded scene has anything that moves (the panel shows the animate switch for it). */
  get moving(): boolean {
    return this.world !== undefined;
  }

  /** Seconds the loaded scene's world has played (window.lantern.worldSeconds; 0 for a scene where nothing moves). */
  get worldSeconds(): number {
    return this.world?.seconds ?? 0;
  }

  /**
   * One animation frame's work: the frame under way goes on (one suspended by Pause, unless a change
   * overtook it), or a new one is planned: the budget's scale applied (between frames only), the
   * camera and the world moved through the time since the last frame. Its GPU work goes in
   * chunks of about CHUNK_TARGET_MS, each awaited: between them the page answers input, and Pause,
   * a change of settings, scene or size stop the frame (the loop starts a fresh one). Once every
   * chunk is done the frame is presented and measured.
   */
  private async renderFrame(renderer: Renderer, context: GPUCanvasContext): Promise<void> {
    // A screenshot of a suspended frame may be finishing it (frameComplete).
    await this.frameSettled;
    let frame = this.frameValue;
    if (frame && !this.frameValid(frame)) {
      this.abandonFrame(frame);
      frame = undefined;
    }
    if (!frame) {
      await this.applyBudget();
      frame = this.frameValue = this.planFrame(renderer);
    }
    let settle!: () => void;
    this.frameSettled = new Promise((resolve) => (settle = resolve));
    try {
      const outcome = await this.runChunks(frame, () => this.state === 'playing' && !document.hidden);
      // Suspended (Pause, a hidden tab): the frame waits in frameValue. Overtaken: the next animation frame plans another.
      if (outcome === 'overtaken') this.abandonFrame(frame);
      if (outcome !== 'done') return;
      this.frameValue = undefined;
      await this.completeFrame(renderer, context, frame);
    } finally {
      settle();
    }
  }

  /** Gives a frame up: the renderer undoes what matters (the real-time ping-pong), the timer forgets its passes (no resolve will read them). */
  private abandonFrame(frame: ViewerFrame): void {
    frame.current?.abandon();
    if (frame.renderer === this.renderer) this.timer?.discard();
    if (this.frameValue === frame) this.frameValue = undefined;
  }

  /** Whether a frame may go on: same renderer, nothing changed what it computes since it was planned. */
  private frameValid(frame: ViewerFrame): boolean {
    return frame.renderer === this.renderer && frame.renderer.frameGeneration() === frame.generation && frame.renderer.width === frame.width && frame.renderer.height === frame.height && (!frame.current || frame.current.done || frame.current.valid);
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

  /** Input, world and the frame's parts by the settings (a real-time frame, the estimate beside a still view, the estimate alone, or nothing to trace). */
  private planFrame(renderer: Renderer): ViewerFrame {
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
    if (!this.settings.accumulate) renderer.resetAccumulation();
    // The counters restart with the estimate (every camera move too): then the whole count is this frame's.
    const fresh = renderer.accumulationEpoch !== this.lastEpoch;
    const timer = this.timer;
    const render = this.settings.render;
    const spf = this.samplesPerFrame();
    const parts: (() => SplitFrame)[] = [];
    let display: ViewerDisplay = 'progressive';
    let after: (() => void) | undefined;
    // The recipe (renderer/recipes/recipe.ts): a debug view that replaces the image needs no path
    // tracing (present() draws it); the frame recipes run frames, the progressive one samples.
    const recipe = recipeFor(render);
    if (recipe === 'debug') {
      display = this.displaying;
    } else if (isFrameRecipe(recipe)) {
      // The real-time chain keeps its own history across camera moves (reprojection). A view that held
      // still since the last frame (no reset of the estimate: camera, world, settings) also adds to the
      // exact progressive estimate, which is shown once it has enough samples.
      const still = this.settings.convergeWhenStill && !fresh && this.realTimeFrames > 0;
      if (still && renderer.sampleCount >= CONVERGE_HANDOFF_SAMPLES) {
        parts.push(() => renderer.beginAccumulate(spf, timer));
        display = 'converged';
      } else {
        parts.push(() => renderer.beginFrame(spf, timer));
        if (still) {
          parts.push(() => renderer.beginAccumulate(spf));
          after = () => renderer.show('frame');
        }
        display = 'frame';
      }
    } else {
      parts.push(() => renderer.beginAccumulate(spf, timer));
    }
    const pixels = renderer.width * renderer.height * parts.length;
    return { renderer, generation: renderer.frameGeneration(), width: renderer.width, height: renderer.height, samples: spf, parts, display, ...(after ? { after } : {}), chunks: 0, busyMs: 0, pixelsDone: 0, pixels };
  }

  /**
   * Submits the frame's chunks one at a time, each awaited, while `keepGoing` says so and nothing
   * overtakes the frame. 'suspended': stopped by keepGoing (the frame can go on later).
   */
  private async runChunks(frame: ViewerFrame, keepGoing: () => boolean): Promise<'done' | 'suspended' | 'overtaken'> {
    const renderer = frame.renderer;
    for (;;) {
      if (!this.frameValid(frame)) return 'overtaken';
      if (!frame.current || frame.current.done) {
        const part = frame.parts.shift();
        if (!part) return 'done';
        frame.current = part();
      }
      if (!keepGoing()) return 'suspended';
      const split = frame.current;
      // A frame cut into several chunks pays a round trip for each: measured at its start (the GPU
      // idle), so the sizer tells the work from the wait.
      if (frame.chunks === 0 && split.rowsDone === 0 && split.columnsLeft === split.width && this.chunks.splits(split.width, split.height, split.samples)) {
        const t = performance.now();
        await renderer.finish();
        this.chunks.observeIdle(performance.now() - t);
      }
      const chunk = this.chunks.next(split.width, split.height, split.rowsLeft, split.samples, split.columnsLeft);
      const t0 = performance.now();
      const pixels = split.submitChunk(chunk.rows, chunk.columns);
      this.imageDirty = true;
      await renderer.finish();
      const ms = performance.now() - t0;
      this.chunks.observe(pixels, split.samples, ms);
      frame.chunks++;
      frame.busyMs += ms;
      frame.pixelsDone += split.splittable ? pixels : split.width * split.height;
      // The page's numbers follow a long frame's progress, a few times a second (not every chunk: the CPU is the GPU on a software adapter).
      if (performance.now() - this.changedAt > CHUNK_STATUS_MS) {
        this.changedAt = performance.now();
        this.hooks.onChange(this);
      }
    }
  }

  /** After the last chunk: present, read the counters and the timings, feed the budget. */
  private async completeFrame(renderer: Renderer, context: GPUCanvasContext, frame: ViewerFrame): Promise<void> {
    frame.after?.();
    this.imageDirty = false;
    this.displaying = frame.display;
    if (frame.display === 'frame') this.realTimeFrames++;
    const timer = this.timer;
    const t0 = performance.now();
    renderer.present(context.getCurrentTexture(), timer);
    // Reading the counters waits for the present and counts the frame's rays exactly.
    const counts = await renderer.readRayCounts();
    const busyMs = frame.busyMs + (performance.now() - t0);
    if (this.frameDelayMs > 0) await new Promise((resolve) => setTimeout(resolve, this.frameDelayMs));
    const total = counts.extension + counts.shadow;
    const fresh = renderer.accumulationEpoch !== this.lastEpoch;
    const rays = fresh ? total : total - this.lastRayCount;
    this.lastRayCount = total;
    this.lastEpoch = renderer.accumulationEpoch;
    if (timer) this.gpuPasses = sumByName(await timer.read());
    const render = this.settings.render;
    if (render.debugView !== 'none' && performance.now() - this.legendAt > LEGEND_INTERVAL_MS) {
      this.legendValue = await renderer.debugLegend();
      this.legendAt = performance.now();
    }
    this.frames.push({ at: performance.now(), rays });
    if (this.frames.length > STATS_WINDOW) this.frames.shift();
    if (this.playedAt !== undefined && this.firstFrameMs === undefined) this.firstFrameMs = performance.now() - this.playedAt;
    // The budget hears the frame's GPU time on a real GPU: the timestamps where every pass of it was
    // timed (a frame of a few chunks: the timer has room for them all), else the chunks' wall time.
    // On a software adapter always the wall time: the GPU is the CPU the page shares, and its
    // timestamps leave out the round trips and the load that the user waits for.
    const budget = this.budgetValue;
    const gpuTimed = budget?.adapter === 'hardware' && timer !== undefined && frame.chunks <= MAX_TIMED_CHUNKS && this.gpuPasses.length > 0;
    const ms = gpuTimed ? this.gpuPasses.reduce((sum, p) => sum + p.ms, 0) : busyMs;
    if (!this.scaleFixed && budget && frame.pixels > 0) {
      budget.observe({ ms, gpuTimed, width: frame.width, height: frame.height, samples: frame.samples * (frame.pixels / (frame.width * frame.height)), at: performance.now() });
    }
  }

  /**
   * Waits until the image is a whole frame: for the frame under way to be done, or, for one that
   * Pause suspended, runs its remaining chunks and presents it (a half-traced real-time frame is no
   * image). Screenshots and readImage call it.
   */
  private async frameComplete(): Promise<void> {
    for (;;) {
      await this.frameSettled;
      const frame = this.frameValue;
      // Between frames, with the last one presented whole.
      if (!frame && !this.imageDirty) return;
      if (this.state === 'playing' && this.looping && !document.hidden) {
        // The loop goes on with it at the next animation frame (its callback was asked for first).
        await new Promise((resolve) => requestAnimationFrame(resolve));
        continue;
      }
      const renderer = this.renderer, context = this.context;
      if (!frame || !renderer || !context || !this.frameValid(frame)) return;
      let settle!: () => void;
      this.frameSettled = new Promise((resolve) => (settle = resolve));
      try {
        if ((await this.runChunks(frame, () => true)) !== 'done') return;
        this.frameValue = undefined;
        await this.completeFrame(renderer, context, frame);
      } finally {
        settle();
      }
      return;
    }
  }
}

/** Milliseconds between the page updates a long frame's chunks give. */
const CHUNK_STATUS_MS = 250;

/** Frames of at most this many chunks are timed by timestamp queries whole (GpuTimer's 64 passes hold them and the passes after). */
const MAX_TIMED_CHUNKS = 16;

/** Pass timings with the chunks of one pass (named alike) summed, in the order the passes first ran. */
function sumByName(passes: readonly PassTime[]): PassTime[] {
  const sums = new Map<string, number>();
  for (const p of passes) sums.set(p.name, (sums.get(p.name) ?? 0) + p.ms);
  return [...sums].map(([name, ms]) => ({ name, ms }));
}

/**
 * The display's refresh rate from requestAnimationFrame intervals over a few frames (displayRateHz),
 * or the default when frames do not come (a hidden tab) within a second.
 */
function measureDisplayRate(frames = 12): Promise<number> {
  return new Promise((resolve) => {
    const intervals: number[] = [];
    let last: number | undefined;
    const done = () => resolve(displayRateHz(intervals));
    const timeout = setTimeout(done, 1000);
    const tick = (now: number) => {
      if (last !== undefined) intervals.push(now - last);
      last = now;
      if (intervals.length >= frames) {
        clearTimeout(timeout);
        done();
      } else requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  });
}

/** What a link may say about the view of the scene it opens. */
export type SceneView = Pick<ViewParams, 'pose' | 'mode' | 'fovDegrees' | 'apertureRadius' | 'focusDistance'>;

/** The depth at the image centre, or half the scene's size when the centre ray meets nothing. */
function defaultFocus(prepared: LoadedScene['prepared'], camera: Camera): number {
  return centreFocusDistance(prepared, camera) ?? Math.max(boundsDiagonal(prepared.bvh) / 2, 1e-3);
}

/** Whether the device reports itself lost within a moment (frames fail before `lost` resolves). */
async function lostSoon(gpu: GpuContext): Promise<boolean> {
  const timeout = new Promise<false>((resolve) => setTimeout(() => resolve(false), 200));
  return Promise.race([gpu.lost.then(() => true), timeout]);
}

export function describeError(error: unknown): string {
  if (error instanceof LanternError) return error.userMessage;
  return `Something went wrong: ${(error as Error)?.message ?? String(error)}`;
}
