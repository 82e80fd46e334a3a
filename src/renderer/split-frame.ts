/**
 * A frame's GPU work cut into chunks submitted one at a time (Renderer.beginFrame, beginAccumulate):
 * what lets the page answer input between the submissions of a slow frame.
 */
import type { Tile } from '../passes/path-trace-pass.ts';

/** What a split frame needs of the renderer that began it. */
export interface FrameHost {
  readonly device: GPUDevice;
  /** Changes whenever the estimate, the history or the scene changes (a frame begun before is given up). */
  frameGeneration(): string;
  /** The image targets in use (a resize replaces them). */
  currentTargets(): object | undefined;
  submit(encoder: GPUCommandEncoder): void;
}

/** What a SplitFrame records: a band of the tracing, the passes after the last band, and what completes or gives up the frame. */
export interface SplitWork {
  band(encoder: GPUCommandEncoder, tile: Tile): void;
  finish(encoder: GPUCommandEncoder): void;
  done(): void;
  abandon(): void;
  /** A frame traced whole, submitting itself (the hybrid recipe). */
  whole?: () => void;
}

/**
 * A frame's GPU work cut into row bands (Renderer.beginFrame, beginAccumulate), submitted one at a
 * time top to bottom: submitChunk records the next band of rows, or a piece of one (and, with the last,
 * the passes after the tracing) and submits it; the caller awaits Renderer.finish() before the next, so each submission
 * is a short wait for the page. Every pixel's paths depend on that pixel alone (its random streams are
 * keyed by pixel and sample index, never by tile), so the bands add up to exactly the unsplit frame.
 * Anything that changes what the frame computes (a camera move, a resize, a scene or settings
 * change: each resets the estimate or the history) makes it invalid; the caller then abandons it.
 */
export class SplitFrame {
  /** The next chunk's corner, and the height of the band under way. */
  private x = 0;
  private y = 0;
  private bandRows = 0;
  private finished = false;
  private abandoned = false;
  private readonly generation: string;

  constructor(
    private readonly renderer: FrameHost,
    private readonly targets: { readonly width: number; readonly height: number },
    /** Paths per pixel of the frame. */
    readonly samples: number,
    /** Whether the tracing can be cut into bands (false: the first submitChunk submits the whole frame). */
    readonly splittable: boolean,
    private readonly work: SplitWork,
    private readonly label: string,
  ) {
    this.generation = renderer.frameGeneration();
  }

  get width(): number {
    return this.targets.width;
  }

  get height(): number {
    return this.targets.height;
  }

  /** Rows done so far (whole bands). */
  get rowsDone(): number {
    return this.y;
  }

  /** Rows not yet done, the current band's included. */
  get rowsLeft(): number {
    return this.height - this.y;
  }

  /** Columns of the current band not yet done (the width between bands). */
  get columnsLeft(): number {
    return this.width - this.x;
  }

  /** Whether the whole frame has been submitted. */
  get done(): boolean {
    return this.finished;
  }

  /** Whether the frame may go on: nothing reset the estimate or the history and the image was not resized since it began. */
  get valid(): boolean {
    return !this.abandoned && !this.finished && this.renderer.currentTargets() === this.targets && this.renderer.frameGeneration() === this.generation;
  }

  /**
   * Records and submits the next chunk: `columns` pixels (default the whole width) of a band of
   * `rows` rows; a band's height is set by its first chunk, and chunks go left to right, bands top to
   * bottom. A frame that is not splittable is submitted whole. The last chunk carries the passes
   * after the tracing in the same submission. Returns the pixels traced.
   */
  submitChunk(rows: number, columns = this.width): number {
    if (!this.valid) throw new Error('SplitFrame: the frame was finished, abandoned or overtaken by a change; begin another');
    if (!this.splittable) {
      rows = this.height;
      columns = this.width;
    }
    if (this.x === 0) this.bandRows = Math.min(Math.max(1, Math.floor(rows)), this.height - this.y);
    const tile = { x: this.x, y: this.y, width: Math.min(Math.max(1, Math.floor(columns)), this.width - this.x), height: this.bandRows };
    this.x += tile.width;
    if (this.x === this.width) {
      this.x = 0;
      this.y += this.bandRows;
    }
    const last = this.y === this.height;
    if (this.work.whole) {
      this.work.whole();
    } else {
      const encoder = this.renderer.device.createCommandEncoder({ label: `${this.label} (${tile.x}, ${tile.y}) ${tile.width}×${tile.height}` });
      this.work.band(encoder, tile);
      if (last) this.work.finish(encoder);
      this.renderer.submit(encoder);
    }
    if (last) {
      this.finished = true;
      this.work.done();
    }
    return tile.width * tile.height;
  }

  /** Gives the frame up (the real-time chain's history stays that of the last finished frame). */
  abandon(): void {
    if (this.finished || this.abandoned) return;
    this.abandoned = true;
    this.work.abandon();
  }
}

