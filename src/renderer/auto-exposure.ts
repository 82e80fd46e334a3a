/**
 * The automatic exposure on the GPU (passes/exposure-pass.ts) and its adaptation over time: the eye
 * adapts over the wall clock between presents, over a sequence's own clock between read-backs
 * (advance), and takes its target at once on a new scene. The kernels are compiled the first time an
 * image is exposed automatically, never for scenes and settings that do not ask for it.
 */
import type { ViewUniform } from '../gpu/view.ts';
import type { GpuTimer } from '../gpu/timestamps.ts';
import { ExposurePass, type ExposureReading } from '../passes/exposure-pass.ts';
import { adaptationKeep, type ExposureChoice } from './exposure.ts';

/** The image whose exposure is chosen: its radiance, and how it is to be read. */
export interface ExposedImage {
  readonly view: ViewUniform;
  readonly radiance: GPUBuffer;
  readonly width: number;
  readonly height: number;
  /** Samples the radiance sums (0: nothing yet; 1 for a frame's mean). */
  readonly sampleCount: number;
  /** Shown as computed (a recipe's debug view): no exposure at all. */
  readonly raw: boolean;
}

export class AutoExposure {
  private pass?: ExposurePass;
  private compiling?: Promise<ExposurePass>;
  private destroyed = false;
  /** Whether the adapted exposure holds this scene's (false: the next tone map snaps to its target). */
  private adapted = false;
  /** Seconds of adaptation the next read-back applies (advance). */
  private pending = 0;
  /** When the last present adapted (performance.now()). */
  private lastPresentMs?: number;

  constructor(private readonly device: GPUDevice) {}

  /** Compiles the two kernels, once. */
  compile(): Promise<ExposurePass> {
    this.compiling ??= ExposurePass.create(this.device).then((pass) => {
      if (this.destroyed) pass.destroy();
      else this.pass = pass;
      return pass;
    });
    return this.compiling;
  }

  /** Another scene: the eye starts adapted to it, not to the last one. */
  snap(): void {
    this.adapted = false;
  }

  /** Lets the exposure adapt by `seconds` more at the next read-back. */
  advance(seconds: number): void {
    if (!(seconds >= 0) || !Number.isFinite(seconds)) throw new Error(`Renderer.advanceExposure: ${seconds} is not a duration in seconds`);
    this.pending += seconds;
  }

  /** The seconds a read-back adapts by (those advanced since the last one). */
  takeAdvanced(): number {
    const seconds = this.pending;
    this.pending = 0;
    return seconds;
  }

  /** The wall-clock seconds since the last present (0 at the first): what is presented is seen in real time. */
  sincePresent(): number {
    const now = performance.now();
    const seconds = this.lastPresentMs === undefined ? 0 : (now - this.lastPresentMs) / 1000;
    this.lastPresentMs = now;
    return seconds;
  }

  /** The automatic exposure as the last tone map left it: the image's log-average luminance (log2) and the exposure (stops). */
  read(): Promise<ExposureReading> {
    if (!this.pass) throw new Error('Renderer: no image has been exposed automatically yet');
    return this.pass.read();
  }

  /**
   * The tone mapper's exposure for an image under `choice`, adapting by `seconds`: manual stops, or the
   * automatic exposure measured on the GPU (recorded here). Until the kernels are compiled, an
   * automatic choice keeps `fallbackStops` (the scene's own exposure).
   */
  encode(encoder: GPUCommandEncoder, choice: ExposureChoice, image: ExposedImage, seconds: number, fallbackStops: number, timer?: GpuTimer): { exposureStops: number; autoExposure?: GPUBuffer } {
    if (choice.kind === 'auto' && !this.pass) choice = { kind: 'manual', stops: fallbackStops };
    let exposure: { exposureStops: number; autoExposure?: GPUBuffer };
    if (image.raw) exposure = { exposureStops: 0 };
    else if (choice.kind === 'manual') exposure = { exposureStops: choice.stops };
    // No samples yet: a black image, and nothing to adapt to.
    else if (image.sampleCount === 0) exposure = { exposureStops: 0 };
    else {
      const pass = this.pass!;
      const keep = this.adapted ? adaptationKeep(seconds, choice.adaptationSeconds) : 0;
      pass.encode(encoder, { view: image.view, radiance: image.radiance, width: image.width, height: image.height, input: { sampleCount: image.sampleCount, keep, compensationStops: choice.compensationStops }, timer });
      this.adapted = true;
      exposure = { exposureStops: 0, autoExposure: pass.state };
    }
    // A manual exposure between automatic ones: the eye adapts afresh when automatic comes back.
    if (choice.kind === 'manual') this.adapted = false;
    return exposure;
  }

  destroy(): void {
    this.destroyed = true;
    this.pass?.destroy();
  }
}
