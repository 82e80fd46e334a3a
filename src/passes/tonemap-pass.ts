/** Tone mapping (shaders/passes/tonemap.wgsl): accumulation → 8-bit sRGB image texture. */
import { pixelGroups } from '../gpu/kernel-variants.ts';
import { ComputeKernel } from '../gpu/kernel.ts';
import { TONE_MAPPERS, type ToneMapper } from './variants.ts';
import type { ViewUniform } from '../gpu/view.ts';
import type { Pass, PassFrame } from './pass.ts';
import { UniformParams } from './uniform-params.ts';

const MODULE = 'passes/tonemap';

export interface TonemapInput {
  /** Stops of exposure; with `autoExposure`, stops over the adapted exposure. */
  readonly exposureStops: number;
  /**
   * The adapted exposure (ExposurePass.state, lib/exposure.wgsl ExposureState), to multiply by; absent
   * for a fixed exposure (a small zero buffer is bound in its place).
   */
  readonly autoExposure?: GPUBuffer;
  readonly toneMapper: ToneMapper;
  readonly sampleCount: number;
}

export interface TonemapFrame extends PassFrame {
  readonly view: ViewUniform;
  /** The radiance (vec4f per pixel, `input.sampleCount` samples summed). */
  readonly accumulation: GPUBuffer;
  /** The 8-bit sRGB image (written). */
  readonly output: GPUTexture;
  readonly input: TonemapInput;
}

export class TonemapPass implements Pass<TonemapFrame> {
  private readonly groups = new WeakMap<GPUTexture, { view: ViewUniform; accumulation: GPUBuffer; exposure: GPUBuffer; group2: GPUBindGroup; group1: GPUBindGroup }>();
  /** Bound where no adapted exposure is: the shader ignores it then. */
  private readonly noExposure: GPUBuffer;

  private constructor(
    device: GPUDevice,
    private readonly kernel: ComputeKernel,
    private readonly params: UniformParams<Record<string, number>>,
  ) {
    this.noExposure = device.createBuffer({ label: 'tone map: no adapted exposure', size: 16, usage: GPUBufferUsage.STORAGE });
  }

  static async create(device: GPUDevice): Promise<TonemapPass> {
    const kernel = await ComputeKernel.create(device, { module: MODULE, entryPoint: 'tonemap_image' });
    return new TonemapPass(device, kernel, new UniformParams(device, MODULE));
  }

  /** Writes the parameters now (queue.writeBuffer): submit before encoding again. */
  encode(encoder: GPUCommandEncoder, { view, accumulation, output, input, timer }: TonemapFrame): void {
    this.params.write({
      exposure_scale: 2 ** input.exposureStops,
      tone_mapper: TONE_MAPPERS.indexOf(input.toneMapper),
      inv_sample_count: input.sampleCount > 0 ? 1 / input.sampleCount : 0,
      auto_exposure: input.autoExposure ? 1 : 0,
    });
    const exposure = input.autoExposure ?? this.noExposure;
    let g = this.groups.get(output);
    if (!g || g.view !== view || g.accumulation !== accumulation || g.exposure !== exposure) {
      g = {
        view,
        accumulation,
        exposure,
        group1: this.kernel.bindGroup(1, { view: view.buffer }),
        group2: this.kernel.bindGroup(2, { params: this.params.buffer, accumulation, output: output.createView(), exposure }),
      };
      this.groups.set(output, g);
    }
    const pass = encoder.beginComputePass({ label: 'tone map', ...(timer ? { timestampWrites: timer.timestampWrites('tone map') } : {}) });
    this.kernel.dispatch(pass, { 1: g.group1, 2: g.group2 }, ...pixelGroups(output.width, output.height));
    pass.end();
  }

  destroy(): void {
    this.params.destroy();
    this.noExposure.destroy();
  }
}
