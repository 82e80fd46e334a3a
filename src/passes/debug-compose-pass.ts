/**
 * The composing half of the debug views (shaders/passes/debug-compose.wgsl): colours the raw values
 * and wireframe lines and composes them with the tone-mapped image into the image that is shown.
 */
import { pixelGroups } from '../gpu/kernel-variants.ts';
import { ComputeKernel } from '../gpu/kernel.ts';
import { COLOR_SCALE_STOPS, stopRgb } from '../math/color-scale.ts';
import { DEBUG_LAYOUTS, DEBUG_VIEWS, type DebugLayout, type DebugView } from './variants.ts';
import type { ViewUniform } from '../gpu/view.ts';
import type { Pass, PassFrame } from './pass.ts';
import { UniformParams, type UniformValues } from './uniform-params.ts';

const MODULE = 'passes/debug-compose';

export interface DebugComposeInput {
  readonly view: DebugView;
  readonly layout: DebugLayout;
  /** Scalar views: the value at the top of the colour scale; 0 for the image's own maximum. */
  readonly scaleMax: number;
  readonly values: GPUBuffer;
  readonly range: GPUBuffer;
  /** The tone-mapped image. */
  readonly image: GPUTexture;
  readonly wireframe: GPUTexture;
}

export interface DebugComposeFrame extends PassFrame {
  readonly view: ViewUniform;
  readonly input: DebugComposeInput;
  /** The composed image (written). */
  readonly output: GPUTexture;
}

export class DebugComposePass implements Pass<DebugComposeFrame> {
  private constructor(
    private readonly kernel: ComputeKernel,
    private readonly params: UniformParams<UniformValues>,
  ) {}

  static async create(device: GPUDevice): Promise<DebugComposePass> {
    const kernel = await ComputeKernel.create(device, { module: MODULE, entryPoint: 'debug_compose' });
    return new DebugComposePass(kernel, new UniformParams(device, MODULE));
  }

  /** Writes the parameters now (queue.writeBuffer): submit before encoding again. */
  encode(encoder: GPUCommandEncoder, { view, input, output }: DebugComposeFrame): void {
    this.params.write({
      view_kind: DEBUG_VIEWS.indexOf(input.view),
      composition: DEBUG_LAYOUTS.indexOf(input.layout),
      scale_max: input.scaleMax,
      scale_stops: COLOR_SCALE_STOPS.flatMap((hex) => [...stopRgb(hex), 1]),
    });
    const pass = encoder.beginComputePass({ label: 'debug compose' });
    this.kernel.dispatch(
      pass,
      {
        1: this.kernel.bindGroup(1, { view: view.buffer }),
        2: this.kernel.bindGroup(2, {
          params: this.params.buffer,
          debug_values: input.values,
          debug_range: input.range,
          image: input.image.createView(),
          wireframe: input.wireframe.createView(),
          output: output.createView(),
        }),
      },
      ...pixelGroups(output.width, output.height),
    );
    pass.end();
  }

  destroy(): void {
    this.params.destroy();
  }
}
