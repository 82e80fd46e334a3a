/**
 * The WebGL2 backend's progressive renderer for a prepared scene (issue #30): the fragment path
 * tracer (passes/path-trace-fragment, frozen by gpu/fragment-tracer-wgsl.ts, translated at build
 * time) on the host of webgl2-renderer.ts. The scene is the one renderer/prepare.ts made for WebGPU:
 * its records as gpu/pack/scene-textures.ts's textures, scene_info, punctual_lights and
 * environment_info as uniform blocks of the same bytes; the view and the dispatch parameters are
 * written as the WebGPU path writes them (gpu/view.ts cameraUniform, passes/path-trace-pass.ts
 * pathTraceParams). The tracer is compiled for the scene's features (programs.ts webGl2TracerSpec:
 * Sobol sampling, 2048-texel rows, the static world a binary BVH): the build carries a few variants;
 * any other is translated here, naga's WebAssembly loaded for it the first time (translate.ts). Exposure: manual stops, or automatic from the read-back estimate (the CPU twin
 * of passes/exposure, renderer/exposure.ts).
 */
import { makeStructuredView, type StructuredView } from 'webgpu-utils';
import { LanternError } from '../errors.ts';
import { FRAGMENT_TRACER_MODULE } from '../gpu/fragment-tracer-wgsl.ts';
import { packSceneTextures } from '../gpu/pack/scene-textures.ts';
import { cameraUniform } from '../gpu/view.ts';
import { reflectModule } from '../gpu/wgsl/reflect.ts';
import { pathTraceParams } from '../passes/path-trace-pass.ts';
import { adaptExposureStops, exposureChoice, log2AverageLuminance, targetExposureStops } from '../renderer/exposure.ts';
import type { PreparedScene } from '../renderer/prepare.ts';
import { effectiveTorch, ESTIMATE_SETTINGS, type RenderSettings } from '../renderer/settings.ts';
import type { Camera, Torch } from '../scene/types.ts';
import { translatedPrograms, type GlslProgram } from './glsl.ts';
import { translateSpec, type NagaTranslate } from './translate.ts';
import { WEBGL2_ROW_SHIFT, webGl2TracerKey, webGl2TracerSpec } from './programs.ts';
import type { SceneFeatures } from '../gpu/pack/scene-pack.ts';
import type { WebGl2Canvas } from './context.ts';
import type { Wait } from './program.ts';
import { slot, WebGl2Renderer, type WebGl2RendererOptions } from './webgl2-renderer.ts';

const ACCUMULATION = slot(2, 1);
const PARAMS = slot(2, 0);
const VIEW = slot(1, 0);

export class WebGl2Tracer {
  private prepared?: PreparedScene;
  private tracerKey?: string;
  private camera?: Camera;
  private settings: RenderSettings;
  private torch?: Torch;
  private readonly uniforms = new Map<string, ArrayBufferView>();
  private readonly view: StructuredView;
  private readonly params: StructuredView;
  /** The automatic exposure's current stops (undefined until the first estimate). */
  private autoStops?: number;
  private lastExposureAt = 0;

  private constructor(
    readonly renderer: WebGl2Renderer,
    settings: RenderSettings,
  ) {
    this.settings = settings;
    this.view = makeStructuredView(reflectModule('view/bindings').defs.uniforms.view!);
    this.params = makeStructuredView(reflectModule(FRAGMENT_TRACER_MODULE).defs.uniforms.params!);
  }

  static async create(canvas: WebGl2Canvas, settings: RenderSettings, options: WebGl2RendererOptions = {}): Promise<WebGl2Tracer> {
    return new WebGl2Tracer(await WebGl2Renderer.create(canvas, options), settings);
  }

  get width(): number {
    return this.renderer.width;
  }

  get height(): number {
    return this.renderer.height;
  }

  get sampleCount(): number {
    return this.renderer.sampleCount;
  }

  /** Uploads a prepared scene (compiling the tracer variant it needs the first time); a scene WebGL2 cannot hold is one LanternError, the shown one kept. */
  async setScene(prepared: PreparedScene): Promise<void> {
    const { packed, scene } = prepared;
    if (packed.features.staticAccel !== 'bvh2') throw new LanternError(`the WebGL2 backend traces binary BVHs only; this scene is packed for ${packed.features.staticAccel}`, 'Set accel to bvh2, or use a browser with WebGPU');
    const limits = this.renderer.ctx.limits;
    const textures = packSceneTextures(packed, { maxTextureDimension2D: limits.maxTextureSize, maxTextureArrayLayers: limits.maxArrayTextureLayers, label: scene.name, rowShift: WEBGL2_ROW_SHIFT });
    const key = webGl2TracerKey(packed.features);
    if (key !== this.tracerKey) {
      await this.renderer.setTracer(await tracerProgram(packed.features), ACCUMULATION);
      this.tracerKey = key;
    }
    this.renderer.setSceneTextures(textures.textures, scene.name);
    this.uniforms.set(slot(0, 0), new Uint8Array(packed.scene_info));
    this.uniforms.set(slot(0, 14), new Uint8Array(packed.punctual_lights));
    this.uniforms.set(slot(0, 8), new Uint8Array(packed.environment.environment_info));
    this.prepared = prepared;
    this.torch = effectiveTorch(scene, this.settings.torch);
    this.camera ??= scene.camera;
    this.autoStops = undefined;
    this.writeView();
  }

