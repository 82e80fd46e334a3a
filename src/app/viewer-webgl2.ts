/**
 * The viewer's frames on the WebGL2 backend (backend-choice.ts; src/webgl2/): one frame per
 * animation frame while playing, each the camera's input applied (the viewer's advance), the
 * samples per frame added to the estimate (restarted each frame when accumulation is off), the image
 * tone-mapped and drawn, then a fence waited for so that at most one frame is in flight. What the
 * WebGPU loop (viewer-frames.ts) adds beyond that (split frames, the real-time recipe, the frame
 * budget's measurements, ray counts) does not exist here: the fragment tracer is progressive only.
 */
import type { Wait } from '../webgl2/program.ts';
import type { WebGl2Compile } from '../webgl2/webgl2-renderer.ts';
import { WebGl2Tracer } from '../webgl2/webgl2-tracer.ts';
import type { RenderSettings } from '../renderer/settings.ts';

export interface WebGl2FramesHost {
  playing(): boolean;
  /** Camera input and the world's time before the frame (Viewer.advance). */
  advance(tracer: WebGl2Tracer): void;
  samplesPerFrame(): number;
  accumulate(): boolean;
  fail(error: unknown): void;
  changed(): void;
}

/** One animation frame, for the compile's polls and the fence's. */
export const nextFrame: Wait = () => new Promise((resolve) => requestAnimationFrame(() => resolve()));

export class WebGl2Frames {
  tracer?: WebGl2Tracer;
  looping = false;
  /** Every program compiled, with its time (the page shows the wait, perf.md quotes them). */
  readonly compiles: WebGl2Compile[] = [];
  /** What compiles now (the page says it), undefined when nothing does. */
  compiling?: string;
  /** Milliseconds from Play to the first frame drawn (undefined before). */
  firstFrameMs?: number;
  playedAt?: number;
  /** When the last frames ended, for the rate. */
  private frameTimes: number[] = [];

  constructor(private readonly host: WebGl2FramesHost) {}

  /** Opens the WebGL2 context on the canvas and compiles the tone map (the tracer compiles with the first scene). */
  async open(canvas: HTMLCanvasElement, settings: RenderSettings): Promise<WebGl2Tracer> {
    this.compiling = 'the tone map';
    this.host.changed();
    try {
      this.tracer = await WebGl2Tracer.create(canvas, settings, { wait: nextFrame, onCompile: (c) => this.compiles.push(c) });
    } finally {
      this.compiling = undefined;
    }
    return this.tracer;
  }

  /** Runs `work` (a scene's upload, which compiles the tracer the first time) saying so on the page; the frame first shows the words. */
  async compilingWhile<T>(what: string, work: () => Promise<T>): Promise<T> {
    this.compiling = what;
    this.host.changed();
    // Without KHR_parallel_shader_compile the compile blocks the page: let the status show first.
    await nextFrame();
    try {
      return await work();
    } finally {
      this.compiling = undefined;
      this.host.changed();
    }
  }

  get framesPerSecond(): number {
    const f = this.frameTimes;
    return f.length > 1 ? ((f.length - 1) * 1000) / (f[f.length - 1]! - f[0]!) : 0;
  }

  get frameMs(): number {
    const f = this.frameTimes;
    return f.length > 1 ? f[f.length - 1]! - f[f.length - 2]! : 0;
  }

  loop(): void {
    if (this.looping) return;
    this.looping = true;
    const step = async () => {
      const tracer = this.tracer;
      if (!this.host.playing() || document.hidden || !tracer) {
        this.looping = false;
        return;
      }
      try {
        this.host.advance(tracer);
        if (!this.host.accumulate()) tracer.resetAccumulation();
        tracer.accumulate(this.host.samplesPerFrame());
        tracer.show();
        await tracer.finish(nextFrame);
        const now = performance.now();
        if (this.firstFrameMs === undefined && this.playedAt !== undefined) this.firstFrameMs = now - this.playedAt;
        this.frameTimes = [...this.frameTimes.slice(-19), now];
        this.host.changed();
      } catch (e) {
        this.looping = false;
        this.host.fail(e);
        return;
      }
      requestAnimationFrame(() => void step());
    };
    requestAnimationFrame(() => void step());
  }
}
