/**
 * `lantern render` in frame mode (--denoise, --temporal, --frames, --path, --mode hybrid): a real-time
 * recipe (Renderer.renderFrame: the denoiser's chain or the hybrid recipe) run frame by frame, --spp samples per frame, the camera still or following
 * a camera path; each frame written as PNG and/or EXR, GPU milliseconds per pass in the report.
 */
import { join } from 'node:path';
import { rmse } from '../../image/compare.ts';
import { GpuTimer } from '../../gpu/timestamps.ts';
import type { Renderer } from '../../renderer/renderer.ts';
import { cameraAt, frameTime, parseCameraPath, type CameraPath } from '../../scene/camera-path.ts';
import type { Camera } from '../../scene/types.ts';
import { isEmptyUpdate } from '../../scene/dynamics.ts';
import type { World } from '../../world/world.ts';
import { readDebugRgb } from '../output-files.ts';
import { FrameWriter } from '../frame-writer.ts';
import { readJsonFile } from '../user-files.ts';
import { median } from '../../math/median.ts';
import { isFrameRecipe, recipeFor, type Recipe, type RecipeIntent } from '../../renderer/recipes/recipe.ts';
import { DEFAULT_SETTINGS } from '../../renderer/settings.ts';
import { mergeSettings } from '../../renderer/settings-schema.ts';
import { settingsFromOptions } from '../setting-options.ts';
import { LanternError } from '../../errors.ts';

export interface FrameModeOptions {
  readonly denoise?: boolean;
  readonly temporal?: boolean;
  /** --restir: a real-time frame's direct light; like --temporal, the switch turns frame mode on. */
  readonly restir?: boolean;
  readonly path?: string;
  /** The --path file, read and checked before the GPU started (render.ts checkRenderOptions). */
  readonly cameraPath?: CameraPath;
  /** --frames: a count (frames 0 to n − 1, the option's first meaning) or a list of frames (FrameList: `0-29`, `1-30,47`). */
  readonly frames?: number | FrameList;
  /** --path-frames: with a list of frames and --path, how many frames the whole path is cut into (default 30). */
  readonly pathFrames?: number;
  /** --mode: the hybrid recipe is a real-time recipe, always rendered in frame mode. */
  readonly mode?: string;
  /** Seconds of frames rendered and thrown away first, so that the GPU's clocks are up when timing starts. */
  readonly warmup?: number;
  /** --fps: frames per second of scene time without a path (the automatic exposure adapts over it too). */
  readonly fps?: number;
}

/** What the options ask of recipeFor beyond the settings: frames in time with --frames or --path. */
export const frameIntent = (o: FrameModeOptions): RecipeIntent => ({ frames: o.frames !== undefined || o.path !== undefined });

/**
 * The recipe the options ask for, by the rule the viewer follows (renderer/recipes/recipe.ts): the
 * settings they give over the defaults, a switch not given being off, and frames in time with
 * --frames or --path.
 */
export function recipeOf(o: FrameModeOptions): Recipe {
  return recipeFor(mergeSettings(DEFAULT_SETTINGS, settingsFromOptions(o as Readonly<Record<string, unknown>>)), frameIntent(o));
}

/**
 * Frame mode: the frames of a frame recipe (the real-time chain's switches --temporal, --denoise,
 * --restir; --mode hybrid), or frames in time (--frames, --path; of a debug view too).
 */
export const isFrameMode = (o: FrameModeOptions): boolean => isFrameRecipe(recipeOf(o)) || Boolean(frameIntent(o).frames);

/** Samples per pixel when --spp is not given: 64 for a progressive render, 1 a frame in frame mode (the real-time chain's budget). */
export const DEFAULT_SPP = 64;
export const DEFAULT_FRAME_SPP = 1;

/** --spp, or its default for the mode: a frame-mode render is the real-time chain, whose frames are 1 spp unless asked otherwise. */
export const samplesPerPixel = (o: FrameModeOptions & { spp?: number }): number => o.spp ?? (isFrameMode(o) ? DEFAULT_FRAME_SPP : DEFAULT_SPP);

