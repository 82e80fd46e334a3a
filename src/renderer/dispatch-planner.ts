/**
 * Decides how much work goes into each submit of a long render: enough that per-submit overhead is
 * negligible, little enough that no submit runs long enough to trip a GPU watchdog (Windows resets a
 * GPU after 2 s; browsers and drivers have similar limits) or to freeze a desktop. Starts at one
 * sample over the whole image, then doubles or halves the samples per dispatch toward a target
 * duration; when even one sample of the whole image is too slow, splits the image into bands.
 */
import type { Tile } from '../passes/path-trace-pass.ts';

export interface DispatchPlannerOptions {
  /** Aim for submits of about this many milliseconds. */
  readonly targetMs: number;
  readonly maxSamplesPerDispatch: number;
  /** Never split the image into more bands than this. */
  readonly maxBands: number;
  /**
   * Samples per dispatch held at this (the last dispatch takes what remains), only the bands
   * adapting: the image then does not depend on timing (float sums are added in a fixed grouping),
   * so a render equals a farm's chunks of this size merged, bit for bit (`render --chunk`).
   */
  readonly fixedSamples?: number;
}

export const DEFAULT_PLANNER_OPTIONS: DispatchPlannerOptions = { targetMs: 60, maxSamplesPerDispatch: 64, maxBands: 64 };

export class DispatchPlanner {
  private samplesPerDispatch = 1;
  private bands = 1;

  constructor(
    readonly width: number,
    readonly height: number,
    private readonly options: DispatchPlannerOptions = DEFAULT_PLANNER_OPTIONS,
  ) {
    if (options.fixedSamples !== undefined) this.samplesPerDispatch = options.fixedSamples;
  }

  /** The next batch: samples per pixel (at most `remaining`) and the tiles covering the image. */
  next(remaining: number): { samples: number; tiles: Tile[] } {
    return { samples: Math.min(this.samplesPerDispatch, remaining), tiles: bandTiles(this.width, this.height, this.bands) };
  }

  /** Reports how long the last batch took, per submit (ms), and adapts the next one. */
  observe(msPerSubmit: number): void {
    const { targetMs } = this.options;
    // With fixedSamples only the bands adapt.
    const adaptSamples = this.options.fixedSamples === undefined;
    if (msPerSubmit > 2 * targetMs) {
      if (adaptSamples && this.samplesPerDispatch > 1) this.samplesPerDispatch = Math.max(1, Math.floor(this.samplesPerDispatch / 2));
      else this.bands = Math.min(this.options.maxBands, this.height, this.bands * 2);
    } else if (msPerSubmit < targetMs / 2) {
      if (this.bands > 1) this.bands = Math.max(1, Math.floor(this.bands / 2));
      else if (adaptSamples) this.samplesPerDispatch = Math.min(this.options.maxSamplesPerDispatch, this.samplesPerDispatch * 2);
    }
  }

  get state(): { samplesPerDispatch: number; bands: number } {
    return { samplesPerDispatch: this.samplesPerDispatch, bands: this.bands };
  }
}

/** `bands` horizontal strips covering a width × height image exactly, top to bottom. */
export function bandTiles(width: number, height: number, bands: number): Tile[] {
  const n = Math.max(1, Math.min(bands, height));
  const tiles: Tile[] = [];
  for (let i = 0; i < n; i++) {
    const y0 = Math.floor((i * height) / n);
    const y1 = Math.floor(((i + 1) * height) / n);
    tiles.push({ x: 0, y: y0, width, height: y1 - y0 });
  }
  return tiles;
}
