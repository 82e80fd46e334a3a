/**
 * The viewer's frame budget (Lantern issue #16): which resolution scale (and how many samples per
 * frame) holds an interactive rate on the adapter at hand, and how much of a frame's path tracing
 * goes into one submission. Pure: the viewer feeds it measured times and applies its choices.
 *
 * The target: a few frames per second on a software adapter (SwiftShader traces on the CPU the page
 * runs on), the display's rate on a real GPU. The cost model is that a frame's time is proportional
 * to its pixels times its samples (path tracing and the denoiser's passes both are per pixel), with
 * the constant measured from the last few frames, so the first frame calibrates and the budget jumps
 * straight to the scale that fits, and later frames follow the view (a wall close up costs less than
 * a long corridor).
 *
 * Every change of scale resizes the image, and a resize drops the real-time chain's history (the
 * denoiser's buffers are per pixel and reallocated: renderer/recipes/real-time.ts ensureBuffers) and restarts
 * the progressive estimate, so the budget changes the scale rarely: only over a hysteresis band
 * (down when frames are clearly over the target, up only when the next step up is predicted to stay
 * clearly under it), after several frames at the current scale, and up only after a longer wait.
 * The steps are powers of 2^(1/4) in scale (2^(1/2) in pixels), so one step up costs a predictable
 * 41 % more and the bands cannot chase each other: going down needs the median of three frames over
 * 1.25 × the target, going up a prediction under 0.8 × the target from the costliest of the last six
 * frames, i.e. every one of them under 0.57 × the target now. Where the load comes and goes (a
 * software adapter shares the CPU with everything else) a step up taken back within 15 s doubles
 * the wait before the next, so the scale settles instead of following the noise (measured in the
 * page on SwiftShader with the median alone: a resize every few seconds).
 *
 * Below a floor the budget lowers the frame rate instead of the resolution: the image's short side
 * never goes under MIN_SHORT_SIDE pixels (or the canvas's own, where that is shorter). Without it a
 * CPU adapter took E1M1 to 21 × 20 pixels and the Cornell box to 60 × 55 (Lantern issue #27),
 * mosaics in which nothing can be recognised; the world keeps real time at any frame rate
 * (app/frame-clock.ts), so a slow frame costs smoothness, not the game.
 */
import { median } from '../math/median.ts';

/** What kind of adapter renders: a CPU implementation (SwiftShader, WARP, llvmpipe) or a real GPU. */
export type AdapterKind = 'software' | 'hardware';

/** Frames per second the budget aims for on a software adapter. */
export const SOFTWARE_TARGET_FPS = 3;
/** Display rates outside this range are taken as measurement noise and clamped. */
const DISPLAY_HZ_RANGE: readonly [number, number] = [24, 240];
/** The display rate assumed until one is measured. */
export const DEFAULT_DISPLAY_HZ = 60;

/** The resolution scales the budget chooses from: 2^(-k/4), from 1 down to 1/32. */
export const SCALE_STEPS: readonly number[] = Array.from({ length: 21 }, (_, k) => 2 ** (-k / 4));
/**
 * The fewest pixels on the image's short side the budget renders: half the 320 × 200 that the
 * Doom and Wolfenstein 3D maps this viewer plays were drawn for, where a door, a sprite or a
 * texture's pattern is still several pixels across (a 16:10 canvas gets 256 × 160 at least).
 */
export const MIN_SHORT_SIDE = 160;
/** Samples per frame the budget adds at full scale when a real GPU has time to spare. */
export const MAX_BUDGET_SAMPLES = 4;

/** A frame is over budget above this multiple of the target... */
const OVER = 1.25;
/** ...and the next step up is taken only when it is predicted below this multiple. */
const UNDER = 0.8;
/** A jump down aims this far under the target, so the frame after it is not at the edge again. */
const AIM = 0.9;
/** Frames measured at a scale before the budget judges it. */
const FRAMES_TO_JUDGE = 3;
/** Frames, and milliseconds, at a scale before the budget tries a step up; every frame of them must predict the step fits. */
const FRAMES_BEFORE_UP = 6;
const MS_BEFORE_UP = 2000;
/**
 * A step up that had to be taken back within this long doubles the wait before the next one (up
 * to MAX_MS_BEFORE_UP): on a machine whose load comes and goes, the budget settles instead of
 * resizing (and dropping the history) every few seconds.
 */
const REVERSAL_MS = 15_000;
const MAX_MS_BEFORE_UP = 64_000;

