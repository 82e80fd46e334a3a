/**
 * The viewer's public types (imported from here, beside the Viewer class of viewer.ts): its state, its own settings and their
 * defaults, the input it reads, what it reports (stats, the budget, the frame under way), what a
 * link may say about the view, and the words for an error. No Renderer, no DOM.
 */
import { LanternError } from '../errors.ts';
import type { ResourceCount } from '../gpu/resource-count.ts';
import type { KernelKind } from '../renderer/specialisation-schedule.ts';
import { DEFAULT_SETTINGS, type RenderSettings } from '../renderer/settings.ts';
import type { HeldSpan } from './camera-controller.ts';
import { KeyTimeline } from './key-timeline.ts';
import type { ViewParams } from './view-params.ts';
import { VIEWER_DEFAULTS } from './viewer-settings.ts';

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
export function idleInput(): ViewerInput {
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

/** What a link may say about the view of the scene it opens. */
export type SceneView = Pick<ViewParams, 'pose' | 'mode' | 'fovDegrees' | 'apertureRadius' | 'focusDistance'>;

/** The words for an error on the page's message line: a LanternError's own, anything else as unexpected. */
export function describeError(error: unknown): string {
  if (error instanceof LanternError) return error.userMessage;
  return `Something went wrong: ${(error as Error)?.message ?? String(error)}`;
}
