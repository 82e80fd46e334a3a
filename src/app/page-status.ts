/**
 * What the page shows besides the image: the message line (info expires, warnings and errors stay,
 * a scene's warnings fold into a count), the status line and the bar beside it (what the page waits
 * for, or the readings), the debug view's legend, and the overlay before Play with the expected wait.
 * main.ts makes one PageStatus over the page's elements; nothing runs at import.
 */
import { describeBackend } from './backend-choice.ts';
import { legendGradientCss, type DebugLegend } from '../renderer/debug-legend.ts';
import { describeEstimate, estimateFirstFrame, frameMs, remainingCompileMs, roughDuration } from './first-frame-estimate.ts';
import { frameRate } from './number-format.ts';
import type { PageState } from './page-state.ts';
import { firstFrameRecord, knownCompileTimes, noteCompiles } from './page-storage.ts';
import { fitStatus, part, type StatusPart } from './status-line.ts';
import type { Viewer } from './viewer.ts';

/** How long an info message stays (warnings and errors stay until closed or replaced). */
const INFO_MESSAGE_MS = 8000;

/** The page's elements that PageStatus fills. */
export interface StatusElements {
  readonly canvas: HTMLCanvasElement;
  readonly progress: HTMLProgressElement;
  readonly stats: HTMLSpanElement;
  readonly message: HTMLDivElement;
  readonly messageBox: HTMLDivElement;
  readonly legend: HTMLDivElement;
  readonly start: HTMLDivElement;
  readonly startPlay: HTMLButtonElement;
}

/** The message line, the status line, the legend and the overlay before Play. */
export class PageStatus {
  constructor(
    private readonly el: StatusElements,
    private readonly page: PageState,
  ) {}

  /**
   * Shows one message (it replaces the last). Info expires after INFO_MESSAGE_MS; warnings and errors
   * stay until closed (×) or replaced. `details` (a scene's loading warnings) fold under the text,
   * which then reads as their count, and open on a click. `note` (information shown with warnings: how
   * a scene is lit) is a line of its own above them, in the colour of information.
   */
  showMessage(text: string, kind: 'info' | 'warning' | 'error', details: readonly string[] = [], note?: string): void {
    clearTimeout(this.page.messageTimer);
    this.el.messageBox.hidden = false;
    this.el.message.hidden = false;
    this.el.message.dataset.kind = kind;
    let body: Node = document.createTextNode(text);
    if (details.length > 0) {
      const fold = document.createElement('details');
      const summary = document.createElement('summary');
      summary.textContent = text;
      const list = document.createElement('div');
      list.textContent = details.map((d) => `· ${d}`).join('\n');
      fold.append(summary, list);
      body = fold;
    }
    const noteLine = note !== undefined ? [Object.assign(document.createElement('div'), { className: 'note', textContent: note })] : [];
    this.el.message.replaceChildren(...noteLine, body);
    if (kind === 'info') this.page.messageTimer = setTimeout(() => this.clearMessage(), INFO_MESSAGE_MS);
  }
  clearMessage(): void {
    clearTimeout(this.page.messageTimer);
    this.el.messageBox.hidden = true;
    this.el.message.hidden = true;
    this.el.message.textContent = '';
  }

