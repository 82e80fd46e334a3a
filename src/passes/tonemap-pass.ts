/** Tone mapping (shaders/passes/tonemap.wgsl): accumulation → 8-bit sRGB image texture. */
import { ComputeKernel } from '../gpu/kernel.ts';
import type { GpuTimer } from '../gpu/timestamps.ts';
import { TONE_MAPPERS, type ToneMapper } from './variants.ts';
import type { ViewUniform } from '../gpu/view.ts';
import { UniformParams } from './uniform-params.ts';

const MODULE = 'passes/tonemap';
const WORKGROUP = 8;

export interface TonemapInput {
  readonly exposureStops: number;
  readonly toneMapper: ToneMapper;
  readonly sampleCount: number;
}

export class TonemapPass {
  private readonly groups = new WeakMap<GPUTexture, { view: ViewUniform; accumulation: GPUBuffer; group2: GPUBindGroup; group1: GPUBindGroup }>();

  private constructor(
    private readonly kernel: ComputeKernel,
    private readonly params: UniformParams<Record<string, number>>,
  ) {}

  static async create(device: GPUDevice): Promise<TonemapPass> {
    const kernel = await ComputeKernel.create(device, { module: MODULE, entryPoint: 'tonemap_image' });
    return new TonemapPass(kernel, new UniformParams(device, MODULE));
  }

  /** Writes the parameters now (queue.writeBuffer): submit before encoding again. */
  encode(encoder: GPUCommandEncoder, view: ViewUniform, accumulation: GPUBuffer, output: GPUTexture, input: TonemapInput, timer?: GpuTimer): void {
    this.params.write({
      exposure_scale: 2 ** input.exposureStops,
      tone_mapper: TONE_MAPPERS.indexOf(input.toneMapper),
      inv_sample_count: input.sampleCount > 0 ? 1 / input.sampleCount : 0,
    });
    let g = this.groups.get(output);
    if (!g || g.view !== view || g.accumulation !== accumulation) {
      g = {
        view,
        accumulation,
        group1: this.kernel.bindGroup(1, { view: view.buffer }),
        group2: this.kernel.bindGroup(2, { params: this.params.buffer, accumulation, output: output.createView() }),
      };
      this.groups.set(output, g);
    }
    const pass = encoder.beginComputePass({ label: 'tone map', ...(timer ? { timestampWrites: timer.timestampWrites('tone map') } : {}) });
    this.kernel.dispatch(pass, { 1: g.group1, 2: g.group2 }, Math.ceil(output.width / WORKGROUP), Math.ceil(output.height / WORKGROUP));
    pass.end();
  }

  destroy(): void {
    this.params.destroy();
  }
}
