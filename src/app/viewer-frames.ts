/**
 * The viewer's frame loop: one frame per animation frame, at most one in flight. Each frame is
 * planned in parts (a real-time frame; beside a still view, the exact progressive estimate that takes
 * over once it holds CONVERGE_HANDOFF_SAMPLES per pixel: converge when still; or the estimate
 * alone), submitted in chunks that the ChunkSizer sizes, each awaited, then presented and measured
 * (rays, pass timings, the debug view's legend, the first frame's wait), its time handed to the
 * frame budget. The viewer (viewer.ts) gives it, through FramesHost, its renderer and settings and
 * its own steps of a frame: the budget's choice of scale, the camera and the world moved.
 */
import type { GpuTimer } from '../gpu/timestamps.ts';
import type { DebugLegend } from '../renderer/debug-legend.ts';
import type { Renderer } from '../renderer/renderer.ts';
import { isFrameRecipe, recipeFor } from '../renderer/recipes/recipe.ts';
import type { SplitFrame } from '../renderer/split-frame.ts';
import { ChunkSizer, type FrameBudget } from './frame-budget.ts';
import { lostSoon } from './viewer-device.ts';
import { CONVERGE_HANDOFF_SAMPLES, type FrameProgress, type PassTime, type ViewerDisplay, type ViewerSettings, type ViewerStats } from './viewer-types.ts';

/** Frames over which frames per second and rays per second are averaged. */
const STATS_WINDOW = 30;
/** How often the debug view's legend is read back (its 'auto' maximum follows the image). */
const LEGEND_INTERVAL_MS = 400;

/**
 * A frame of the viewer in progress: its parts (a real-time frame; the progressive estimate beside a
 * still view, or alone) begun one after another, each submitted in chunks; what the display shows
 * once they are all done.
 */
export interface ViewerFrame {
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

/**
 * What the frames read of the viewer, at each use (a lost device replaces the renderer, its context
 * and its timer), and the viewer's own steps of a frame: the budget's scale, the camera and the world.
 */
export interface FramesHost {
  renderer(): Renderer | undefined;
  context(): GPUCanvasContext | undefined;
  timer(): GpuTimer | undefined;
  settings(): ViewerSettings;
  /** The samples per pixel a frame traces (the budget's choice while it is on). */
  samplesPerFrame(): number;
  /** The frame budget while it chooses the scale (undefined before the GPU starts and once the user fixed the resolution). */
  budget(): FrameBudget | undefined;
  /** Milliseconds each frame waits after its GPU work (the test hook Viewer.frameDelayMs). */
  delayMs(): number;
  /** Whether the viewer plays (state 'playing'), and whether it has a scene. */
  playing(): boolean;
  hasScene(): boolean;
  /** Forgets held input before now (the input's restartClock): the frames' time counts from here. */
  restartClock(): void;
  /** Before a new frame: the budget's choice of scale applied (a resize: between frames only). */
  applyBudget(): Promise<void>;
  /** Then, in the same turn as its plan: camera input and the world moved through the frame's time. */
  advance(renderer: Renderer): void;
  /** A frame failed (not by a lost device): the viewer stops and says why. */
  fail(error: unknown): void;
  /** Anything shown changed (hooks.onChange). */
  changed(): void;
}

/** The frame under way, its chunks, and what the frames measured. */
export class ViewerFrames {
  /** Sizes each submission of a frame's tracing from measured chunk times (made at start, for the adapter). */
  chunks = new ChunkSizer();
  /** The frame under way (or suspended by Pause): its chunks go on at the next animation frame. */
  current?: ViewerFrame;
  /** Settles when the frame under way is done or stopped (readImage waits for it: a half-traced frame is no image). */
  settled: Promise<void> = Promise.resolve();
  /** Whether chunks were submitted since the last frame was presented (the real-time output is then half overwritten). */
  imageDirty = false;
  /** Real-time frames since the estimate last restarted (scene, settings, size). */
  realTimeFrames = 0;
  /** What the last frame put on screen: a real-time frame, or the progressive estimate (progressive mode, or a still view converged). */
  displaying: ViewerDisplay = 'progressive';
  /** The debug view's legend as last read back, and when (0: read it at the next frame). */
  legend?: DebugLegend;
  legendAt = 0;
  /** When the first Play was pressed, until its first frame is done (then firstFrameMs holds the wait). */
  playedAt?: number;
  firstFrameMs?: number;
  /** Whether the animation-frame loop runs (loop). */
  looping = false;
  /** When a chunk last told the page (hooks.onChange). */
  private changedAt = 0;
  private frames: { at: number; rays: number }[] = [];
  private gpuPasses: PassTime[] = [];
  private lastRayCount = 0;
  private lastEpoch = -1;