  /**
   * The status line and the bar beside it: what the page waits for (the scene loading, the pipelines
   * compiling, with how many of how many and the time left) or, while playing, the readings. Fitted
   * to its width (status-line.ts: the least important figures go first); the whole line and the
   * budget's reasons are the tooltip.
   */
  showStatus(v: Viewer): void {
    const s = v.stats;
    const c = v.compiles;
    noteCompiles(this.page, c);
    const compiling = c !== undefined && c.done < c.needed ? c : undefined;
    this.el.progress.hidden = this.page.loading === undefined && !compiling;
    this.el.progress.value = compiling ? compiling.done / compiling.needed : this.page.loadFraction;
    const waitParts = (prefix: string, what: string) => {
      if (!compiling) return [];
      const { done, needed } = compiling;
      const leftMs = this.page.adapterFacts ? remainingCompileMs(compiling, performance.now(), knownCompileTimes(this.page), this.page.adapterFacts) + (v.awaitingFirstFrame ? frameMs(this.page.adapterFacts, this.expectedPixels(v)) : 0) : undefined;
      return [
        part(10, `${prefix}compiling ${what}, ${done} of ${needed}`, `compiling, ${done} of ${needed}`, `${done}/${needed} compiled`),
        leftMs === undefined ? undefined : part(6, `about ${roughDuration(leftMs)} left`, `~${roughDuration(leftMs)}`),
      ];
    };
    let parts: (StatusPart | undefined)[];
    if (this.page.loading !== undefined) parts = compiling ? waitParts('loading: ', 'shaders') : [part(10, `loading: ${this.page.loading}…`)];
    else if (v.state === 'idle') parts = [part(10, 'press Play to start')];
    else if (v.webgl2.compiling) parts = [part(10, `compiling ${v.webgl2.compiling} (WebGL2; ANGLE takes seconds for it)…`, 'compiling (WebGL2)…')];
    else if (v.state === 'starting' || (v.awaitingFirstFrame && compiling)) parts = compiling ? waitParts('', 'shaders') : [part(10, 'starting the GPU…')];
    else if (v.awaitingFirstFrame && v.backend.kind === 'webgl2') parts = [part(10, 'rendering the first frame (WebGL2: the driver compiles the path tracer at its first draw, seconds to minutes)…', 'rendering the first frame…')];
    else if (v.awaitingFirstFrame) parts = [part(10, 'rendering the first frame…')];
    else {
      const r = v.settings.render;
      const fps = frameRate(s.framesPerSecond);
      parts = [
        // A recipe switched to compiles while the frames go on with the one before.
        ...waitParts('', v.compilingFor ?? 'shaders'),
        // A debug view that replaces the image traces no paths: no samples to count.
        part(9, r.debugView !== 'none' && r.debugLayout === 'replace' ? 'debug view' : `${s.samples} spp`),
        part(8, fps, fps.replace(/ \(.*\)$/, '')),
        part(5, `${s.width}×${s.height}`),
        part(3, v.budgetText(true), v.budget.on ? `budget ${v.budget.scale.toFixed(2)}×` : undefined),
        part(2, s.adapter),
        // Which backend renders, and why WebGL2 when it does (backend-choice.ts).
        v.backend.kind === 'webgl2' ? part(7, describeBackend(v.backend), 'WebGL2') : undefined,
        document.hidden && v.state === 'playing' ? part(9, 'paused while the tab is hidden', 'paused (hidden)') : undefined,
      ];
    }
    this.el.stats.textContent = fitStatus(parts, (text) => {
      this.el.stats.textContent = text;
      return this.el.stats.scrollWidth <= this.el.stats.clientWidth;
    });
    const whole = parts.flatMap((p) => (p ? [p.forms[0]] : [])).join(' · ');
    this.el.stats.title = s.budget && v.state !== 'idle' ? `${whole}\n${s.budget}` : whole;
  }

  /** The debug view's legend under the image: what it shows and, for scalar views, the colour scale with its numbers. */
  showLegend(l: DebugLegend | undefined): void {
    this.el.legend.hidden = !l;
    if (!l) return;
    this.el.legend.querySelector('.label')!.textContent = l.label;
    const bar = this.el.legend.querySelector<HTMLDivElement>('.bar')!;
    bar.hidden = !l.scale;
    if (l.scale) {
      bar.style.background = legendGradientCss();
      bar.querySelector('.min')!.textContent = formatScale(l.scale.min);
      bar.querySelector('.max')!.textContent = `${formatScale(l.scale.max)}${l.scale.auto ? ' (image max)' : ''}`;
    }
  }

  /** The pixels the first frame will have: the canvas's device pixels times the resolution scale. */
  private expectedPixels(v: Viewer): number {
    return Math.max(1, Math.round(this.el.canvas.width * v.settings.scale) * Math.round(this.el.canvas.height * v.settings.scale));
  }

  /** The overlay before Play: the scene's name, Play, and the expected wait; without WebGPU, how to get it. */
  showStart(v: Viewer): void {
    const before = v.state === 'idle';
    this.el.start.hidden = !before;
    if (!before) return;
    this.el.start.querySelector('.scene-name')!.textContent = this.page.loading !== undefined ? `Loading ${v.stats.sceneName || 'the scene'}…` : v.stats.sceneName;
    // Without WebGPU, WebGL2 renders; the notes say how to get WebGPU for what needs it.
    const noGpu = this.page.backendChosen && v.backend.kind === 'webgl2' && !navigator.gpu;
    this.el.start.querySelector<HTMLElement>('.no-webgpu')!.hidden = !noGpu;
    this.el.startPlay.disabled = !v.scene || this.page.loading !== undefined;
    const estimate = estimateFirstFrame(this.page.adapterFacts, this.expectedPixels(v), firstFrameRecord());
    this.el.start.querySelector('.estimate')!.textContent = v.backend.kind === 'webgl2' ? describeBackend(v.backend) : estimate ? describeEstimate(estimate) : '';
  }
}

const formatScale = (v: number) => (Number.isInteger(v) ? String(v) : v.toFixed(1));