/** Whether an adapter renders on the CPU: the spec's isFallbackAdapter, or a software renderer's name. */
export function adapterKind(info: { readonly name: string; readonly isFallbackAdapter?: boolean | undefined }): AdapterKind {
  if (info.isFallbackAdapter) return 'software';
  return /swiftshader|llvmpipe|lavapipe|softpipe|microsoft basic render|\bwarp\b/i.test(info.name) ? 'software' : 'hardware';
}

/**
 * The display's refresh rate from requestAnimationFrame intervals (ms): the median interval, so a
 * few late callbacks (the page starting, a scene uploading) do not pull it down.
 */
export function displayRateHz(intervalsMs: readonly number[]): number {
  const ok = intervalsMs.filter((ms) => Number.isFinite(ms) && ms > 0);
  if (ok.length === 0) return DEFAULT_DISPLAY_HZ;
  const hz = 1000 / median(ok);
  return Math.min(DISPLAY_HZ_RANGE[1], Math.max(DISPLAY_HZ_RANGE[0], hz));
}

/** One measured frame. */
export interface FrameSample {
  /** GPU milliseconds of the frame (timestamp queries), or wall milliseconds of its submissions to onSubmittedWorkDone. */
  readonly ms: number;
  /** Whether `ms` came from timestamp queries. */
  readonly gpuTimed: boolean;
  /** The image rendered, pixels (the render size, not the canvas's). */
  readonly width: number;
  readonly height: number;
  /** Paths per pixel traced. */
  readonly samples: number;
  /** When the frame finished (performance.now()), for the wait before a step up. */
  readonly at: number;
}

export interface BudgetChoice {
  /** Render resolution relative to the canvas's device pixels. */
  readonly scale: number;
  /** Paths per pixel each frame. */
  readonly samplesPerFrame: number;
}

export interface FrameBudgetOptions {
  readonly adapter: AdapterKind;
  /** The display's refresh rate (displayRateHz); the target on a real GPU. */
  readonly displayHz?: number;
  /** The canvas at scale 1, device pixels (the floor and the software adapter's first scale; frames update them). */
  readonly canvasWidth: number;
  readonly canvasHeight: number;
  /** The samples per frame the user asked for: the budget never goes below it. */
  readonly baseSamples?: number;
}

/**
 * Decides the scale and the samples per frame from measured frames. `choice` is what the next frame
 * should use; `observe` reports a frame rendered with the choice that was current when it began.
 */
export class FrameBudget {
  readonly adapter: AdapterKind;
  readonly displayHz: number;
  private step: number;
  private samples: number;
  private baseSamples: number;
  /** Milliseconds per pixel and sample of the last frames (at most FRAMES_BEFORE_UP; since the last change, but one). */
  private costs: number[] = [];
  private changedAt: number | undefined;
  /** When the last step up was taken, and the wait before the next one (doubled by each reversal). */
  private upAt: number | undefined;
  private upWaitMs = MS_BEFORE_UP;
  private framesSinceChange = 0;
  private calibrated = false;
  private last?: FrameSample;
  /** The smallest scale's step: the image's short side at it is MIN_SHORT_SIDE or more (floorStep). */
  private floor: number;
  /** Whether the last fit wanted a scale below the floor (the frame rate gave instead). */
  private floored = false;

  constructor(options: FrameBudgetOptions) {
    this.adapter = options.adapter;
    this.displayHz = options.displayHz ?? DEFAULT_DISPLAY_HZ;
    this.baseSamples = Math.max(1, Math.floor(options.baseSamples ?? 1));
    this.samples = this.baseSamples;
    this.floor = floorStep(Math.min(options.canvasWidth, options.canvasHeight));
    // A real GPU starts at full resolution (the submissions are short whatever the frame costs); a
    // software adapter at the floor, the smallest image it may show, since one frame at full size
    // can take minutes there.
    this.step = options.adapter === 'software' ? this.floor : 0;
  }

  /** Milliseconds per frame the budget aims for. */
  get targetMs(): number {
    return this.adapter === 'software' ? 1000 / SOFTWARE_TARGET_FPS : 1000 / this.displayHz;
  }

  get targetFps(): number {
    return 1000 / this.targetMs;
  }

  get choice(): BudgetChoice {
    return { scale: SCALE_STEPS[this.step]!, samplesPerFrame: this.samples };
  }

  /** The last frame reported. */
  get lastFrame(): FrameSample | undefined {
    return this.last;
  }

