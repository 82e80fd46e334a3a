/**
 * When the tracing kernels are specialised to the frozen scene (gpu/specialisation.ts): on request,
 * or once the scene has gone a while without an edit (the idle policy the front ends share). The
 * compile is asynchronous and every edit overtakes it: frames keep rendering with the generic kernels
 * until it is ready, and go back to them at once when the scene or an estimate setting changes.
 */
import { LanternError } from '../errors.ts';
import { describeSpecialisation, specialiseScene, type SpecialiseOptions } from '../gpu/specialisation.ts';
import type { SceneResources } from '../gpu/scene-resources.ts';
import type { TracingKernels } from '../passes/path-trace-pass.ts';
import { LIGHT_SAMPLING } from '../passes/variants.ts';
import type { WavefrontFramePass } from '../passes/wavefront-frame-pass.ts';
import type { PreparedScene } from './prepare.ts';
import type { RenderSettings } from './settings.ts';

/** Which kernels the tracing passes run: the generic ones (the scene read from buffers) or those specialised to the frozen scene. */
export const KERNEL_KINDS = ['generic', 'specialised'] as const;
export type KernelKind = (typeof KERNEL_KINDS)[number];

/** What requestSpecialisation compiled and switched to. */
export interface SpecialisationReport {
  /** Wall milliseconds of the asynchronous compile (every specialised pipeline, in parallel). */
  readonly compileMs: number;
  /** gpu/specialisation.ts describeSpecialisation: traversal, material kinds, inlined settings. */
  readonly description: string;
  /** Traced without a BVH (primitives unrolled as constants). */
  readonly unrolled: boolean;
  readonly primitiveCount: number;
}

/** What the schedule specialises: the scene and settings as they are now, and every tracing pass's kernels. */
export interface SpecialisationSubject {
  current(): { readonly prepared: PreparedScene; readonly resources: SceneResources; readonly settings: RenderSettings } | undefined;
  /** The progressive path tracer's kernels first (they say which kind runs), then the other recipes' that exist now. */
  kernels(): { readonly sets: readonly TracingKernels[]; readonly wavefront?: WavefrontFramePass };
}

export class SpecialisationSchedule {
  /** Bumped by every edit, so a compile that an edit overtook is dropped. */
  private epoch = 0;
  private pending?: { readonly epoch: number; readonly done: Promise<SpecialisationReport | undefined> };
  private value?: SpecialisationReport;
  private idleMs?: number;
  private idleTimer?: ReturnType<typeof setTimeout>;
  /** The error of the last automatic (idle) specialisation, if it failed; rendering stays generic. */
  error?: unknown;

  constructor(private readonly subject: SpecialisationSubject) {}

  /** Which kernels run now: generic until a compile is ready, and again after every edit. */
  get kernel(): KernelKind {
    const resources = this.subject.current()?.resources;
    return resources && this.subject.kernels().sets[0]?.isSpecialised(resources) ? 'specialised' : 'generic';
  }

  /** Which kernels the wavefront frame path tracer runs now. */
  get wavefrontKernel(): KernelKind {
    const resources = this.subject.current()?.resources;
    return resources && this.subject.kernels().wavefront?.isSpecialised(resources) ? 'specialised' : 'generic';
  }

  /** What the specialised kernels in use were compiled for, and how long that took. */
  get report(): SpecialisationReport | undefined {
    return this.kernel === 'specialised' ? this.value : undefined;
  }

  /** Renderer.requestSpecialisation. */
  request(options: SpecialiseOptions = {}): Promise<SpecialisationReport | undefined> {
    const current = this.subject.current();
    if (!current) throw new Error('Renderer: setScene() before requestSpecialisation()');
    // Specialised kernels are compiled in RGB; spectral mode keeps the generic spectral variants.
    if (current.settings.spectral) return Promise.resolve(undefined);
    // A scene with moving instances is never frozen: its generic two-level kernels are the ones to use.
    if (current.prepared.levels) return Promise.resolve(undefined);
    if (this.kernel === 'specialised') return Promise.resolve(this.value);
    const epoch = this.epoch;
    if (this.pending?.epoch === epoch) return this.pending.done;
    const done = this.specialise(epoch, options);
    this.pending = { epoch, done };
    return done;
  }

  private async specialise(epoch: number, options: SpecialiseOptions): Promise<SpecialisationReport | undefined> {
    const { prepared, resources, settings: s } = this.subject.current()!;
    const spec = specialiseScene(prepared.packed, prepared.scene.name, { maxBounces: s.maxBounces, lightSampling: LIGHT_SAMPLING.indexOf(s.lightSampling) }, options);
    const { sets, wavefront } = this.subject.kernels();
    const t0 = performance.now();
    const [compiled, wavefrontKernels] = await Promise.all([Promise.all(sets.map((k) => k.compileSpecialised(spec))), wavefront?.compileSpecialised(spec)]);
    const compileMs = performance.now() - t0;
    if (epoch !== this.epoch || resources !== this.subject.current()?.resources) return undefined;
    sets.forEach((k, i) => k.useSpecialised({ scene: resources, kernel: compiled[i]!.kernel }));
    if (wavefront && wavefrontKernels) wavefront.useSpecialised({ scene: resources, kernels: wavefrontKernels });
    this.value = { compileMs, description: describeSpecialisation(spec), unrolled: spec.unrolled !== undefined, primitiveCount: spec.primitiveCount };
    return this.value;
  }

  /** Renderer.invalidateSpecialisation: back to the generic kernels, any compile under way dropped, the idle timer restarted. */
  invalidate(): void {
    this.epoch++;
    this.pending = undefined;
    this.value = undefined;
    const { sets, wavefront } = this.subject.kernels();
    for (const k of sets) k.useSpecialised(undefined);
    wavefront?.useSpecialised(undefined);
    this.schedule();
  }

  /** Renderer.setIdleSpecialisation. */
  setIdle(idleMs: number | undefined): void {
    if (idleMs !== undefined && !(Number.isFinite(idleMs) && idleMs >= 0)) throw new LanternError(`the idle delay before specialising must be a number of milliseconds ≥ 0, not ${idleMs}`);
    this.idleMs = idleMs;
    this.schedule();
  }

  private schedule(): void {
    if (this.idleTimer !== undefined) clearTimeout(this.idleTimer);
    this.idleTimer = undefined;
    if (this.idleMs === undefined || !this.subject.current() || this.kernel === 'specialised') return;
    this.idleTimer = setTimeout(() => {
      this.idleTimer = undefined;
      if (!this.subject.current()) return;
      this.request().then(
        () => (this.error = undefined),
        (e: unknown) => (this.error = e),
      );
    }, this.idleMs);
  }
}
