import { describe, expect, it } from 'vitest';
import { adapterKind, ChunkSizer, CHUNK_TARGET_MS, describeFixedScale, displayRateHz, FrameBudget, MIN_SHORT_SIDE, SCALE_STEPS, type FrameBudgetOptions } from './frame-budget.ts';

const CANVAS = { canvasWidth: 1280, canvasHeight: 800 };
const CANVAS_PIXELS = 1280 * 800;
/** SwiftShader on the test machine: about 25 µs per pixel and sample (a 1280×800 frame ≈ 26 s). */
const SWIFTSHADER = 25e-3;
/**
 * An adapter 32 times quicker: every image it can afford has 32 times the pixels (ten steps of √2),
 * so the budget works well above its floor (269 × 168 on this canvas), where it makes the choices it
 * made before it had one for SwiftShader, ten steps up.
 */
const QUICK_CPU = SWIFTSHADER / 32;

/**
 * Runs the viewer's side of the budget against a simulated adapter: each frame costs
 * `msPerPixelSample(frame)` × pixels × samples, frames follow each other back to back (at most 60 a
 * second); `canvas(frame)` may resize the canvas.
 */
function simulate(options: FrameBudgetOptions, msPerPixelSample: (frame: number) => number, frames: number, canvas = (_frame: number) => [options.canvasWidth, options.canvasHeight] as const) {
  const budget = new FrameBudget(options);
  let at = 0;
  const history: { scale: number; samples: number; ms: number; width: number; height: number; changed: boolean }[] = [];
  let last = [options.canvasWidth, options.canvasHeight].join();
  for (let i = 0; i < frames; i++) {
    const [cw, ch] = canvas(i);
    // The viewer tells the budget of a resized canvas before the next frame (viewer.ts resizeCanvas).
    if ([cw, ch].join() !== last) budget.resizeCanvas(cw, ch);
    last = [cw, ch].join();
    const { scale, samplesPerFrame } = budget.choice;
    // The viewer's render size (viewer.ts resizeRenderer).
    const width = Math.max(1, Math.round(cw * scale)), height = Math.max(1, Math.round(ch * scale));
    const ms = msPerPixelSample(i) * width * height * samplesPerFrame;
    // Frames are paced by the display (requestAnimationFrame) when the GPU is quicker.
    at += Math.max(ms, 1000 / 60);
    const changed = budget.observe({ ms, gpuTimed: false, width, height, samples: samplesPerFrame, at });
    history.push({ scale, samples: samplesPerFrame, ms, width, height, changed });
  }
  return { budget, history };
}

describe('adapterKind', () => {
  it('takes the fallback flag or a software renderer by name as software, anything else as a GPU', () => {
    expect(adapterKind({ name: 'SwiftShader Device (Subzero) (0x0000C0DE)' })).toBe('software');
    expect(adapterKind({ name: 'llvmpipe (LLVM 15.0.6, 256 bits)' })).toBe('software');
    expect(adapterKind({ name: 'Some GPU', isFallbackAdapter: true })).toBe('software');
    expect(adapterKind({ name: 'NVIDIA H200' })).toBe('hardware');
    expect(adapterKind({ name: 'Intel(R) UHD Graphics 620' })).toBe('hardware');
  });
});

describe('displayRateHz', () => {
  it('is the median interval, so late callbacks do not pull it down, clamped to plausible displays', () => {
    expect(displayRateHz([16.7, 16.6, 16.7, 250, 16.8, 16.6, 400])).toBeCloseTo(1000 / 16.7, 5);
    expect(displayRateHz([6.94, 6.95, 6.94])).toBeCloseTo(144, 0);
    expect(displayRateHz([])).toBe(60);
    expect(displayRateHz([1000, 1000])).toBe(24);
  });
});

