/**
 * Present (shaders/passes/present.wgsl): draws the tone-mapped image onto a canvas texture, scaled to
 * fit. One render pipeline, for the canvas's format, compiled asynchronously when the pass is made;
 * the bind group layout comes from reflection.
 */
import { BindGroupFactory, compileShader, createBindGroupLayouts } from '../gpu/kernel.ts';
import { compileRenderPipeline } from '../gpu/pipeline-compiles.ts';
import { entryPointBindings, reflectModule } from '../gpu/wgsl/reflect.ts';
import type { Pass, PassFrame } from './pass.ts';

const MODULE = 'passes/present';

export interface PresentFrame extends PassFrame {
  /** The tone-mapped (or composed) image to show. */
  readonly image: GPUTexture;
  /** The canvas texture drawn into, of the pass's `format`. */
  readonly target: GPUTexture;
}

export class PresentPass implements Pass<PresentFrame> {
  private readonly groups = new WeakMap<GPUTexture, GPUBindGroup>();

  private constructor(
    private readonly bindings: BindGroupFactory,
    private readonly sampler: GPUSampler,
    /** The canvas format the pipeline draws into. */
    readonly format: GPUTextureFormat,
    private readonly pipeline: GPURenderPipeline,
  ) {}

  static async create(device: GPUDevice, format: GPUTextureFormat): Promise<PresentPass> {
    const shader = reflectModule(MODULE);
    const module = await compileShader(device, shader.linked);
    const slots = entryPointBindings(shader, ['present_vertex', 'present_fragment'], GPUShaderStage.VERTEX | GPUShaderStage.FRAGMENT);
    const layouts = createBindGroupLayouts(device, MODULE, slots);
    const sampler = device.createSampler({ label: 'present', magFilter: 'linear', minFilter: 'linear' });
    const pipeline = await compileRenderPipeline(device, {
      label: `present ${format}`,
      layout: device.createPipelineLayout({ label: 'present', bindGroupLayouts: layouts }),
      vertex: { module, entryPoint: 'present_vertex' },
      fragment: { module, entryPoint: 'present_fragment', targets: [{ format }] },
      primitive: { topology: 'triangle-list' },
    });
    return new PresentPass(new BindGroupFactory(device, MODULE, layouts, slots), sampler, format, pipeline);
  }

  encode(encoder: GPUCommandEncoder, { image, target, timer }: PresentFrame): void {
    if (target.format !== this.format) throw new Error(`present: the pipeline draws into ${this.format}, not ${target.format} (enablePresentation with the canvas's format)`);
    let group = this.groups.get(image);
    if (!group) {
      group = this.bindings.bindGroup(0, { image: image.createView(), image_sampler: this.sampler });
      this.groups.set(image, group);
    }
    const pass = encoder.beginRenderPass({
      label: 'present',
      ...(timer ? { timestampWrites: timer.timestampWrites('present') } : {}),
      colorAttachments: [{ view: target.createView(), loadOp: 'clear', storeOp: 'store', clearValue: [0, 0, 0, 1] }],
    });
    pass.setPipeline(this.pipeline);
    pass.setBindGroup(0, group);
    pass.draw(3);
    pass.end();
  }

  /** Nothing of its own to free: the bind groups are dropped with their images. */
  destroy(): void {}
}