  setCamera(camera: Camera): void {
    this.camera = camera;
    this.writeView();
    this.renderer.resetAccumulation();
  }

  /** New settings; those the estimate depends on restart it. */
  updateSettings(settings: RenderSettings): void {
    const before = this.settings;
    this.settings = settings;
    this.torch = effectiveTorch(this.prepared?.scene, settings.torch);
    if (ESTIMATE_SETTINGS.some((k) => settings[k] !== before[k])) this.renderer.resetAccumulation();
  }

  resize(width: number, height: number): void {
    this.renderer.resize(width, height);
    this.writeView();
  }

  resetAccumulation(): void {
    this.renderer.resetAccumulation();
  }

  /** Adds `samples` paths a pixel, `perDraw` in each draw. */
  accumulate(samples: number, perDraw = 1): void {
    if (!this.prepared) throw new LanternError('WebGL2: no scene to render yet');
    const s = this.settings;
    for (let done = 0; done < samples; done += perDraw) {
      const n = Math.min(perDraw, samples - done);
      this.params.set(
        pathTraceParams({
          tile: { x: 0, y: 0, width: this.width, height: this.height },
          sampleIndex: this.sampleCount,
          samples: n,
          maxBounces: s.maxBounces,
          seed: s.seed,
          lightSampling: s.lightSampling,
          sampler: 'sobol',
          ...(this.torch ? { torch: this.torch } : {}),
        }),
      );
      this.uniforms.set(PARAMS, new Uint8Array(this.params.arrayBuffer.slice(0)));
      this.renderer.accumulate({ uniforms: this.uniforms, samples: n });
    }
  }

  /** The exposure in stops the image gets now: manual, or adapted toward the estimate's average (read back). */
  exposureStops(now = performance.now()): number {
    const scene = this.prepared?.scene;
    const choice = exposureChoice(scene, this.camera?.exposureStops ?? 0, this.settings);
    if (choice.kind === 'manual') return choice.stops;
    if (this.sampleCount === 0) return this.autoStops ?? 0;
    const sums = this.renderer.readAccumulation();
    const target = targetExposureStops(log2AverageLuminance(sums, 4, 1 / this.sampleCount), choice.compensationStops);
    const seconds = (now - this.lastExposureAt) / 1000;
    this.lastExposureAt = now;
    this.autoStops = this.autoStops === undefined ? target : adaptExposureStops(this.autoStops, target, seconds, choice.adaptationSeconds);
    return this.autoStops;
  }

  /** Tone-maps the estimate and draws it on the canvas. */
  show(): void {
    this.renderer.tonemap(this.exposureStops(), this.settings.toneMapper);
    this.renderer.present();
  }

  readImage(): Uint8Array {
    return this.renderer.readImage();
  }

  readAccumulation(): Float32Array {
    return this.renderer.readAccumulation();
  }

  /** Waits for the GPU's work so far (a fence polled after each `wait`). */
  finish(wait?: Wait): Promise<void> {
    return this.renderer.finish(wait);
  }

  destroy(): void {
    this.renderer.destroy();
  }

  private writeView(): void {
    if (!this.camera || this.width === 0) return;
    this.view.set({ camera: cameraUniform(this.camera, this.width / this.height), image_size: [this.width, this.height] });
    this.uniforms.set(VIEW, new Uint8Array(this.view.arrayBuffer.slice(0)));
  }
}

/** Variants translated in this page, by key. */
const translatedHere = new Map<string, Promise<GlslProgram>>();
let naga: Promise<NagaTranslate> | undefined;

/** The tracer for `features`: the build's translation, else naga's in the page (loaded once, on the first such scene). */
function tracerProgram(features: SceneFeatures): Promise<GlslProgram> {
  const spec = webGl2TracerSpec(features);
  const built = translatedPrograms().get(spec.key);
  if (built) return Promise.resolve(built);
  let p = translatedHere.get(spec.key);
  if (!p) {
    naga ??= import('naga-wasm').then(async (m) => {
      await m.init();
      return m.translate as NagaTranslate;
    });
    p = naga.then((translate) => translateSpec(spec, translate));
    translatedHere.set(spec.key, p);
    p.catch(() => translatedHere.delete(spec.key));
  }
  return p;
}