  constructor(private readonly host: FramesHost) {}

  /** The frames' readings for Viewer.stats; `samplesPerFrame`: what each real-time frame traces. */
  readings(samplesPerFrame: number): Pick<ViewerStats, 'samples' | 'display' | 'framesPerSecond' | 'frameMs' | 'gpuPasses' | 'raysPerSecond'> {
    const f = this.frames;
    const span = f.length > 1 ? (f[f.length - 1]!.at - f[0]!.at) / 1000 : 0;
    const rays = f.slice(1).reduce((n, x) => n + x.rays, 0);
    return {
      samples: this.displaying === 'frame' ? this.realTimeFrames * samplesPerFrame : (this.host.renderer()?.sampleCount ?? 0),
      display: this.displaying,
      framesPerSecond: span > 0 ? (f.length - 1) / span : 0,
      frameMs: f.length > 1 ? f[f.length - 1]!.at - f[f.length - 2]!.at : 0,
      gpuPasses: this.gpuPasses,
      raysPerSecond: span > 0 ? rays / span : 0,
    };
  }

  /** Forgets the frame times (a new scene, the loop stopped): the rates start afresh. */
  resetRates(): void {
    this.frames = [];
  }

  /** How far the frame under way has got (undefined between frames); `suspended`: the viewer is not playing. */
  progress(suspended: boolean): FrameProgress | undefined {
    const f = this.current;
    return f && { chunks: f.chunks, busyMs: f.busyMs, pixelsDone: f.pixelsDone, pixels: f.pixels, suspended };
  }

  /**
   * Runs one frame per animation frame, with at most one in flight, until the viewer stops playing,
   * the tab hides, or the renderer or the scene is gone; a frame that fails stops the viewer.
   */
  loop(): void {
    if (this.looping) return;
    this.looping = true;
    // Keys held while paused or hidden move nothing, and the world does not play that time: the
    // frame's time (held spans, idle included) counts from here.
    this.host.restartClock();
    const frame = async () => {
      const renderer = this.host.renderer();
      const context = this.host.context();
      if (!this.host.playing() || document.hidden || !renderer || !context || !this.host.hasScene()) {
        this.looping = false;
        this.resetRates();
        return;
      }
      try {
        await this.renderFrame(renderer, context);
      } catch (e) {
        this.looping = false;
        // A frame cut short by a lost device is the loss handler's business, not a failure.
        if (renderer !== this.host.renderer() || (await lostSoon(renderer.gpu))) return;
        this.host.fail(e);
        return;
      }
      this.host.changed();
      requestAnimationFrame(frame);
    };
    requestAnimationFrame(frame);
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
    // A screenshot of a suspended frame may be finishing it (whole).
    await this.settled;
    let frame = this.current;
    if (frame && !this.valid(frame)) {
      this.abandon(frame);
      frame = undefined;
    }
    if (!frame) {
      await this.host.applyBudget();
      this.host.advance(renderer);
      frame = this.current = this.plan(renderer, this.host.samplesPerFrame());
    }
    let settle!: () => void;
    this.settled = new Promise((resolve) => (settle = resolve));
    try {
      const outcome = await this.run(frame, () => this.host.playing() && !document.hidden);
      // Suspended (Pause, a hidden tab): the frame waits in current. Overtaken: the next animation frame plans another.
      if (outcome === 'overtaken') this.abandon(frame);
      if (outcome !== 'done') return;
      this.current = undefined;
      await this.complete(renderer, context, frame);
    } finally {
      settle();
    }
  }

  /** Gives a frame up: the renderer undoes what matters (the real-time ping-pong), the timer forgets its passes (no resolve will read them). */
  private abandon(frame: ViewerFrame): void {
    frame.current?.abandon();
    if (frame.renderer === this.host.renderer()) this.host.timer()?.discard();
    if (this.current === frame) this.current = undefined;
  }

  /** Whether a frame may go on: same renderer, nothing changed what it computes since it was planned. */
  private valid(frame: ViewerFrame): boolean {
    return frame.renderer === this.host.renderer() && frame.renderer.frameGeneration() === frame.generation && frame.renderer.width === frame.width && frame.renderer.height === frame.height && (!frame.current || frame.current.done || frame.current.valid);
  }

