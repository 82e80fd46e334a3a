/**
 * A per-pixel pass over the whole image with one workgroup per tile of WORKGROUP.pixelX × pixelY (gpu/kernel-variants.ts): the view (group 1) for
 * the image size, and its own parameters, inputs and outputs (group 2). The denoiser's temporal,
 * à-trous and output passes are image passes. Parameters live in `slots` uniform buffers, so a pass
 * that runs several times in one submit (the à-trous iterations) writes each slot once.
 */
import { pixelGroups } from '../gpu/kernel-variants.ts';
import { ComputeKernel, type NamedResource } from '../gpu/kernel.ts';
import type { ViewUniform } from '../gpu/view.ts';
import type { Pass, PassFrame } from './pass.ts';
import { UniformParams, type UniformValues } from './uniform-params.ts';

export interface ImagePassFrame extends PassFrame {
  /** Bind groups 1 and 2 (bindGroups()). */
  readonly groups: Record<number, GPUBindGroup>;
  readonly width: number;
  readonly height: number;
  /** The compute pass's label and timer label; default the pass's own. */
  readonly label?: string;
}

export class ImagePass<T extends UniformValues> implements Pass<ImagePassFrame> {
  private constructor(
    private readonly kernel: ComputeKernel,
    private readonly params: readonly UniformParams<T>[],
    private readonly label: string,
  ) {}

  static async create<T extends UniformValues>(device: GPUDevice, module: string, entryPoint: string, label: string, slots = 1): Promise<ImagePass<T>> {
    const kernel = await ComputeKernel.create(device, { module, entryPoint });
    return new ImagePass(kernel, Array.from({ length: slots }, () => new UniformParams<T>(device, module)), label);
  }

  /** Bind groups 1 and 2 for one set of resources (named as in WGSL; `params` is added), parameters from `slot`. */
  bindGroups(view: ViewUniform, resources: Readonly<Record<string, NamedResource>>, slot = 0): Record<number, GPUBindGroup> {
    return {
      1: this.kernel.bindGroup(1, { view: view.buffer }),
      2: this.kernel.bindGroup(2, { ...resources, params: this.params[slot]!.buffer }),
    };
  }

  /** Writes a slot's parameters now (queue.writeBuffer): submit before writing the same slot again. */
  write(values: T, slot = 0): void {
    this.params[slot]!.write(values);
  }

  encode(encoder: GPUCommandEncoder, { groups, width, height, timer, label = this.label }: ImagePassFrame): void {
    const pass = encoder.beginComputePass({ label, ...(timer ? { timestampWrites: timer.timestampWrites(label) } : {}) });
    this.kernel.dispatch(pass, groups, ...pixelGroups(width, height));
    pass.end();
  }

  destroy(): void {
    for (const p of this.params) p.destroy();
  }
}
