/**
 * Present (shaders/passes/present.wgsl): draws the tone-mapped image onto a canvas texture, scaled to
 * fit. A render pipeline per canvas format; the bind group layout comes from reflection.
 */
import { BindGroupFactory, compileShader, createBindGroupLayouts } from '../gpu/kernel.ts';
import type { GpuTimer } from '../gpu/timestamps.ts';
import { entryPointBindings, reflectModule } from '../gpu/wgsl/reflect.ts';

const MODULE = 'passes/present';

export class PresentPass {
  private readonly pipelines = new Map<GPUTextureFormat, GPURenderPipeline>();
  private readonly groups = new WeakMap<GPUTexture, GPUBindGroup>();

  private constructor(
    private readonly device: GPUDevice,
    private readonly module: GPUShaderModule,
    private readonly bindings: BindGroupFactory,
    private readonly sampler: GPUSampler,
  ) {}

  static async create(device: GPUDevice): Promise<PresentPass> {
    const shader = reflectModule(MODULE);
    const module = await compileShader(device, shader.linked);
    const slots = entryPointBindings(shader, ['present_vertex', 'present_fragment'], GPUShaderStage.VERTEX | GPUShaderStage.FRAGMENT);
    const layouts = createBindGroupLayouts(device, MODULE, slots);
    const sampler = device.createSampler({ label: 'present', magFilter: 'linear', minFilter: 'linear' });
    return new PresentPass(device, module, new BindGroupFactory(device, MODULE, layouts, slots), sampler);
  }

  encode(encoder: GPUCommandEncoder, image: GPUTexture, target: GPUTexture, timer?: GpuTimer): void {
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
    pass.setPipeline(this.pipeline(target.format));
    pass.setBindGroup(0, group);
    pass.draw(3);
    pass.end();
  }

  private pipeline(format: GPUTextureFormat): GPURenderPipeline {
    let p = this.pipelines.get(format);
    if (!p) {
      p = this.device.createRenderPipeline({
        label: `present ${format}`,
        layout: this.device.createPipelineLayout({ label: 'present', bindGroupLayouts: [...this.bindings.layouts] }),
        vertex: { module: this.module, entryPoint: 'present_vertex' },
        fragment: { module: this.module, entryPoint: 'present_fragment', targets: [{ format }] },
        primitive: { topology: 'triangle-list' },
      });
      this.pipelines.set(format, p);
    }
    return p;
  }
}
