/**
 * The wireframe debug view (shaders/passes/bvh-wireframe.wgsl): the edges of a list of BVH boxes
 * drawn as lines onto a texture cleared to transparent. A render pipeline (line-list) so that the
 * hardware clips lines at the near plane; its bind group layouts come from reflection.
 */
import { BindGroupFactory, compileShader, createBindGroupLayouts } from '../gpu/kernel.ts';
import { compileRenderPipeline } from '../gpu/pipeline-compiles.ts';
import type { SceneResources } from '../gpu/scene-resources.ts';
import { entryPointBindings, reflectModule } from '../gpu/wgsl/reflect.ts';
import type { ViewUniform } from '../gpu/view.ts';
import type { Pass, PassFrame } from './pass.ts';
import { UniformParams } from './uniform-params.ts';

const MODULE = 'passes/bvh-wireframe';
/** 12 edges × 2 ends. */
const VERTICES_PER_BOX = 24;
export const WIREFRAME_FORMAT: GPUTextureFormat = 'rgba8unorm';

export interface BvhWireframeFrame extends PassFrame {
  readonly scene: SceneResources;
  readonly view: ViewUniform;
  /** Indices into the BVH of the boxes to draw. */
  readonly nodes: GPUBuffer;
  readonly count: number;
  /** Points nearer than this along the view direction are clipped. */
  readonly near: number;
  readonly target: GPUTexture;
}

export class BvhWireframePass implements Pass<BvhWireframeFrame> {
  private constructor(
    private readonly bindings: BindGroupFactory,
    private readonly pipeline: GPURenderPipeline,
    private readonly params: UniformParams<{ near: number }>,
  ) {}

  static async create(device: GPUDevice): Promise<BvhWireframePass> {
    const shader = reflectModule(MODULE);
    const module = await compileShader(device, shader.linked);
    const slots = entryPointBindings(shader, ['wireframe_vertex', 'wireframe_fragment'], GPUShaderStage.VERTEX | GPUShaderStage.FRAGMENT);
    const layouts = createBindGroupLayouts(device, MODULE, slots);
    const pipeline = await compileRenderPipeline(device, {
      label: MODULE,
      layout: device.createPipelineLayout({ label: MODULE, bindGroupLayouts: layouts }),
      vertex: { module, entryPoint: 'wireframe_vertex' },
      fragment: { module, entryPoint: 'wireframe_fragment', targets: [{ format: WIREFRAME_FORMAT }] },
      primitive: { topology: 'line-list' },
    });
    return new BvhWireframePass(new BindGroupFactory(device, MODULE, layouts, slots), pipeline, new UniformParams(device, MODULE));
  }

  /**
   * Clears `target` to transparent and draws the boxes of `nodes` (count indices into the BVH) onto
   * it; points nearer than `near` along the view direction are clipped. Writes the parameters now.
   */
  encode(encoder: GPUCommandEncoder, { scene, view, nodes, count, near, target }: BvhWireframeFrame): void {
    this.params.write({ near });
    const pass = encoder.beginRenderPass({
      label: 'bvh wireframe',
      colorAttachments: [{ view: target.createView(), loadOp: 'clear', storeOp: 'store', clearValue: [0, 0, 0, 0] }],
    });
    if (count > 0) {
      pass.setPipeline(this.pipeline);
      pass.setBindGroup(0, this.bindings.bindGroup(0, scene.bindings));
      pass.setBindGroup(1, this.bindings.bindGroup(1, { view: view.buffer }));
      pass.setBindGroup(2, this.bindings.bindGroup(2, { params: this.params.buffer, wireframe_nodes: nodes }));
      pass.draw(VERTICES_PER_BOX, count);
    }
    pass.end();
  }

  destroy(): void {
    this.params.destroy();
  }
}