  /**
   * A new frame's parts by the settings (a real-time frame, the estimate beside a still view, the
   * estimate alone, or nothing to trace), `spf` samples per pixel each; the camera and the world have moved.
   */
  private plan(renderer: Renderer, spf: number): ViewerFrame {
    const settings = this.host.settings();
    if (!settings.accumulate) renderer.resetAccumulation();
    // The counters restart with the estimate (every camera move too): then the whole count is this frame's.
    const fresh = renderer.accumulationEpoch !== this.lastEpoch;
    const timer = this.host.timer();
    const render = settings.render;
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
      const still = settings.convergeWhenStill && !fresh && this.realTimeFrames > 0;
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
  private async run(frame: ViewerFrame, keepGoing: () => boolean): Promise<'done' | 'suspended' | 'overtaken'> {
    const renderer = frame.renderer;
    for (;;) {
      if (!this.valid(frame)) return 'overtaken';
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
        this.host.changed();
      }
    }
  }

  /** After the last chunk: present, read the counters and the timings, feed the budget. */
  private async complete(renderer: Renderer, context: GPUCanvasContext, frame: ViewerFrame): Promise<void> {
    frame.after?.();
    this.imageDirty = false;
    this.displaying = frame.display;
    if (frame.display === 'frame') this.realTimeFrames++;
    const timer = this.host.timer();
    const t0 = performance.now();
    renderer.present(context.getCurrentTexture(), timer);
    // Reading the counters waits for the present and counts the frame's rays exactly.
    const counts = await renderer.readRayCounts();
    const busyMs = frame.busyMs + (performance.now() - t0);
    const delayMs = this.host.delayMs();
    if (delayMs > 0) await new Promise((resolve) => setTimeout(resolve, delayMs));
    const total = counts.extension + counts.shadow;
    const fresh = renderer.accumulationEpoch !== this.lastEpoch;
    const rays = fresh ? total : total - this.lastRayCount;
    this.lastRayCount = total;
    this.lastEpoch = renderer.accumulationEpoch;
    if (timer) this.gpuPasses = sumByName(await timer.read());
    const render = this.host.settings().render;
    if (render.debugView !== 'none' && performance.now() - this.legendAt > LEGEND_INTERVAL_MS) {
      this.legend = await renderer.debugLegend();
      this.legendAt = performance.now();
    }
    this.frames.push({ at: performance.now(), rays });
    if (this.frames.length > STATS_WINDOW) this.frames.shift();
    if (this.playedAt !== undefined && this.firstFrameMs === undefined) this.firstFrameMs = performance.now() - this.playedAt;
    // The budget hears the frame's GPU time on a real GPU: the timestamps where every pass of it was
    // timed (a frame of a few chunks: the timer has room for them all), else the chunks' wall time.
    // On a software adapter always the wall time: the GPU is the CPU the page shares, and its
    // timestamps leave out the round trips and the load that the user waits for.
    const budget = this.host.budget();
    const gpuTimed = budget?.adapter === 'hardware' && timer !== undefined && frame.chunks <= MAX_TIMED_CHUNKS && this.gpuPasses.length > 0;
    const ms = gpuTimed ? this.gpuPasses.reduce((sum, p) => sum + p.ms, 0) : busyMs;
    if (budget && frame.pixels > 0) {
      budget.observe({ ms, gpuTimed, width: frame.width, height: frame.height, samples: frame.samples * (frame.pixels / (frame.width * frame.height)), at: performance.now() });
    }
  }

  /**
   * Waits until the image is a whole frame: for the frame under way to be done, or, for one that
   * Pause suspended, runs its remaining chunks and presents it (a half-traced real-time frame is no
   * image). Screenshots and readImage call it. `loopGoesOn`: whether the viewer's loop goes on with
   * the frame at the next animation frame (playing, the tab shown).
   */
  async whole(loopGoesOn: () => boolean): Promise<void> {
    for (;;) {
      await this.settled;
      const frame = this.current;
      // Between frames, with the last one presented whole.
      if (!frame && !this.imageDirty) return;
      if (loopGoesOn()) {
        // The loop goes on with it at the next animation frame (its callback was asked for first).
        await new Promise((resolve) => requestAnimationFrame(resolve));
        continue;
      }
      const renderer = this.host.renderer(), context = this.host.context();
      if (!frame || !renderer || !context || !this.valid(frame)) return;
      let settle!: () => void;
      this.settled = new Promise((resolve) => (settle = resolve));
      try {
        if ((await this.run(frame, () => true)) !== 'done') return;
        this.current = undefined;
        await this.complete(renderer, context, frame);
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
