/**
 * The page's render loop around the shared Renderer: acquire the device on the first Play, then one
 * frame (samples + tone map + present) per animation frame with at most one frame in flight, so a slow
 * GPU (or SwiftShader) never piles up work. Pause keeps the accumulated image.
 */
import { acquireGpu } from '../gpu/device.ts';
import { builtinScene } from '../loaders/builtin/index.ts';
import { Renderer } from '../renderer/renderer.ts';

export type ViewerState = 'idle' | 'starting' | 'playing' | 'paused' | 'failed';

export interface ViewerStats {
  readonly samples: number;
  readonly framesPerSecond: number;
  readonly scene: string;
  readonly adapter: string;
}

export class Viewer {
  state: ViewerState = 'idle';
  /** Why the viewer stopped, when state is 'failed'. */
  failure: unknown;
  private renderer?: Renderer;
  private context?: GPUCanvasContext;
  private sceneName: string;
  private lastFrameTimes: number[] = [];
  private looping = false;

  constructor(
    private readonly canvas: HTMLCanvasElement,
    initialScene: string,
    /** Render resolution relative to the canvas's pixels. */
    private readonly scale: number,
    private readonly onChange: (viewer: Viewer) => void,
  ) {
    this.sceneName = initialScene;
  }

  get stats(): ViewerStats {
    const t = this.lastFrameTimes;
    const fps = t.length > 1 ? ((t.length - 1) * 1000) / (t[t.length - 1]! - t[0]!) : 0;
    return { samples: this.renderer?.sampleCount ?? 0, framesPerSecond: fps, scene: this.sceneName, adapter: this.renderer?.gpu.adapterName ?? '' };
  }

  /** Starts (acquiring the GPU on first use) or resumes accumulation. */
  async play(): Promise<void> {
    if (this.state === 'playing' || this.state === 'starting') return;
    if (!this.renderer) {
      this.setState('starting');
      const gpu = await acquireGpu(navigator.gpu);
      const context = this.canvas.getContext('webgpu');
      if (!context) throw new Error('the canvas has no WebGPU context');
      context.configure({ device: gpu.device, format: navigator.gpu.getPreferredCanvasFormat(), alphaMode: 'opaque' });
      this.context = context;
      const renderer = await Renderer.create(gpu);
      await renderer.enablePresentation();
      await renderer.resize(Math.max(1, Math.round(this.canvas.width * this.scale)), Math.max(1, Math.round(this.canvas.height * this.scale)));
      await renderer.setScene(builtinScene(this.sceneName));
      this.renderer = renderer;
      gpu.lost.then((info) => {
        if (info.reason !== 'destroyed') this.fail(new Error(`the GPU device was lost (${info.message || info.reason}); reload the page`));
      });
    }
    this.setState('playing');
    this.loop();
  }

  pause(): void {
    if (this.state === 'playing') this.setState('paused');
  }

  /** Switches scene; before the first Play it only remembers the choice (no GPU work). */
  async selectScene(name: string): Promise<void> {
    this.sceneName = name;
    if (this.renderer) await this.renderer.setScene(builtinScene(name));
    this.onChange(this);
  }

  /** Shows an error and stops; the page stays usable for reading the message. */
  fail(error: unknown): void {
    console.error(error);
    this.failure = error;
    this.setState('failed');
  }

  private setState(state: ViewerState): void {
    this.state = state;
    this.onChange(this);
  }

  private loop(): void {
    if (this.looping) return;
    this.looping = true;
    const frame = async () => {
      if (this.state !== 'playing' || !this.renderer || !this.context) {
        this.looping = false;
        return;
      }
      try {
        this.renderer.accumulate(1);
        this.renderer.present(this.context.getCurrentTexture());
        await this.renderer.finish();
      } catch (e) {
        this.looping = false;
        this.fail(e);
        return;
      }
      this.lastFrameTimes.push(performance.now());
      if (this.lastFrameTimes.length > 30) this.lastFrameTimes.shift();
      this.onChange(this);
      requestAnimationFrame(frame);
    };
    requestAnimationFrame(frame);
  }
}
