/**
 * Automatic exposure (shaders/passes/exposure.wgsl): the log-average luminance of the radiance the
 * tone map is about to show, reduced in two dispatches (64 × 64-pixel tiles to partial sums, then one
 * workgroup over those), and the adapted exposure written to a small state buffer the tone map reads.
 * Nothing comes back to the CPU on the way: the exposure stays on the GPU.
 */
import { ComputeKernel } from '../gpu/kernel.ts';
import { readBuffer } from '../gpu/readback.ts';
import type { ViewUniform } from '../gpu/view.ts';
import type { Pass, PassFrame } from './pass.ts';
import { UniformParams } from './uniform-params.ts';

const MODULE = 'passes/exposure';
/** REDUCE_TILE of exposure.wgsl: the pixels one reduce workgroup covers along each axis. */
const TILE = 64;
/** ExposureState of lib/exposure.wgsl: three f32. */
const STATE_BYTES = 16;

export interface ExposureInput {
  /** Samples accumulated per pixel in `radiance` (1 for a real-time frame). */
  readonly sampleCount: number;
  /** exp(−Δt / τ): 0 snaps to the target. */
  readonly keep: number;
  readonly compensationStops: number;
}

export interface ExposureReading {
  /** log2 of the log-average luminance of the last image reduced. */
  readonly log2Average: number;
  /** The exposure in use, stops. */
  readonly stops: number;
}

export interface ExposureFrame extends PassFrame {
  readonly view: ViewUniform;
  /** The radiance to reduce (vec4f per pixel, `input.sampleCount` samples summed). */
  readonly radiance: GPUBuffer;
  readonly width: number;
  readonly height: number;
  readonly input: ExposureInput;
}

/** Its output is its own: `state`, which the tone map binds (read() brings it to the CPU). */
export class ExposurePass implements Pass<ExposureFrame> {
  /** The adapted exposure (ExposureState): the tone map binds it. */
  readonly state: GPUBuffer;
  private partials?: GPUBuffer;
  private readonly groups = new WeakMap<GPUBuffer, { view: ViewUniform; partials: GPUBuffer; group1: GPUBindGroup; reduce: GPUBindGroup; adapt: GPUBindGroup }>();

  private constructor(
    private readonly device: GPUDevice,
    private readonly reduce: ComputeKernel,
    private readonly adapt: ComputeKernel,
    private readonly params: UniformParams<Record<string, number>>,
  ) {
    this.state = device.createBuffer({ label: 'exposure state', size: STATE_BYTES, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC });
  }

  static async create(device: GPUDevice): Promise<ExposurePass> {
    const [reduce, adapt] = await Promise.all([
      ComputeKernel.create(device, { module: MODULE, entryPoint: 'exposure_reduce' }),
      ComputeKernel.create(device, { module: MODULE, entryPoint: 'exposure_adapt' }),
    ]);
    return new ExposurePass(device, reduce, adapt, new UniformParams(device, MODULE));
  }

  /** Writes the parameters now (queue.writeBuffer): submit before encoding again. */
  encode(encoder: GPUCommandEncoder, { view, radiance, width, height, input, timer }: ExposureFrame): void {
    const groupsX = Math.ceil(width / TILE);
    const groupsY = Math.ceil(height / TILE);
    const count = groupsX * groupsY;
    if (!this.partials || this.partials.size < count * 8) {
      this.partials?.destroy();
      this.partials = this.device.createBuffer({ label: 'exposure partial sums', size: count * 8, usage: GPUBufferUsage.STORAGE });
    }
    this.params.write({ inv_sample_count: input.sampleCount > 0 ? 1 / input.sampleCount : 0, groups_x: groupsX, group_count: count, keep: input.keep, compensation_stops: input.compensationStops });
    let g = this.groups.get(radiance);
    if (!g || g.view !== view || g.partials !== this.partials) {
      g = {
        view,
        partials: this.partials,
        group1: this.reduce.bindGroup(1, { view: view.buffer }),
        reduce: this.reduce.bindGroup(2, { params: this.params.buffer, radiance, partials: this.partials }),
        adapt: this.adapt.bindGroup(2, { params: this.params.buffer, partials: this.partials, state: this.state }),
      };
      this.groups.set(radiance, g);
    }
    const pass = encoder.beginComputePass({ label: 'exposure', ...(timer ? { timestampWrites: timer.timestampWrites('exposure') } : {}) });
    this.reduce.dispatch(pass, { 1: g.group1, 2: g.reduce }, groupsX, groupsY);
    this.adapt.dispatch(pass, { 2: g.adapt }, 1);
    pass.end();
  }

  /** The state as the last encoded pass left it (waits for the GPU). */
  async read(): Promise<ExposureReading> {
    const [log2Average, stops] = new Float32Array(await readBuffer(this.device, this.state, STATE_BYTES));
    return { log2Average: log2Average!, stops: stops! };
  }

  destroy(): void {
    this.state.destroy();
    this.partials?.destroy();
    this.params.destroy();
  }
}
