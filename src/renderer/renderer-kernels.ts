/**
 * The kernels a Renderer runs (renderer/renderer.ts extends this): the recipes compiled so far and
 * what compile() adds to them (renderer/recipes/recipe-set.ts), when the tracing kernels are
 * specialised to the scene (renderer/specialisation-schedule.ts), and what both report: which kernels
 * and integrator run, the errors of background compiles, the real-time chain's memory, and the raw
 * output of the benchmarks' trace-only frame.
 */
import type { SceneFeatures } from '../gpu/pack/scene-pack.ts';
import type { SceneResources } from '../gpu/scene-resources.ts';
import type { SpecialiseOptions } from '../gpu/specialisation.ts';
import type { PreparedScene } from './prepare.ts';
import type { ProgressiveRecipe } from './recipes/progressive.ts';
import type { DenoiserBufferSize, FrameTrace } from './recipes/real-time.ts';
import { recipeCompiles, type RecipeIntent } from './recipes/recipe.ts';
import { RecipeSet } from './recipes/recipe-set.ts';
import type { Integrator, RenderSettings } from './settings.ts';
import { SpecialisationSchedule, type KernelKind, type SpecialisationReport } from './specialisation-schedule.ts';

export abstract class RendererKernels {
  /** The recipes compiled so far (renderer/recipes/recipe-set.ts). */
  protected readonly recipes: RecipeSet;
  /** When the tracing kernels are specialised to the scene (requestSpecialisation, the idle policy). */
  protected readonly specialising = new SpecialisationSchedule({
    current: () => (this.scene && this.resources ? { prepared: this.scene, resources: this.resources, settings: this.settings } : undefined),
    kernels: () => this.recipes.tracingKernels(),
  });

  protected constructor(device: GPUDevice, progressive: ProgressiveRecipe | undefined) {
    this.recipes = new RecipeSet(device, progressive, {
      firstFeatures: () => this.sceneFeatures,
      sceneFeatures: () => this.scene?.packed.features,
      sampler: () => this.settings.sampler,
      tracingAdded: async () => {
        // Specialised kernels are compiled for every tracing pass at once (a compile under way lacks the new one's): specialise again with it.
        this.invalidateSpecialisation();
      },
    });
  }

  /** The settings now. */
  abstract get settings(): RenderSettings;
  /** The scene set now, if one is. */
  abstract get scene(): PreparedScene | undefined;
  /** The scene's resources on the GPU, if one is set. */
  protected abstract get resources(): SceneResources | undefined;

  /** The features of the scene setScene will get, as Renderer.create was told, until one is set. */
  protected expectedFeatures?: SceneFeatures;

  /** The features of the scene (or of the one about to be set): what a recipe enabled now compiles for first. */
  protected get sceneFeatures(): SceneFeatures | undefined {
    return this.scene?.packed.features ?? this.expectedFeatures;
  }

  /**
   * Compiles what the recipe of the settings (with `changes`) runs (recipeCompiles), for this and
   * every later scene, before its first frame; nothing is compiled twice. `intent.frames`: frames are
   * asked for even with every filter of the real-time chain off (the CLI's --frames).
   */
  async compile(changes: Partial<RenderSettings> = {}, intent: RecipeIntent = {}): Promise<void> {
    await this.recipes.compile(recipeCompiles({ ...this.settings, ...changes }, intent));
  }

  /** The error of the last background compile of the wavefront path tracer, if it failed (frames stay on the megakernel). */
  get wavefrontError(): unknown {
    return this.recipes.wavefrontError;
  }

  /** The error of the last background compile of the ReSTIR passes, if it failed (frames keep one light sample per bounce). */
  get restirError(): unknown {
    return this.recipes.restirError;
  }

  /** Which path tracer traced the last real-time frame (settings.integrator, or the megakernel while the wavefront compiles). */
  get frameIntegrator(): Integrator {
    return this.recipes.realTime?.frameIntegrator ?? 'megakernel';
  }

  /** Bytes per pixel of the real-time denoising chain's buffers, each and in all (RealTimeRecipe.bufferSizes; empty until a frame). */
  get denoiserMemory(): { readonly bytesPerPixel: number; readonly buffers: readonly DenoiserBufferSize[] } {
    return { bytesPerPixel: this.recipes.realTime?.bytesPerPixel() ?? 0, buffers: this.recipes.realTime?.bufferSizes() ?? [] };
  }

  /** Bytes the wavefront path tracer's own buffers hold (path state and queues; 0 until it traced a frame). */
  get wavefrontBytes(): number {
    return this.recipes.realTime?.wavefrontAllocatedBytes ?? 0;
  }

  /**
   * The raw output of the last traceFrame: demodulated radiance, G-buffer, guide, albedo, emission
   * (after renderFrame the radiance words hold the frame's output instead: the chain reuses them).
   * traceFrame overwrites the shown frame's output likewise.
   */
  readFrameTrace(): Promise<FrameTrace> {
    const realTime = this.recipes.realTime;
    if (!realTime) throw new Error('Renderer: compile() the real-time chain before readFrameTrace()');
    return realTime.readTrace();
  }

  // Specialisation (renderer/specialisation-schedule.ts): kernels compiled for the frozen scene, used once ready.

  /** Which kernels accumulate() and renderFrame() run now (camera moves, resizes and display settings keep them). */
  get kernel(): KernelKind {
    return this.specialising.kernel;
  }

  /** Which kernels the wavefront frame path tracer runs now. */
  get wavefrontKernel(): KernelKind {
    return this.specialising.wavefrontKernel;
  }

  /** What the specialised kernels in use were compiled for, and how long that took. */
  get specialisation(): SpecialisationReport | undefined {
    return this.specialising.report;
  }

  /** The error of the last automatic (idle) specialisation, if it failed; rendering stays generic. */
  get specialisationError(): unknown {
    return this.specialising.error;
  }

  /**
   * Compiles the kernels specialised to the scene and settings as they are now: resolves with the
   * report once switched, undefined when an edit came first, and at once with undefined in spectral
   * mode and for scenes with moving instances. Accumulation continues (the same estimator).
   */
  requestSpecialisation(options: SpecialiseOptions = {}): Promise<SpecialisationReport | undefined> {
    return this.specialising.request(options);
  }

  /** Back to the generic kernels, any compile under way dropped; every method that edits the scene or an estimate setting calls it. */
  invalidateSpecialisation(): void {
    this.specialising.invalidate();
  }

  /** The front ends' idle policy: specialise once the scene has gone `idleMs` without an edit (the viewer: 1000); undefined turns it off. */
  setIdleSpecialisation(idleMs: number | undefined): void {
    this.specialising.setIdle(idleMs);
  }
}