  /** The user's samples per frame changed: the budget's floor follows (above it, the budget's own choice stays). */
  setBaseSamples(samples: number): void {
    this.baseSamples = Math.max(1, Math.floor(samples));
    this.samples = Math.max(this.samples, this.baseSamples);
  }

  /**
   * The canvas was resized (device pixels at scale 1): the floor follows it, and the next frame keeps
   * what it would cost rather than the scale. A smaller canvas may raise the scale to the new floor at
   * once; a larger one lowers it at once where the frames measured so far predict the new size over
   * budget (a software adapter that rendered a 300 × 120 canvas whole must not try 1280 × 800 whole:
   * that frame takes minutes); before any frame, a software adapter starts at the new floor. Going up
   * waits for frames, as always. Returns whether the choice changed.
   */
  resizeCanvas(width: number, height: number): boolean {
    if (!(width > 0 && height > 0)) return false;
    this.floor = floorStep(Math.min(width, height));
    if (this.step > this.floor) return this.moveTo({ step: this.floor, samples: this.baseSamples }, this.changedAt ?? 0);
    if (!this.calibrated) return this.adapter === 'software' && this.step !== this.floor ? this.moveTo({ step: this.floor, samples: this.samples }, 0) : false;
    const cost = median(this.costs);
    const pixelsAtScale1 = width * height;
    if (cost * pixelsAtScale1 * SCALE_STEPS[this.step]! ** 2 * this.samples <= OVER * this.targetMs) return false;
    const to = this.fit(pixelsAtScale1, cost);
    return to.step > this.step || to.samples < this.samples ? this.moveTo(to, this.changedAt ?? 0) : false;
  }

  /** Reports a frame; returns whether the choice changed (the viewer then resizes before the next frame). */
  observe(frame: FrameSample): boolean {
    const pixels = frame.width * frame.height;
    if (!(frame.ms > 0 && pixels > 0 && frame.samples > 0)) return false;
    this.last = frame;
    this.costs.push(frame.ms / (pixels * frame.samples));
    if (this.costs.length > FRAMES_BEFORE_UP) this.costs.shift();
    this.framesSinceChange++;
    this.changedAt ??= frame.at;
    const scale = SCALE_STEPS[this.step]!;
    const pixelsAtScale1 = pixels / scale ** 2;
    // The canvas may have been resized since: its short side now, as this frame was rendered at `scale`.
    this.floor = floorStep(Math.min(frame.width, frame.height) / scale);
    if (this.step > this.floor) return this.moveTo({ step: this.floor, samples: this.baseSamples }, frame.at);
    if (!this.calibrated) {
      // The first frame sets the cost: jump to what fits at once (down or up).
      this.calibrated = true;
      return this.moveTo(this.fit(pixelsAtScale1, median(this.costs)), frame.at);
    }
    if (this.framesSinceChange < FRAMES_TO_JUDGE) return false;
    // The median of the last frames: one slow frame (a scene update, a compile) moves nothing.
    const cost = median(this.costs.slice(-FRAMES_TO_JUDGE));
    const predict = (step: number, samples: number) => cost * pixelsAtScale1 * SCALE_STEPS[step]! ** 2 * samples;
    const now = predict(this.step, this.samples);
    if (now > OVER * this.targetMs) {
      // Taken back soon after a step up: wait longer before the next.
      if (this.upAt !== undefined && frame.at - this.upAt < REVERSAL_MS) this.upWaitMs = Math.min(MAX_MS_BEFORE_UP, 2 * this.upWaitMs);
      this.upAt = undefined;
      return this.moveTo(this.fit(pixelsAtScale1, cost), frame.at);
    }
    const waited = this.framesSinceChange >= FRAMES_BEFORE_UP && this.costs.length >= FRAMES_BEFORE_UP && frame.at - this.changedAt >= this.upWaitMs;
    if (!waited) return false;
    // Up one step at a time, resolution first, then (at full resolution) samples, and only when the
    // costliest of the last frames predicts it fits: noise delays a step up, never causes one.
    const worst = Math.max(...this.costs);
    const fitsUp = (step: number, samples: number) => worst * pixelsAtScale1 * SCALE_STEPS[step]! ** 2 * samples < UNDER * this.targetMs;
    const maxSamples = Math.max(MAX_BUDGET_SAMPLES, this.baseSamples);
    let to: { step: number; samples: number } | undefined;
    if (this.step > 0 && fitsUp(this.step - 1, this.samples)) to = { step: this.step - 1, samples: this.samples };
    else if (this.step === 0 && this.samples < maxSamples && fitsUp(0, this.samples * 2)) to = { step: 0, samples: Math.min(this.samples * 2, maxSamples) };
    if (!to) return false;
    this.upAt = frame.at;
    this.floored = false;
    return this.moveTo(to, frame.at);
  }

