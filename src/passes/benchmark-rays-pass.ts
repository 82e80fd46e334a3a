/**
 * Primary-ray generation for the traversal benchmark (shaders/passes/primary-rays.wgsl): rays through
 * pixel centres, stored by 8 × 8-pixel tiles or by rows. The diffuse rays are made on the CPU from
 * the traced hits (renderer/benchmark-rays.ts).
 */
import { pixelGroups } from '../gpu/kernel-variants.ts';
import { ComputeKernel } from '../gpu/kernel.ts';
import type { ViewUniform } from '../gpu/view.ts';
import type { Pass, PassFrame } from './pass.ts';
import { UniformParams } from './uniform-params.ts';

/** The WGSL's RAY_ORDER_* values. */
const RAY_ORDER_CODE = { tiles: 0, scanline: 1 } as const;
export type RayOrder = keyof typeof RAY_ORDER_CODE;
export const RAY_ORDERS = Object.keys(RAY_ORDER_CODE) as RayOrder[];

export interface BenchmarkRaysFrame extends PassFrame {
  readonly view: ViewUniform;
  readonly width: number;
  readonly height: number;
  /** Where the rays go, one per pixel. */
  readonly rays: GPUBuffer;
  readonly order: RayOrder;
}

export class BenchmarkRaysPass implements Pass<BenchmarkRaysFrame> {
  private constructor(
    private readonly primary: ComputeKernel,
    private readonly params: UniformParams<{ order: number }>,
  ) {}

  static async create(device: GPUDevice): Promise<BenchmarkRaysPass> {
    const primary = await ComputeKernel.create(device, { module: 'passes/primary-rays', entryPoint: 'generate_primary_rays' });
    return new BenchmarkRaysPass(primary, new UniformParams(device, 'passes/primary-rays'));
  }

  /** Writes its parameters now (queue.writeBuffer): submit before encoding again. */
  encode(encoder: GPUCommandEncoder, { view, width, height, rays, order }: BenchmarkRaysFrame): void {
    this.params.write({ order: RAY_ORDER_CODE[order] });
    const pass = encoder.beginComputePass({ label: 'generate primary rays' });
    this.primary.dispatch(
      pass,
      { 1: this.primary.bindGroup(1, { view: view.buffer }), 2: this.primary.bindGroup(2, { rays, params: this.params.buffer }) },
      ...pixelGroups(width, height),
    );
    pass.end();
  }

  destroy(): void {
    this.params.destroy();
  }
}
