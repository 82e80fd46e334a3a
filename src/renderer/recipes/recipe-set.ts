/**
 * The recipes a renderer has compiled: the progressive one from the start unless the renderer was
 * made without it (then, as the others, once compile() asks for it), the others once compile() asked
 * for them (renderer/recipes/recipe.ts recipeCompiles), each for every scene prepared so far and
 * every later one. What a frame runs is looked up here; nothing outside decides it.
 */
import type { SceneFeatures } from '../../gpu/pack/scene-pack.ts';
import type { TracingKernels } from '../../passes/path-trace-pass.ts';
import type { WavefrontFramePass } from '../../passes/wavefront-frame-pass.ts';
import { DebugViews } from './debug.ts';
import type { FrameRecipe } from './frame-recipe.ts';
import { HybridRecipe } from './hybrid.ts';
import { ProgressiveRecipe } from './progressive.ts';
import { RealTimeRecipe } from './real-time.ts';
import type { Recipe, RecipeCompiles } from './recipe.ts';
import type { RenderSettings } from '../settings.ts';
import { resolveSampler, type Sampler, type SamplerSetting } from '../../passes/variants.ts';

/** What the set asks of its renderer. */
export interface RecipeSetHooks {
  /** The features of the scene set now, or of the one about to be set (what a recipe made now compiles first). */
  firstFeatures(): SceneFeatures | undefined;
  /** The features of the scene set now, if one is. */
  sceneFeatures(): SceneFeatures | undefined;
  /** The sampler setting now (what a tracing pass made later compiles for). */
  sampler(): SamplerSetting;
  /** A tracing pass joined the set: specialised kernels are compiled anew with it. */
  tracingAdded(): Promise<void>;
}

export class RecipeSet {
  realTime?: RealTimeRecipe;
  hybrid?: HybridRecipe;
  debugViews?: DebugViews;
  /** Whether the spectral variants are compiled for each scene. */
  spectral = false;
  /** The error of the last background compile of the wavefront path tracer, if it failed (frames stay on the megakernel). */
  wavefrontError?: unknown;
  /** The error of the last background compile of the ReSTIR passes, if it failed (frames keep one light sample per bounce). */
  restirError?: unknown;
  /** The path tracers' kernels for the sampler setting, compiling after a change (useSamplers). */
  private samplerPending: Promise<void> = Promise.resolve();
  /** The progressive recipe's compile, when compile() made it (a renderer made without it). */
  private progressivePending?: Promise<ProgressiveRecipe>;

  constructor(
    private readonly device: GPUDevice,
    /** The progressive path tracer: undefined until compile() asks for it, where the renderer was made without it. */
    public progressive: ProgressiveRecipe | undefined,
    private readonly hooks: RecipeSetHooks,
  ) {}

  /** Compiles what `wants` names that is not compiled yet, for the scene and every later one. */
  async compile(wants: RecipeCompiles): Promise<void> {
    await Promise.all([
      wants.progressive ? this.compileProgressive() : undefined, wants.debugViews ? this.compileDebugViews() : undefined,
      wants.spectral ? this.compileSpectral() : undefined, wants.hybrid ? this.compileHybrid() : undefined,
    ]);
    if (wants.realTime) await this.compileRealTime(wants);
  }

  /** Compiles every recipe compiled so far for a scene with these features (before it is uploaded). */
  prepare(features: SceneFeatures): Promise<unknown> {
    return Promise.all([
      this.progressive?.prepare(features), this.realTime?.prepare(features), this.hybrid?.prepare(features), this.debugViews?.prepare(features),
      ...(this.spectral ? [this.progressive?.prepare(features, true), this.realTime?.prepare(features, true)] : []),
    ]);
  }

  /** The progressive path tracer, for the sampler setting now, where the renderer was made without it. */
  private async compileProgressive(): Promise<void> {
    if (this.progressive) return;
    this.progressivePending ??= (async () => {
      const recipe = await ProgressiveRecipe.create(this.device, this.hooks.firstFeatures(), resolveSampler(this.hooks.sampler(), 'progressive'));
      const features = this.hooks.sceneFeatures();
      if (features) await Promise.all([recipe.prepare(features), this.spectral ? recipe.prepare(features, true) : undefined]);
      return recipe;
    })();
    try {
      const recipe = await this.progressivePending;
      if (this.progressive) return;
      this.progressive = recipe;
    } finally {
      this.progressivePending = undefined;
    }
    await this.hooks.tracingAdded();
  }

  async compileDebugViews(): Promise<DebugViews> {
    this.debugViews ??= await DebugViews.create(this.device, this.hooks.firstFeatures());
    const features = this.hooks.sceneFeatures();
    if (features) await this.debugViews.prepare(features);
    return this.debugViews;
  }

  private async compileSpectral(): Promise<void> {
    this.spectral = true;
    const features = this.hooks.sceneFeatures();
    if (features) await Promise.all([this.progressive?.prepare(features, true), this.realTime?.prepare(features, true)]);
  }

  private async compileHybrid(): Promise<void> {
    this.hybrid ??= await HybridRecipe.create(this.device, this.hooks.firstFeatures());
    const features = this.hooks.sceneFeatures();
    if (features) await this.hybrid.prepare(features);
  }