  /**
   * The one-line account of the choice: `budget: 0.35× (software adapter, 3 fps target; last frame
   * 310 ms)`; without the last frame (`lastFrame` false) it changes only with the choice, which a
   * status line that must not reflow every frame wants.
   */
  describe(lastFrame = true): string {
    const { scale, samplesPerFrame } = this.choice;
    const spp = samplesPerFrame > this.baseSamples ? ` · ${samplesPerFrame} spp` : '';
    const why = this.adapter === 'software' ? `software adapter, ${formatNumber(this.targetFps)} fps target` : `display ${formatNumber(this.displayHz)} Hz, ${formatNumber(this.targetFps)} fps target`;
    const last = this.last ? `last frame ${formatMs(this.last.ms)}${this.last.gpuTimed ? ' GPU' : ''}` : 'measuring';
    // At the floor with frames over the target: the frame rate gives, not the resolution.
    const floor = this.floored && this.step === this.floor ? ` floor ${MIN_SHORT_SIDE} px` : '';
    return `budget: ${formatScale(scale)}${spp}${floor} (${why}${lastFrame ? `; ${last}` : ''})`;
  }

  /**
   * The largest scale (and, at full scale, samples) whose predicted frame fits AIM × the target; at
   * the smallest, the floor (`floored` says so: the frame rate gives instead).
   */
  private fit(pixelsAtScale1: number, cost: number): { step: number; samples: number } {
    const fits = (step: number, samples: number) => cost * pixelsAtScale1 * SCALE_STEPS[step]! ** 2 * samples <= AIM * this.targetMs;
    this.floored = false;
    // Samples above the user's come off first: resolution matters more than fewer noisy frames.
    for (let step = 0; step <= this.floor; step++) {
      if (fits(step, this.baseSamples)) {
        if (step > 0) return { step, samples: this.baseSamples };
        let samples = this.baseSamples;
        while (samples * 2 <= Math.max(MAX_BUDGET_SAMPLES, this.baseSamples) && fits(0, samples * 2) && samples * 2 <= this.samples) samples *= 2;
        return { step: 0, samples };
      }
    }
    this.floored = true;
    return { step: this.floor, samples: this.baseSamples };
  }

  private moveTo(to: { step: number; samples: number }, at: number): boolean {
    if (to.step === this.step && to.samples === this.samples) return false;
    this.step = to.step;
    this.samples = to.samples;
    this.costs = this.costs.slice(-1);
    this.framesSinceChange = 0;
    this.changedAt = at;
    return true;
  }
}

/** The budget's account when the user fixed the resolution (the panel's scale, or a `scale=` link parameter). */
export function describeFixedScale(scale: number): string {
  return `budget: off (resolution fixed at ${formatScale(scale)})`;
}

/** Target milliseconds per submission: short enough that input, Pause and setting changes wait at most this long. */
export const CHUNK_TARGET_MS = 40;
/** Bands are whole workgroup rows (the tracing kernels' @workgroup_size is 8 × 8). */
export const CHUNK_ROW_MULTIPLE = 8;

/** The next submission's piece of the image: a band of `rows` rows, `columns` wide (the whole width unless one band is too slow). */
export interface Chunk {
  readonly rows: number;
  readonly columns: number;
}

/**
 * How much of a frame's path tracing goes into the next submission: measured time per pixel and
 * sample over the last submissions, aiming at CHUNK_TARGET_MS. A chunk is a band of whole workgroup
 * rows across the image, or, where even one workgroup row across is too slow (SwiftShader on a wide
 * canvas: 8 × 1280 pixels take a quarter of a second), a piece of such a row. Before anything is
 * measured: an eighth of the image on a real GPU, one workgroup row on a software adapter.
 */
export class ChunkSizer {
  /** Milliseconds per pixel-sample of the work alone, smoothed over submissions (undefined until measured). */
  private cost?: number;
  /** Milliseconds of a submission's round trip without work (submit to onSubmittedWorkDone of nothing). */
  private overheadMs = 0;

