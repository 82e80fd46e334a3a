/**
 * Ray generation for the traversal benchmark: primary rays through pixel centres
 * (shaders/passes/primary-rays.wgsl) and diffuse rays from the primary hits
 * (shaders/passes/diffuse-rays.wgsl). Two modules, one small class: they only ever run together.
 */
import { ComputeKernel } from '../gpu/kernel.ts';
import type { ViewUniform } from '../gpu/view.ts';
import { rayDispatchSize } from './trace-rays-pass.ts';
import { UniformParams } from './uniform-params.ts';

const PRIMARY_WORKGROUP = 8;

export class BenchmarkRaysPass {
  private constructor(
    private readonly device: GPUDevice,
    private readonly primary: ComputeKernel,
    private readonly diffuse: ComputeKernel,
    private readonly params: UniformParams<{ ray_count: number; seed: number }>,
  ) {}

  static async create(device: GPUDevice): Promise<BenchmarkRaysPass> {
    const primary = await ComputeKernel.create(device, { module: 'passes/primary-rays', entryPoint: 'generate_primary_rays' });
    const diffuse = await ComputeKernel.create(device, { module: 'passes/diffuse-rays', entryPoint: 'generate_diffuse_rays' });
    return new BenchmarkRaysPass(device, primary, diffuse, new UniformParams(device, 'passes/diffuse-rays'));
  }

  encodePrimary(encoder: GPUCommandEncoder, view: ViewUniform, width: number, height: number, rays: GPUBuffer): void {
    const pass = encoder.beginComputePass({ label: 'generate primary rays' });
    this.primary.dispatch(
      pass,
      { 1: this.primary.bindGroup(1, { view: view.buffer }), 2: this.primary.bindGroup(2, { rays }) },
      Math.ceil(width / PRIMARY_WORKGROUP),
      Math.ceil(height / PRIMARY_WORKGROUP),
    );
    pass.end();
  }

  /** Writes its parameters now (queue.writeBuffer): submit before encoding again. */
  encodeDiffuse(encoder: GPUCommandEncoder, count: number, primaryRays: GPUBuffer, primaryHits: GPUBuffer, rays: GPUBuffer, seed: number): void {
    this.params.write({ ray_count: count, seed });
    const pass = encoder.beginComputePass({ label: 'generate diffuse rays' });
    const [x, y] = rayDispatchSize(count, this.device.limits.maxComputeWorkgroupsPerDimension);
    this.diffuse.dispatch(pass, { 2: this.diffuse.bindGroup(2, { params: this.params.buffer, rays, primary_rays: primaryRays, primary_hits: primaryHits }) }, x, y);
    pass.end();
  }

  destroy(): void {
    this.params.destroy();
  }
}