  /** The real-time chain, with the wavefront integrator and ReSTIR where asked. */
  private async compileRealTime(wants: { readonly wavefront: boolean; readonly restir: boolean }): Promise<void> {
    const created = !this.realTime;
    // For the sampler the settings ask for now: the default's kernels would be compiled and then switched away from.
    this.realTime ??= await RealTimeRecipe.create(this.device, this.hooks.firstFeatures(), resolveSampler(this.hooks.sampler(), 'real-time'));
    const features = this.hooks.sceneFeatures();
    if (features) await Promise.all([this.realTime.prepare(features), this.spectral ? this.realTime.prepare(features, true) : undefined]);
    if (wants.wavefront) await this.compileWavefront();
    if (wants.restir) await this.compileRestir();
    if (created) {
      this.useSamplers(this.hooks.sampler());
      await this.samplerPending;
      await this.hooks.tracingAdded();
    }
  }

  /** The wavefront frame path tracer, into the real-time chain (compiled first). Until it is ready, frames are traced by the megakernel. */
  async compileWavefront(): Promise<void> {
    if (!this.realTime) throw new Error('Renderer: the real-time chain before its wavefront integrator');
    const created = !this.realTime.wavefrontPass;
    await this.realTime.compileWavefront(this.hooks.sceneFeatures());
    this.wavefrontError = undefined;
    if (created) await this.hooks.tracingAdded();
  }

  /** The ReSTIR passes, into the real-time chain (compiled first). Until they are ready, frames run without them. */
  async compileRestir(): Promise<void> {
    if (!this.realTime) throw new Error('Renderer: the real-time chain before ReSTIR');
    await this.realTime.compileRestir(this.hooks.sceneFeatures());
    this.restirError = undefined;
  }

  /**
   * Compiles in the background what changed settings add to the recipes compiled: the wavefront
   * integrator (frames use the megakernel until it is ready) and the ReSTIR passes (frames take one
   * light sample per bounce until then). A failure is kept in wavefrontError or restirError.
   */
  follow(s: Pick<RenderSettings, 'integrator' | 'restir'>): void {
    if (!this.realTime) return;
    if (s.integrator === 'wavefront') this.compileWavefront().catch((e: unknown) => (this.wavefrontError = e));
    if (s.restir) this.compileRestir().catch((e: unknown) => (this.restirError = e));
  }

  /**
   * Compiles the path tracers for the samplers the setting resolves to, where they are compiled for
   * others (a PCG kernel holds no Sobol code: lib/random.wgsl SAMPLER). Until they are ready, samples
   * and frames are traced with the old ones (unbiased, but the old sampler's): renders that want the
   * new sampler's estimate alone await samplersSettled() first (Renderer.accelSettled).
   */
  useSamplers(setting: SamplerSetting): void {
    const wanted: [TracingKernels, Sampler][] = this.progressive ? [[this.progressive.kernels, resolveSampler(setting, 'progressive')]] : [];
    if (this.realTime) wanted.push([this.realTime.frameKernels, resolveSampler(setting, 'real-time')]);
    const switching = wanted.filter(([k, sampler]) => k.sampler !== sampler);
    if (switching.length === 0) return;
    const done = Promise.all(switching.map(([k, sampler]) => k.useSampler(sampler))).then(() => undefined);
    this.samplerPending = this.samplerPending.catch(() => undefined).then(() => done);
    this.samplerPending.catch(() => undefined); // the error is samplersSettled()'s to report
  }

  /** Resolves once every path tracer runs the sampler last asked for (rejects if its compile failed). */
  samplersSettled(): Promise<void> {
    return this.samplerPending;
  }

  /** The compiled recipe a frame of this recipe runs (undefined: a debug view alone, drawn at present). */
  frameRecipe(recipe: Recipe): FrameRecipe | undefined {
    if (recipe === 'debug') return undefined;
    if (recipe === 'progressive') throw new Error('Renderer: the progressive recipe is accumulated, not rendered as frames');
    const compiled = recipe === 'hybrid' ? this.hybrid : this.realTime;
    if (!compiled) throw new Error(`Renderer: compile() the ${recipe} recipe before renderFrame()`);
    return compiled;
  }

  /** Every tracing pass's kernels, the progressive path tracer's first (what specialisation compiles for). */
  tracingKernels(): { readonly sets: readonly TracingKernels[]; readonly wavefront?: WavefrontFramePass } {
    const wavefront = this.realTime?.wavefrontPass;
    return { sets: [...(this.progressive ? [this.progressive.kernels] : []), ...(this.realTime ? [this.realTime.frameKernels] : [])], ...(wavefront ? { wavefront } : {}) };
  }

  /** Drops the frame recipes' histories. */
  resetHistory(): void {
    this.realTime?.resetHistory();
    this.hybrid?.resetHistory();
  }

  destroy(): void {
    this.progressive?.destroy();
    this.progressive = undefined;
    this.realTime?.destroy();
    this.realTime = undefined;
    this.hybrid?.destroy();
    this.hybrid = undefined;
    this.debugViews?.destroy();
    this.debugViews = undefined;
  }
}
