/**
 * The viewer's GPU: acquiring it at the first Play (the device, the canvas's WebGPU context, the
 * Renderer with what the first frame needs compiled, the pass timer), the record of the device's
 * pipeline compiles that the page shows, and what a lost device needs: the losses counted (the
 * viewer gives up when they come too often) and a frame's failure told from a loss. The viewer
 * opens a new device the same way after a loss and refills it (viewer.ts start, onDeviceLost).
 */
import { LanternError } from '../errors.ts';
import { acquireGpu, type GpuContext } from '../gpu/device.ts';
import { observeCompiles, setCompileConcurrency, type CompileProgress } from '../gpu/pipeline-compiles.ts';
import { GpuTimer } from '../gpu/timestamps.ts';
import { Renderer } from '../renderer/renderer.ts';
import type { RenderSettings } from '../renderer/settings.ts';
import { adapterKind, displayRateHz, type AdapterKind } from './frame-budget.ts';
import type { LoadedScene } from './scene-request.ts';

/**
 * Pipelines compiled at a time on the page: Chromium compiles them on its GPU process's thread pool
 * (max(3, cores - 1) foreground workers), and compiles filling it stop the page's frames
 * (gpu/pipeline-compiles.ts). One worker is left free.
 */
const pageCompileConcurrency = () => Math.max(2, (navigator.hardwareConcurrency || 2) - 2);

/** Milliseconds without an edit after which the scene's specialised kernels are compiled (Lantern issue #11). */
const SPECIALISE_AFTER_IDLE_MS = 1000;

/** More losses than this within a minute and the viewer gives up instead of recreating the device. */
export const MAX_DEVICE_LOSSES_PER_MINUTE = 3;

/** The pipeline compiles of the viewer's device, as the page shows them (Viewer.compiles, Viewer.pipelines). */
export class PipelineLog {
  /** The device's batch of pipeline compiles as last reported (gpu/pipeline-compiles.ts), under way or done. */
  compiles?: CompileProgress;
  /** Every pipeline requested on the current device, by key (label and constants), in request order. */
  pipelines: string[] = [];

  /** Follows a new device's compiles (its list starts empty), telling `onChange` at each report. */
  watch(device: GPUDevice, onChange: () => void): void {
    this.pipelines = [];
    observeCompiles(device, (progress) => {
      this.compiles = progress;
      for (const c of progress.compiles) if (!this.pipelines.includes(c.key)) this.pipelines.push(c.key);
      onChange();
    });
  }
}

/** What the first frame needs: read once the GPU is acquired (a scene or settings may have come meanwhile). */
export interface FirstFrameNeeds {
  readonly render: RenderSettings;
  readonly loaded: LoadedScene | undefined;
}

/** A started GPU for the viewer, with the display's rate and the adapter's kind for the frame budget. */
export interface ViewerDevice {
  readonly gpu: GpuContext;
  readonly context: GPUCanvasContext;
  readonly renderer: Renderer;
  readonly timer: GpuTimer | undefined;
  readonly displayHz: number;
  readonly adapter: AdapterKind;
}

/**
 * Acquires the GPU, configures the canvas for it and makes the Renderer, compiling what the first
 * frame needs; its compiles go to `log` (and `onChange`) from the start.
 */
export async function openDevice(canvas: HTMLCanvasElement, needs: () => FirstFrameNeeds, log: PipelineLog, onChange: () => void): Promise<ViewerDevice> {
  // The display's rate is measured while the GPU starts (requestAnimationFrame runs free then).
  const [gpu, displayHz] = await Promise.all([acquireGpu(navigator.gpu), measureDisplayRate()]);
  const context = canvas.getContext('webgpu');
  if (!context) throw new LanternError('the canvas has no WebGPU context', 'Reload the page; if it persists, the browser has WebGPU disabled');
  const format = navigator.gpu.getPreferredCanvasFormat();
  context.configure({ device: gpu.device, format, alphaMode: 'opaque' });
  // Every compile from here on is counted, so the page can say what it waits for.
  setCompileConcurrency(gpu.device, pageCompileConcurrency());
  log.watch(gpu.device, onChange);
  // What the first frame needs and nothing more, compiled side by side: the path tracer for the
  // loaded scene alone (its upload overlaps the compile), the tone mapper and the present pass;
  // then whatever the settings ask for (debug views, a real-time recipe, spectral), together.
  const { render: s, loaded } = needs();
  const renderer = await Renderer.create(gpu, { presentation: format, ...(loaded ? { features: loaded.prepared.packed.features } : {}) });
  // The renderer's idle policy: kernels specialised to the scene once it has gone this long without an
  // edit. Not on SwiftShader (a CPU): compiling them there takes minutes of the CPU the page runs on.
  if (!/swiftshader/i.test(gpu.adapterName)) renderer.setIdleSpecialisation(SPECIALISE_AFTER_IDLE_MS);
  await renderer.compile(s);
  const timer = gpu.hasTimestamps ? new GpuTimer(gpu.device) : undefined;
  // A new device may be another adapter (a lost GPU replaced by the fallback): the budget measures it afresh.
  const adapter = adapterKind({ name: gpu.adapterName, isFallbackAdapter: gpu.adapter.info.isFallbackAdapter });
  return { gpu, context, renderer, timer, displayHz, adapter };
}

/** The device losses the viewer has answered, to give up when they come too often. */
export class DeviceLosses {
  private losses: number[] = [];
  private expectingLoss = false;

  /** The test hook destroys the device next: that loss is answered like a driver reset. */
  expect(): void {
    this.expectingLoss = true;
  }

  /** Counts a loss and returns the losses within the last minute; undefined for a device destroyed on purpose (Viewer.destroy). */
  count(info: GPUDeviceLostInfo): number | undefined {
    const simulated = this.expectingLoss;
    this.expectingLoss = false;
    if (info.reason === 'destroyed' && !simulated) return undefined;
    const now = performance.now();
    this.losses = [...this.losses.filter((t) => now - t < 60_000), now];
    return this.losses.length;
  }
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

/** Whether the device reports itself lost within a moment (frames fail before `lost` resolves). */
export async function lostSoon(gpu: GpuContext): Promise<boolean> {
  const timeout = new Promise<false>((resolve) => setTimeout(() => resolve(false), 200));
  return Promise.race([gpu.lost.then(() => true), timeout]);
}
