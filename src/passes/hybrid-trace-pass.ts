/**
 * The hybrid recipe's traced passes (shaders/passes/hybrid.wgsl): resolve (the raster's visibility
 * to the exact ray hit: guide and motion), shade (emission and direct light), reflect (specular
 * paths from the primary hit) and GI (diffuse paths at the GI target's scale). Each is one entry
 * point over the scene, the view and the hybrid's per-pixel buffers (group 2, the same names for all
 * four), dispatched over a tile: the whole image, or the GI target. The kernels are the path
 * tracer's (TracingKernels): a variant per scene feature set (the renderer does not specialise them).
 */
import type { SceneFeatures } from '../gpu/pack/scene-pack.ts';
import type { SceneResources } from '../gpu/scene-resources.ts';
import type { NamedResource } from '../gpu/kernel.ts';
import type { ViewUniform } from '../gpu/view.ts';
import type { Pass, PassFrame } from './pass.ts';
import { TracingKernels, type Tile } from './path-trace-pass.ts';

const MODULE = 'passes/hybrid';

/** The four traced steps of a hybrid frame, in the order a frame runs them, with their entry points. */
export const HYBRID_TRACED = { resolve: 'hybrid_resolve', shade: 'hybrid_shade', reflect: 'hybrid_reflect', gi: 'hybrid_gi' } as const;
export type HybridTraced = keyof typeof HYBRID_TRACED;

/** The timer labels of the traced steps. */
const LABELS: Record<HybridTraced, string> = { resolve: 'resolve', shade: 'shade', reflect: 'reflect', gi: 'GI' };

export interface HybridTraceFrame extends PassFrame {
  readonly scene: SceneResources;
  readonly view: ViewUniform;
  /** The hybrid's buffers as group 2 names them. Bind groups are cached by `key`: pass the same object while the buffers are the same. */
  readonly targets: { readonly key: object; readonly resources: () => Readonly<Record<string, NamedResource>> };
  /** The pixels (or GI texels) dispatched over. */
  readonly tile: Tile;
}

export class HybridTracePass implements Pass<HybridTraceFrame> {
  private constructor(
    private readonly kernels: TracingKernels,
    private readonly label: string,
  ) {}

  /** `first`: the features of the scene to be rendered, where known (its variant compiles instead of a plain scene's). */
  static async create(device: GPUDevice, step: HybridTraced, first?: SceneFeatures): Promise<HybridTracePass> {
    return new HybridTracePass(await TracingKernels.create(device, MODULE, HYBRID_TRACED[step], {}, first), LABELS[step]);
  }

  /** Compiles the variant a scene with these features needs (RGB: spectral mode is the path tracers'). */
  prepare(features: SceneFeatures): Promise<void> {
    return this.kernels.prepare(features);
  }

  encode(encoder: GPUCommandEncoder, { scene, view, targets, tile, timer }: HybridTraceFrame): void {
    this.kernels.dispatch(encoder, this.label, scene, view, targets.key, targets.resources, tile, false, timer);
  }

  /** The kernels own nothing per frame: the buffers are the recipe's. */
  destroy(): void {}
}
