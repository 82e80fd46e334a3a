/**
 * What an image becomes once traced (Renderer.present, readImage): its exposure (manual, or
 * automatic and adapting: renderer/auto-exposure.ts), the tone map to 8-bit sRGB, a debug view
 * composed with it or instead of it (recipes/debug.ts), and on the page the selected object's
 * outline (renderer/selection.ts) and the present pass onto the canvas.
 */
import { readTexture4x8 } from '../gpu/readback.ts';
import type { SceneResources } from '../gpu/scene-resources.ts';
import type { GpuTimer } from '../gpu/timestamps.ts';
import type { ViewUniform } from '../gpu/view.ts';
import { PresentPass } from '../passes/present-pass.ts';
import type { TonemapPass } from '../passes/tonemap-pass.ts';
import { AutoExposure } from './auto-exposure.ts';
import type { ExposureChoice } from './exposure.ts';
import type { ImageTargets } from './image.ts';
import type { PreparedScene } from './prepare.ts';
import type { DebugViews } from './recipes/debug.ts';
import { Selection } from './selection.ts';
import type { RenderSettings } from './settings.ts';

/** The image to show, as the Renderer has it now. */
export interface ShownImage {
  readonly targets: ImageTargets;
  readonly view: ViewUniform;
  readonly settings: RenderSettings;
  /** The progressive estimate (the accumulation) or the last frame's linear output. */
  readonly radiance: GPUBuffer;
  /** Samples the radiance sums: the estimate's count, or 1 for a frame's mean. */
  readonly sampleCount: number;
  /** A recipe's own debug view (settings.denoiseView): shown as computed, no exposure, no tone curve. */
  readonly raw: boolean;
  readonly exposure: ExposureChoice;
  /** The scene's own exposure, kept while the automatic exposure's kernels compile. */
  readonly sceneStops: number;
  readonly scene: { readonly prepared: PreparedScene; readonly resources: SceneResources };
  /** The debug views, compiled where settings.debugView asks for one. */
  readonly debugViews: DebugViews | undefined;
}

export class ImageOutput {
  readonly exposure: AutoExposure;
  readonly selection: Selection;

  constructor(
    private readonly device: GPUDevice,
    private readonly tonemap: TonemapPass,
    private presentPass?: PresentPass,
  ) {
    this.exposure = new AutoExposure(device);
    this.selection = new Selection(device);
  }

  /** Compiles the present pipeline for targets of `format` (a canvas's; browser only: the CLI never draws to a surface). */
  async setPresentationFormat(format: GPUTextureFormat): Promise<void> {
    if (this.presentPass?.format !== format) this.presentPass = await PresentPass.create(this.device, format);
  }

  /** Tone-maps the image and draws it onto `target` (a canvas texture), with the selection outlined; with a timer, times the passes. */
  present(target: GPUTexture, shown: ShownImage, timer?: GpuTimer): void {
    if (!this.presentPass) throw new Error('Renderer: a presentation format (create or setPresentationFormat) before present()');
    const encoder = this.device.createCommandEncoder({ label: 'present' });
    // What is presented is seen in real time: the exposure adapts over the wall-clock time since the last present.
    this.encodeTonemap(encoder, shown, this.exposure.sincePresent(), timer);
    const image = this.selection.encode(encoder, shown.scene.resources, shown.view, this.encodeDebugView(encoder, shown));
    this.presentPass.encode(encoder, { image, target, timer });
    timer?.resolve(encoder);
    this.device.queue.submit([encoder.finish()]);
  }

  /** The tone-mapped sRGB image (with the debug view as settings.debugLayout asks), RGBA8, top row first; adapts by the seconds advanced. */
  async readImage(shown: ShownImage, timer?: GpuTimer): Promise<Uint8Array> {
    if (shown.exposure.kind === 'auto') await this.exposure.compile();
    const encoder = this.device.createCommandEncoder({ label: 'tone map for readback' });
    this.encodeTonemap(encoder, shown, this.exposure.takeAdvanced(), timer);
    timer?.resolve(encoder);
    const image = this.encodeDebugView(encoder, shown);
    this.device.queue.submit([encoder.finish()]);
    return readTexture4x8(this.device, image);
  }

  /** Runs the debug view once (settings.debugView must name one) and waits for it. */
  async renderDebugView(shown: ShownImage): Promise<void> {
    const encoder = this.device.createCommandEncoder({ label: 'debug view' });
    this.encodeDebugView(encoder, shown);
    this.device.queue.submit([encoder.finish()]);
    await this.device.queue.onSubmittedWorkDone();
  }

  private encodeTonemap(encoder: GPUCommandEncoder, shown: ShownImage, seconds: number, timer?: GpuTimer): void {
    const { targets, radiance, sampleCount, raw } = shown;
    const image = { view: shown.view, radiance, width: targets.width, height: targets.height, sampleCount, raw };
    const exposure = this.exposure.encode(encoder, shown.exposure, image, seconds, shown.sceneStops, timer);
    this.tonemap.encode(encoder, { view: shown.view, accumulation: radiance, output: targets.output, input: { ...exposure, toneMapper: raw ? 'linear' : shown.settings.toneMapper, sampleCount }, timer });
  }

  /** Encodes the debug view when one is set and returns the image to show: the composed one, or the tone-mapped one. */
  private encodeDebugView(encoder: GPUCommandEncoder, shown: ShownImage): GPUTexture {
    const { settings, targets } = shown;
    if (settings.debugView === 'none') return targets.output;
    if (!shown.debugViews) throw new Error('Renderer: compile() the debug views before showing one');
    return shown.debugViews.encode(encoder, { prepared: shown.scene.prepared, resources: shown.scene.resources, view: shown.view, image: targets.output, settings });
  }

  destroy(): void {
    this.tonemap.destroy();
    this.exposure.destroy();
    this.selection.destroy();
  }
}
