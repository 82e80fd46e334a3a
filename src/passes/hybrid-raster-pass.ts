/**
 * The hybrid recipe's raster first hit (shaders/passes/hybrid-raster.wgsl): two render pipelines
 * over the scene's primitive records, one for triangles and one for spheres and capsules (drawn as
 * their boxes, depth from the exact intersection), into a visibility buffer (rg32uint: instance,
 * primitive) and a reversed depth buffer: opaque triangles, analytic primitives, then alpha-masked
 * triangles (the only fragments that may discard). One draw for the static world and one per moving instance
 * (its mesh's primitives, placed by its instance record). Pipelines are compiled per scene features,
 * as the compute kernels are.
 */
import { compileShader, createBindGroupLayouts, BindGroupFactory } from '../gpu/kernel.ts';
import { FEATURE_CONSTANTS, featureConstants, featureKey } from '../gpu/kernel-variants.ts';
import type { SceneFeatures } from '../gpu/pack/scene-pack.ts';
import { compileRenderPipeline } from '../gpu/pipeline-compiles.ts';
import type { SceneResources } from '../gpu/scene-resources.ts';
import type { ViewUniform } from '../gpu/view.ts';
import { entryPointBindings, reflectModule } from '../gpu/wgsl/reflect.ts';
import type { Pass, PassFrame } from './pass.ts';
import { UniformParams, type UniformValues } from './uniform-params.ts';

const MODULE = 'passes/hybrid-raster';
const ENTRIES = ['raster_triangle', 'raster_fragment', 'raster_masked_triangle', 'raster_masked_fragment', 'raster_analytic', 'raster_analytic_fragment'] as const;
/** The features the raster module compiles by. */
const RASTER_FEATURES: readonly (keyof SceneFeatures)[] = ['alphaMasks', 'analyticPrimitives', 'instances'];

export const VISIBILITY_FORMAT: GPUTextureFormat = 'rg32uint';
export const DEPTH_FORMAT: GPUTextureFormat = 'depth32float';
/** The visibility texel of an uncovered pixel (hybrid/visibility.wgsl VISIBILITY_NONE). */
const VISIBILITY_NONE = 0xffffffff;

/** One draw: `count` primitives from `first` in the primitive records, placed by GPU instance `instance` (0: the static world). */
export interface RasterDraw {
  readonly first: number;
  readonly count: number;
  readonly instance: number;
}

export interface RasterFrame extends PassFrame {
  readonly scene: SceneResources;
  readonly view: ViewUniform;
  readonly visibility: GPUTextureView;
  readonly depth: GPUTextureView;
  readonly draws: readonly RasterDraw[];
  /** Subpixel offset of this frame (pixels). */
  readonly jitter: readonly [number, number];
  /** Linear depth of the near plane (scene units). */
  readonly near: number;
}

interface Pipelines {
  readonly triangles: GPURenderPipeline;
  readonly masked: GPURenderPipeline;
  readonly analytic: GPURenderPipeline;
}

export class HybridRasterPass implements Pass<RasterFrame> {
  private readonly ready = new Map<string, Pipelines>();
  private readonly pending = new Map<string, Promise<Pipelines>>();
  private readonly sceneGroups = new WeakMap<SceneResources, GPUBindGroup>();
  private readonly viewGroups = new WeakMap<ViewUniform, GPUBindGroup>();
  private paramsGroup?: GPUBindGroup;

  private constructor(
    private readonly device: GPUDevice,
    private readonly groups: BindGroupFactory,
    private readonly layout: GPUPipelineLayout,
    private readonly module: GPUShaderModule,
    private readonly declared: ReadonlySet<string>,
    private readonly params: UniformParams<UniformValues>,
  ) {}