describe('FrameBudget', () => {
  it('starts a software adapter at its floor and settles at a few frames per second', () => {
    const { budget, history } = simulate({ adapter: 'software', ...CANVAS }, () => QUICK_CPU, 40);
    // The smallest image it may show: the short side at the floor (2^(−9/4) · 800 = 168).
    expect(history[0]!.height).toBe(168);
    expect(budget.choice.scale).toBeGreaterThan(0.4);
    const settled = history.slice(-10);
    for (const f of settled) {
      expect(f.ms).toBeLessThanOrEqual((1.25 * 1000) / 3);
      expect(f.ms).toBeGreaterThan(((0.8 / Math.SQRT2) * 1000) / 3);
    }
    // The one jump after the first frame, then nothing: the history is dropped once.
    expect(history.filter((f) => f.changed)).toHaveLength(1);
    expect(budget.targetFps).toBe(3);
    expect(budget.describe()).toMatch(/^budget: 0\.\d+× \(software adapter, 3 fps target; last frame \d+ ms\)$/);
    expect(budget.describe(false)).toMatch(/^budget: 0\.\d+× \(software adapter, 3 fps target\)$/);
  });

  it('holds the display rate on a real GPU, adding samples at full resolution when there is time to spare', () => {
    // A fast GPU: 1 ns per pixel-sample, a 1280×800 frame in 1 ms: full scale, the most samples.
    const fast = simulate({ adapter: 'hardware', displayHz: 60, ...CANVAS }, () => 1e-6, 400);
    expect(fast.budget.choice).toEqual({ scale: 1, samplesPerFrame: 4 });
    expect(fast.budget.describe()).toContain('· 4 spp (display 60 Hz, 60 fps target');
    // A weak GPU: 40 ns per pixel-sample (41 ms at full size): scaled to fit 16.7 ms.
    const weak = simulate({ adapter: 'hardware', displayHz: 60, ...CANVAS }, () => 40e-6, 60);
    const last = weak.history.slice(-10);
    for (const f of last) expect(f.ms).toBeLessThanOrEqual(1.25 * (1000 / 60));
    expect(weak.budget.choice.scale).toBeLessThan(1);
    expect(weak.budget.choice.samplesPerFrame).toBe(1);
    // A 144 Hz display aims at 6.9 ms instead.
    const high = simulate({ adapter: 'hardware', displayHz: 144, ...CANVAS }, () => 40e-6, 60);
    expect(high.budget.choice.scale).toBeLessThan(weak.budget.choice.scale);
    for (const f of high.history.slice(-10)) expect(f.ms).toBeLessThanOrEqual(1.25 * (1000 / 144));
  });

  it('does not oscillate when the cost sits at a step boundary or the frames are noisy', () => {
    // The cost that puts the frame exactly on the target at some step, with ±15 % noise.
    const noisy = (i: number) => QUICK_CPU * (1 + 0.15 * Math.sin(i * 2.1));
    const { history } = simulate({ adapter: 'software', ...CANVAS }, noisy, 200);
    expect(history.filter((f) => f.changed).length).toBeLessThanOrEqual(2);
    for (let s = 0; s < SCALE_STEPS.length; s++) {
      const cost = (1000 / 3 / (CANVAS_PIXELS * SCALE_STEPS[s]! ** 2)) * 1.0;
      const run = simulate({ adapter: 'software', ...CANVAS }, () => cost, 100);
      expect(run.history.filter((f) => f.changed).length).toBeLessThanOrEqual(1);
    }
  });

  it('settles on a machine whose load comes and goes (frames anywhere from half to twice their cost)', () => {
    // A seeded generator (mulberry32): the same noise every run.
    let state = 12345;
    const random = () => {
      state = (state + 0x6d2b79f5) >>> 0;
      let t = state;
      t = Math.imul(t ^ (t >>> 15), t | 1);
      t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
      return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
    };
    const noisy = () => QUICK_CPU * 2 ** (2 * random() - 1);
    const { history } = simulate({ adapter: 'software', ...CANVAS }, noisy, 600);
    const changes = history.map((f, i) => ({ ...f, i })).filter((f) => f.changed);
    // 600 frames at about 3 a second: over three minutes. A handful of resizes, most of them early,
    // none in the last minute and a half (the waits before stepping up have grown).
    expect(changes.length).toBeLessThanOrEqual(8);
    expect(changes.filter((f) => f.i >= 300)).toHaveLength(0);
  });

  it('follows the view: a costlier view scales down soon, a cheaper one scales up after a wait', () => {
    // The view changes at frame 30 to one 4× as costly, and at frame 80 back.
    const cost = (i: number) => (i >= 30 && i < 80 ? 4 * QUICK_CPU : QUICK_CPU);
    const { history } = simulate({ adapter: 'software', ...CANVAS }, cost, 160);
    const before = history[29]!.scale;
    // Down within a few frames of the change, by the whole factor at once (one resize, not a staircase).
    const downAt = history.findIndex((f, i) => i >= 30 && f.scale < before);
    expect(downAt).toBeGreaterThan(30);
    expect(downAt).toBeLessThanOrEqual(30 + 4);
    expect(history[downAt]!.scale).toBeCloseTo(before / 2, 5);
    // Back up after the view gets cheap again, and not before it did.
    expect(history.slice(downAt, 80).every((f) => f.scale === history[downAt]!.scale)).toBe(true);
    // Within one step of where it was: going up needs a prediction under 0.8 × the target, where
    // the first jump aimed at 0.9 × (the hysteresis).
    expect(history[159]!.scale).toBeGreaterThanOrEqual(before * 2 ** -0.25 - 1e-9);
    expect(history[159]!.scale).toBeLessThanOrEqual(before + 1e-9);
    expect(history[159]!.ms).toBeLessThanOrEqual(1000 / 3);
  });

  it('a single slow frame (a compile, an upload) moves nothing', () => {
    const cost = (i: number) => (i === 20 ? 10 * QUICK_CPU : QUICK_CPU);
    const { history } = simulate({ adapter: 'software', ...CANVAS }, cost, 40);
    expect(history.filter((f) => f.changed)).toHaveLength(1);
  });

  it('never goes below the samples per frame the user asked for', () => {
    const { budget } = simulate({ adapter: 'software', ...CANVAS, baseSamples: 2 }, () => QUICK_CPU, 40);
    expect(budget.choice.samplesPerFrame).toBe(2);
  });

  it('holds its floor on a very slow adapter: the frame rate gives, not the resolution', () => {
    // This machine's SwiftShader would fit 3 fps at 13,000 pixels (144 × 90: a mosaic); an adapter
    // 40 times slower still, or a weak GPU at a 60 Hz display, at a few hundred.
    for (const [options, cost] of [
      [{ adapter: 'software', ...CANVAS }, SWIFTSHADER],
      [{ adapter: 'software', ...CANVAS }, 1],
      [{ adapter: 'hardware', displayHz: 60, ...CANVAS }, 5e-3],
    ] as const) {
      const { budget, history } = simulate(options, () => cost, 60);
      for (const f of history) expect(Math.min(f.width, f.height)).toBeGreaterThanOrEqual(MIN_SHORT_SIDE);
      // At the floor (256 × 160 would be under it: the steps give 269 × 168), and slower than the target.
      expect(history.at(-1)).toMatchObject({ width: 269, height: 168 });
      expect(history.at(-1)!.ms).toBeGreaterThan(budget.targetMs);
      expect(budget.describe(false)).toMatch(/^budget: 0\.21× floor 160 px \(/);
    }
    // Where the floor fits, the account does not mention it.
    expect(simulate({ adapter: 'software', ...CANVAS }, () => QUICK_CPU, 40).budget.describe(false)).not.toMatch(/floor/);
  });

  it('keeps the floor as the canvas changes: a smaller canvas raises the scale at once; one shorter than the floor renders whole', () => {
    // The window halved at frame 20 (640 × 400): 0.21 of it would be 84 rows.
    const { history } = simulate({ adapter: 'software', ...CANVAS }, () => SWIFTSHADER, 40, (i) => (i < 20 ? [1280, 800] : [640, 400]));
    expect(history[20]).toMatchObject({ width: 269, height: 168 });
    for (const f of history.slice(20)) expect(f.height).toBeGreaterThanOrEqual(MIN_SHORT_SIDE);
    const tiny = simulate({ adapter: 'software', canvasWidth: 300, canvasHeight: 120 }, () => SWIFTSHADER, 20);
    expect(tiny.history.every((f) => f.scale === 1)).toBe(true);
  });

  it('keeps the cost when the canvas grows: a canvas rendered whole, then 1280 × 800, does not render whole', () => {
    // 300 × 120 is shorter than the floor, so it renders at 1× (0.9 s a frame here); 1280 × 800 at 1×
    // would take 26 s. The first frame after the resize already has the floor's size, or one near it.
    for (const grownAt of [0, 10]) {
      const { history, budget } = simulate({ adapter: 'software', canvasWidth: 300, canvasHeight: 120 }, () => SWIFTSHADER, 30, (i) => (i < grownAt || grownAt === 0 && i === 0 ? [300, 120] : [1280, 800]));
      const after = history.slice(Math.max(1, grownAt));
      for (const f of after) expect(f.ms, `frame of ${f.width} × ${f.height}`).toBeLessThan(4 * budget.targetMs);
      for (const f of after) expect(Math.min(f.width, f.height)).toBeGreaterThanOrEqual(MIN_SHORT_SIDE);
    }
    // Before any frame, a software adapter starts at the new canvas's floor.
    const fresh = new FrameBudget({ adapter: 'software', canvasWidth: 300, canvasHeight: 120 });
    expect(fresh.choice.scale).toBe(1);
    expect(fresh.resizeCanvas(1280, 800)).toBe(true);
    expect(Math.round(800 * fresh.choice.scale)).toBe(168);
  });
});

describe('describeFixedScale', () => {
  it('says the budget is off and why', () => {
    expect(describeFixedScale(0.5)).toBe('budget: off (resolution fixed at 0.5×)');
  });
});

describe('ChunkSizer', () => {
  it('cuts a slow frame into bands of whole workgroup rows of about the target time, and a fast one not at all', () => {
    const width = 640, height = 400;
    // Before any measurement, on a GPU: about an eighth of the image, in whole workgroup rows.
    const sizer = new ChunkSizer('hardware');
    expect(sizer.next(width, height, height, 1)).toEqual({ rows: 48, columns: width });
    // 1 µs per pixel-sample at 2 spp: 40 / (1e-3 × 640 × 2) = 31 rows → 24.
    sizer.observe(width * 8, 2, 1e-3 * width * 8 * 2);
    const chunk = sizer.next(width, height, height, 2);
    expect(chunk).toEqual({ rows: 24, columns: width });
    expect(chunk.rows * width * 2 * 1e-3).toBeLessThanOrEqual(CHUNK_TARGET_MS);
    // 0.1 µs per pixel-sample: 64 µs a row, the whole image in one submission.
    const fast = new ChunkSizer('hardware');
    fast.observe(width * 56, 1, 1e-4 * width * 56);
    expect(fast.next(width, height, height, 1)).toEqual({ rows: height, columns: width });
  });

  it('cuts a band into pieces where one workgroup row across is too slow (a software adapter)', () => {
    const width = 1280, height = 800;
    // A software adapter starts with one workgroup row, a piece of it.
    const sizer = new ChunkSizer('software');
    expect(sizer.next(width, height, height, 1)).toEqual({ rows: 8, columns: 64 });
    // 25 µs per pixel-sample: 40 ms is 1600 pixels, 8 rows × 200 columns.
    sizer.observe(8 * 64, 1, 25e-3 * 8 * 64);
    const chunk = sizer.next(width, height, height, 1);
    expect(chunk).toEqual({ rows: 8, columns: 200 });
    expect(chunk.rows * chunk.columns * 25e-3).toBeLessThanOrEqual(CHUNK_TARGET_MS);
    // The end of a band: no sliver of a piece left over.
    expect(sizer.next(width, height, height, 1, 204)).toEqual({ rows: 8, columns: 204 });
  });

  it('keeps chunks mostly work when the submission round trip itself is slow', () => {
    // A loaded browser: 30 ms to answer an empty submission; the work is 25 µs per pixel-sample.
    const sizer = new ChunkSizer('software');
    sizer.observeIdle(30);
    for (let i = 0; i < 20; i++) {
      const { rows, columns } = sizer.next(1280, 800, 800, 1);
      sizer.observe(rows * columns, 1, 30 + 25e-3 * rows * columns);
    }
    const { rows, columns } = sizer.next(1280, 800, 800, 1);
    const workMs = 25e-3 * rows * columns;
    // At least as much work as round trip (aiming at twice the round trip, 60 ms), and not beyond it.
    expect(workMs).toBeGreaterThanOrEqual(30 - 25e-3 * 64);
    expect(workMs + 30).toBeLessThanOrEqual(60);
    expect(sizer.splits(1280, 800, 1)).toBe(true);
  });

  it('never leaves a sliver under a workgroup row for a submission of its own', () => {
    const sizer = new ChunkSizer('hardware');
    sizer.observe(100 * 8, 1, 40);
    expect(sizer.next(100, 100, 12, 1).rows).toBe(12);
    expect(sizer.next(100, 100, 3, 1).rows).toBe(3);
    expect(sizer.next(100, 100, 0, 1)).toEqual({ rows: 0, columns: 0 });
  });
});