/** `--frames 1-30,47`: frames of the whole sequence, numbered from 0 (frame-0000 is the first), sorted. */
export interface FrameList {
  readonly list: readonly number[];
}

/** Frames a path is cut into when no count says otherwise. */
export const DEFAULT_PATH_FRAMES = 30;

/**
 * Which frames to write and of how long a sequence: `frames` (sorted), `total` (the path is cut into
 * that many; undefined without a path: the world's clock runs at --fps), and `sequence` (outputs are
 * folders of frame-NNNN files: more than one frame, a path, or a list).
 */
export function frameSelection(o: Pick<FrameModeOptions, 'frames' | 'path' | 'cameraPath' | 'pathFrames'>): { frames: readonly number[]; total: number | undefined; sequence: boolean } {
  const path = o.path !== undefined || o.cameraPath !== undefined;
  if (o.frames === undefined || typeof o.frames === 'number') {
    if (o.pathFrames !== undefined) throw new LanternError('--path-frames goes with a list of --frames (such as 0-29); a count of --frames is already the path\'s length');
    const n = o.frames ?? (path ? DEFAULT_PATH_FRAMES : 1);
    return { frames: Array.from({ length: n }, (_, i) => i), total: path ? n : undefined, sequence: n > 1 || path };
  }
  if (o.pathFrames !== undefined && !path) throw new LanternError('--path-frames applies with --path only', 'Leave it out: without a path frame f is at --time + f / --fps');
  const total = path ? (o.pathFrames ?? DEFAULT_PATH_FRAMES) : undefined;
  const last = o.frames.list[o.frames.list.length - 1]!;
  if (total !== undefined && last >= total) throw new LanternError(`--frames names frame ${last}, but the path has ${total} frames (0-${total - 1})`, 'Give --path-frames the length of the whole path');
  return { frames: o.frames.list, total, sequence: true };
}

export interface FrameModeResult {
  readonly frames: number;
  readonly seconds: number;
  /** Median GPU milliseconds of each pass over the frames (absent without timestamp queries). */
  readonly gpuMs?: Record<string, number>;
  /** With --exr: RMSE between consecutive frames' linear radiance, mean over the second half of the frames (temporal stability). */
  readonly frameChangeRmse?: number;
  readonly outputs: { png?: string; exr?: string };
}

/**
 * Renders the frames. With more than one frame (or a path), `png` and `exr` name folders that
 * receive frame-0000.png, ...; with one frame they name files.
 */
/** A moving scene's world, played on from `start` seconds (frame times: the path's, else `fps` frames per second). */
export interface FrameWorld {
  readonly world: World;
  readonly start: number;
  readonly fps: number;
}