  constructor(
    private readonly adapter: AdapterKind = 'hardware',
    private readonly targetMs: number = CHUNK_TARGET_MS,
  ) {}

  /**
   * What a chunk aims at: the target, or twice the round trip where that is longer (a loaded browser
   * can take tens of milliseconds to answer an empty submission), so at least half of each
   * submission's time is work: chunks sized from the target alone would shrink toward nothing.
   */
  private get aimMs(): number {
    return Math.max(this.targetMs, 2 * this.overheadMs);
  }

  /**
   * The next chunk of an image `width` × `height` at `samples` per pixel, with `remainingRows` rows
   * left (`remainingColumns` of the current band, when a band is under way: its height stays).
   */
  next(width: number, height: number, remainingRows: number, samples: number, remainingColumns = width): Chunk {
    if (remainingRows <= 0) return { rows: 0, columns: 0 };
    const pixels = this.cost === undefined ? (this.adapter === 'software' ? 0 : (width * height) / 8) : (this.aimMs - this.overheadMs) / (this.cost * samples);
    const wanted = pixels / width;
    const rows = Math.max(CHUNK_ROW_MULTIPLE, Math.floor(wanted / CHUNK_ROW_MULTIPLE) * CHUNK_ROW_MULTIPLE);
    // No sliver left over for a submission of its own.
    const bandRows = rows >= remainingRows || remainingRows - rows < CHUNK_ROW_MULTIPLE ? remainingRows : rows;
    if (wanted >= CHUNK_ROW_MULTIPLE) return { rows: bandRows, columns: width };
    // Even a workgroup row across is too much: a piece of one, in whole workgroups.
    const pieceRows = remainingRows - CHUNK_ROW_MULTIPLE < CHUNK_ROW_MULTIPLE ? remainingRows : CHUNK_ROW_MULTIPLE;
    const across = this.cost === undefined ? CHUNK_ROW_MULTIPLE * 8 : pixels / pieceRows;
    const columns = Math.max(CHUNK_ROW_MULTIPLE, Math.floor(across / CHUNK_ROW_MULTIPLE) * CHUNK_ROW_MULTIPLE);
    return { rows: pieceRows, columns: columns >= remainingColumns || remainingColumns - columns < CHUNK_ROW_MULTIPLE ? remainingColumns : columns };
  }

  /** Whether the last chunk asked for was less than a whole image (the viewer then measures the round trip now and then). */
  splits(width: number, height: number, samples: number): boolean {
    const chunk = this.next(width, height, height, samples);
    return chunk.rows < height || chunk.columns < width;
  }

  /** Reports the round trip of an empty submission (ms). */
  observeIdle(ms: number): void {
    if (!(ms >= 0)) return;
    this.overheadMs = this.overheadMs === 0 ? ms : 0.5 * this.overheadMs + 0.5 * ms;
  }

  /** Reports a submission of `pixels` × `samples` that took `ms` (submit to onSubmittedWorkDone). */
  observe(pixels: number, samples: number, ms: number): void {
    if (!(pixels > 0 && samples > 0 && ms >= 0)) return;
    // The work's share: what the round trip alone does not explain (at least a tenth, so noise in the round trip cannot make work free).
    const cost = Math.max(ms - this.overheadMs, 0.1 * ms) / (pixels * samples);
    // Quick to follow a costlier view (down at once), slower to trust a cheap one.
    this.cost = this.cost === undefined || cost > this.cost ? cost : 0.5 * this.cost + 0.5 * cost;
  }
}

/**
 * The step of the smallest scale whose image keeps MIN_SHORT_SIDE pixels on a canvas whose short
 * side is `shortSide` (the viewer rounds the render size: so does this); 0 for a canvas shorter than that.
 */
function floorStep(shortSide: number): number {
  let step = 0;
  while (step + 1 < SCALE_STEPS.length && Math.round(shortSide * SCALE_STEPS[step + 1]!) >= MIN_SHORT_SIDE) step++;
  return step;
}

/** Two significant figures, no trailing zeros: 0.35×, 0.125× is 0.13×, 1×. */
function formatScale(scale: number): string {
  return `${Number(scale.toPrecision(2))}×`;
}

function formatNumber(x: number): string {
  return String(Number(x.toPrecision(3)));
}

function formatMs(ms: number): string {
  return ms >= 10_000 ? `${(ms / 1000).toFixed(1)} s` : ms >= 100 ? `${Math.round(ms)} ms` : `${Number(ms.toPrecision(2))} ms`;
}