  /** `first`: the features of the scene to be rendered, where known: its pipelines start compiling at once (prepare reports their errors). */
  static async create(device: GPUDevice, first?: SceneFeatures): Promise<HybridRasterPass> {
    const shader = reflectModule(MODULE);
    const slots = entryPointBindings(shader, ENTRIES, GPUShaderStage.VERTEX | GPUShaderStage.FRAGMENT);
    const layouts = createBindGroupLayouts(device, MODULE, slots);
    const layout = device.createPipelineLayout({ label: MODULE, bindGroupLayouts: layouts });
    const module = await compileShader(device, shader.linked);
    const declared = new Set(Object.values(FEATURE_CONSTANTS).filter((name) => new RegExp(`override\\s+${name}\\b`).test(shader.linked.code)));
    const pass = new HybridRasterPass(device, new BindGroupFactory(device, MODULE, layouts, slots), layout, module, declared, new UniformParams(device, MODULE, 'raster'));
    if (first) pass.prepare(first).catch(() => undefined); // prepare(first) again reports a failure
    return pass;
  }

  private key(f: SceneFeatures): string {
    return featureKey(RASTER_FEATURES, f);
  }

  /** Compiles the pipelines a scene with these features needs, once. */
  async prepare(f: SceneFeatures): Promise<void> {
    const key = this.key(f);
    if (this.ready.has(key)) return;
    let pending = this.pending.get(key);
    if (!pending) {
      const constants = Object.fromEntries(Object.entries(featureConstants(RASTER_FEATURES, f)).filter(([name]) => this.declared.has(name)));
      const make = (vertex: string, fragment: string) =>
        compileRenderPipeline(this.device, {
          label: `${MODULE}:${vertex}`,
          layout: this.layout,
          vertex: { module: this.module, entryPoint: vertex, constants },
          fragment: { module: this.module, entryPoint: fragment, constants, targets: [{ format: VISIBILITY_FORMAT }] },
          primitive: { topology: 'triangle-list', cullMode: 'none' },
          depthStencil: { format: DEPTH_FORMAT, depthWriteEnabled: true, depthCompare: 'greater' },
        });
      pending = Promise.all([make('raster_triangle', 'raster_fragment'), make('raster_masked_triangle', 'raster_masked_fragment'), make('raster_analytic', 'raster_analytic_fragment')]).then(([triangles, masked, analytic]) => ({ triangles, masked, analytic }));
      this.pending.set(key, pending);
    }
    this.ready.set(key, await pending);
  }

  /** Records the raster pass (parameters are written now: submit before encoding again). */
  encode(encoder: GPUCommandEncoder, f: RasterFrame): void {
    const pipelines = this.ready.get(this.key(f.scene.features));
    if (!pipelines) throw new Error(`${MODULE}: no pipelines for scene features ${JSON.stringify(f.scene.features)} (prepare() first)`);
    this.params.write({ jitter: [...f.jitter], near: f.near });
    let sceneGroup = this.sceneGroups.get(f.scene);
    if (!sceneGroup) this.sceneGroups.set(f.scene, (sceneGroup = this.groups.bindGroup(0, f.scene.bindings)));
    let viewGroup = this.viewGroups.get(f.view);
    if (!viewGroup) this.viewGroups.set(f.view, (viewGroup = this.groups.bindGroup(1, { view: f.view.buffer })));
    this.paramsGroup ??= this.groups.bindGroup(2, { raster: this.params.buffer });
    const pass = encoder.beginRenderPass({
      label: 'raster',
      colorAttachments: [{ view: f.visibility, loadOp: 'clear', storeOp: 'store', clearValue: { r: VISIBILITY_NONE, g: VISIBILITY_NONE, b: 0, a: 0 } }],
      depthStencilAttachment: { view: f.depth, depthLoadOp: 'clear', depthStoreOp: 'store', depthClearValue: 0 },
      ...(f.timer ? { timestampWrites: f.timer.timestampWrites('raster') } : {}),
    });
    const draw = (pipeline: GPURenderPipeline, verticesPerPrimitive: number) => {
      pass.setPipeline(pipeline);
      pass.setBindGroup(0, sceneGroup);
      pass.setBindGroup(1, viewGroup);
      pass.setBindGroup(2, this.paramsGroup!);
      for (const d of f.draws) if (d.count > 0) pass.draw(d.count * verticesPerPrimitive, 1, d.first * verticesPerPrimitive, d.instance);
    };
    draw(pipelines.triangles, 3);
    if (f.scene.features.analyticPrimitives) draw(pipelines.analytic, 36);
    if (f.scene.features.alphaMasks) draw(pipelines.masked, 3);
    pass.end();
  }

  destroy(): void {
    this.params.destroy();
  }
}