export async function renderFrames(renderer: Renderer, base: Camera, spp: number, o: FrameModeOptions, out: { png?: string; exr?: string }, moving?: FrameWorld): Promise<FrameModeResult> {
  const path = o.cameraPath ?? (o.path !== undefined ? parseCameraPath(readJsonFile(o.path, '--path'), o.path) : undefined);
  const selection = frameSelection({ ...o, ...(path ? { cameraPath: path } : {}) });
  // A frame depends on those before it (the temporal history, ReSTIR's reservoirs, the hybrid's TAA,
  // the adapting exposure, the sample index): with any of those but the sample index, every frame
  // up to the last one asked for is rendered and those not asked for are not read back or written;
  // without them, frames not asked for are not traced at all, the sample index set to what they
  // would have left (the world and camera still step through them: doors open as the camera
  // passes). Either way each written frame is the whole sequence's, bit for bit.
  const wanted = new Set(selection.frames);
  const st = renderer.settings;
  let lastTraced = -1;
  const historyFree = recipeFor(st, { frames: true }) === 'real-time' && !st.temporal && !st.denoise && !st.restir && renderer.exposureChoice.kind !== 'auto';
  const frames = selection.frames[selection.frames.length - 1]! + 1;
  const total = selection.total ?? frames;
  const sequence = selection.sequence;
  // The denoiser's settings (--temporal, --denoise, --history-cap, ...) and the hybrid recipe's are the caller's, applied with the others.
  await renderer.compile({}, { frames: true });
  const debugOnly = recipeFor(renderer.settings, { frames: true }) === 'debug';
  const timer = renderer.gpu.hasTimestamps ? new GpuTimer(renderer.device) : undefined;
  if (o.warmup) {
    // A GPU idle a moment ago runs its first frames at low clocks: light recipes would be timed there.
    renderer.setCamera(path ? cameraAt(path, frameTime(path, 0, total), base) : base);
    for (const until = performance.now() + o.warmup * 1000; performance.now() < until; ) {
      renderer.renderFrame(spp);
      await renderer.finish();
    }
    renderer.resetHistory();
  }
  const samples = new Map<string, number[]>();
  const changes: number[] = [];
  let previous: Float32Array | undefined;
  const start = performance.now();
  // The files are encoded and written on other threads while the GPU renders on (frame-writer.ts).
  const writer = new FrameWriter(out.png || out.exr ? undefined : 0);
  try {
    for (let f = 0; f < frames; f++) {
      const camera = path ? cameraAt(path, frameTime(path, f, total), base) : base;
      renderer.setCamera(camera);
      if (moving) {
        // Scene time follows the path's clock, or the frame rate; the first frame is at `start`.
        const t = moving.start + (path ? frameTime(path, f, total) - frameTime(path, 0, total) : f / moving.fps);
        const update = moving.world.advanceTo(Math.max(t, moving.world.seconds), camera);
        if (!isEmptyUpdate(update)) renderer.applySceneUpdate(update);
      }
      // Without history a frame still inherits state of the frame before it (found: the first frame
      // traced after a start differs from the sequence's in the EXR's last bits), so the frame before
      // each listed one is traced too, not read back.
      if (historyFree && !wanted.has(f) && !wanted.has(f + 1)) continue;
      // After skipped frames only: a sequence traced whole never seeks, and stays what it was.
      if (historyFree && lastTraced !== f - 1) renderer.seekFrameSamples(f * spp, f === 0 ? undefined : path ? cameraAt(path, frameTime(path, f - 1, total), base) : base);
      renderer.renderFrame(spp, timer);
      lastTraced = f;
      const name = `frame-${String(f).padStart(4, '0')}`;
      // The automatic exposure adapts over the sequence's own clock (the first frame takes its target).
      if (f > 0) renderer.advanceExposure(path ? frameTime(path, f, total) - frameTime(path, f - 1, total) : 1 / (o.fps ?? 30));
      if (!wanted.has(f)) {
        // Not asked for: rendered for what the next frames inherit, not read back. Its timestamps are dropped.
        if (timer) await timer.read();
        continue;
      }
      // The tone map (and automatic exposure) are timed with the frame's passes.
      const image = out.png ? await renderer.readImage(timer) : undefined;
      if (timer) for (const { name, ms } of await timer.read()) samples.set(name, [...(samples.get(name) ?? []), ms]);
      if (image && out.png) await writer.write({ kind: 'png', path: sequence ? join(out.png, `${name}.png`) : out.png, width: renderer.width, height: renderer.height, rgba: image });
      if (out.exr) {
        // A debug view that replaces the image has no radiance: its frames hold its values, as a still render's EXR does.
        const { width, height, radiance } = debugOnly ? { width: renderer.width, height: renderer.height, radiance: await readDebugRgb(renderer) } : await renderer.readFrame();
        if (previous && f >= frames / 2) changes.push(rmse(radiance, previous));
        previous = radiance;
        await writer.write({ kind: 'exr', path: sequence ? join(out.exr, `${name}.exr`) : out.exr, width, height, radiance });
      }
    }
  } catch (e) {
    await writer.close().catch(() => undefined);
    throw e;
  }
  await renderer.finish();
  await writer.close();
  const seconds = (performance.now() - start) / 1000;
  timer?.destroy();
  const gpuMs = timer ? Object.fromEntries([...samples].map(([name, ms]) => [name, median(ms)])) : undefined;
  const frameChangeRmse = changes.length > 0 ? changes.reduce((a, b) => a + b, 0) / changes.length : undefined;
  return { frames: selection.frames.length, seconds, ...(gpuMs ? { gpuMs } : {}), ...(frameChangeRmse !== undefined ? { frameChangeRmse } : {}), outputs: out };
}
