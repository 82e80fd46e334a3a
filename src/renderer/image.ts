/**
 * The image: its targets (the accumulation, the ray counters, the tone-mapped texture), sized within
 * the GPU's limits, and the progressive estimate they hold (its sample count, and an epoch that
 * counts its restarts).
 */
import { LanternError } from '../errors.ts';
import { withErrorScope } from '../gpu/device.ts';

/** Bytes per pixel of the accumulation buffer (one vec4f). */
const ACCUMULATION_BYTES_PER_PIXEL = 16;
/** An image side beyond this is refused even where the GPU would allow it. */
export const MAX_IMAGE_SIDE = 16384;

/** The image's own buffers, which outlive frames and recipes (the Renderer's; a resize replaces them). */
export interface ImageTargets {
  readonly width: number;
  readonly height: number;
  /** The progressive estimate: a vec4f per pixel (radiance sum, luminance square sum). */
  readonly accumulation: GPUBuffer;
  /** Extension and shadow rays traced since the estimate restarted (two u64 as four u32). */
  readonly rayCounters: GPUBuffer;
  /** The tone-mapped image (rgba8unorm). */
  readonly output: GPUTexture;
}

/** The targets of a width × height image (checkImageSize first); GPU errors in making them reject, naming the size. */
export function createImageTargets(device: GPUDevice, width: number, height: number): Promise<ImageTargets> {
  return withErrorScope(device, `a ${width}×${height} image`, () => ({
    width,
    height,
    accumulation: device.createBuffer({ label: 'accumulation', size: width * height * ACCUMULATION_BYTES_PER_PIXEL, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC | GPUBufferUsage.COPY_DST }),
    rayCounters: device.createBuffer({ label: 'ray counters', size: 16, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC | GPUBufferUsage.COPY_DST }),
    output: device.createTexture({
      label: 'tone-mapped image',
      size: [width, height],
      format: 'rgba8unorm',
      usage: GPUTextureUsage.STORAGE_BINDING | GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_SRC,
    }),
  }));
}

export function destroyImageTargets(targets: ImageTargets): void {
  targets.accumulation.destroy();
  targets.rayCounters.destroy();
  targets.output.destroy();
}

/** Throws a LanternError when an image of this size is not a sensible request or exceeds the GPU's limits. */
export function checkImageSize(width: number, height: number, limits: GPUSupportedLimits): void {
  for (const [name, v] of [['width', width], ['height', height]] as const) {
    if (!Number.isInteger(v) || v < 1) throw new LanternError(`image ${name} must be a whole number of pixels ≥ 1, not ${v}`);
  }
  const maxSide = Math.min(MAX_IMAGE_SIDE, limits.maxTextureDimension2D);
  if (width > maxSide || height > maxSide) {
    throw new LanternError(`image ${width}×${height} is too large: each side may be at most ${maxSide} pixels on this GPU`);
  }
  const bytes = width * height * ACCUMULATION_BYTES_PER_PIXEL;
  if (bytes > limits.maxStorageBufferBindingSize || bytes > limits.maxBufferSize) {
    const maxPixels = Math.floor(Math.min(limits.maxStorageBufferBindingSize, limits.maxBufferSize) / ACCUMULATION_BYTES_PER_PIXEL);
    throw new LanternError(`image ${width}×${height} is too large for this GPU: at most ${maxPixels} pixels fit one accumulation buffer`);
  }
}

/** The image's targets and the estimate in them. */
export class ImageEstimate {
  private value?: ImageTargets;
  private sampleCount = 0;
  private offset = 0;
  private epochValue = 0;

  constructor(private readonly device: GPUDevice) {}

  /** The targets, once sized. */
  get targets(): ImageTargets | undefined {
    return this.value;
  }
  /** Samples per pixel in the estimate. */
  get samples(): number {
    return this.sampleCount;
  }
  /**
   * The global index of the estimate's next sample: its first sample's index (0 unless the restart
   * named one: a farm's shard renders samples [s0, s1) of one sequence) plus the samples so far.
   */
  get nextSampleIndex(): number {
    return this.offset + this.sampleCount;
  }
  /** Counts restarts (the ray counters restart with each). */
  get epoch(): number {
    return this.epochValue;
  }

  /** Sizes the image (checked against the GPU's limits); false when it already had this size. */
  async resize(width: number, height: number): Promise<boolean> {
    checkImageSize(width, height, this.device.limits);
    if (this.value && this.value.width === width && this.value.height === height) return false;
    const targets = await createImageTargets(this.device, width, height);
    this.destroy();
    this.value = targets;
    return true;
  }

  /** Discards every sample and the ray counts; the next sample is the sequence's `firstSample`-th. */
  restart(firstSample = 0): void {
    this.sampleCount = 0;
    this.offset = firstSample;
    this.epochValue++;
    if (!this.value) return;
    const encoder = this.device.createCommandEncoder({ label: 'reset accumulation' });
    encoder.clearBuffer(this.value.accumulation);
    encoder.clearBuffer(this.value.rayCounters);
    this.device.queue.submit([encoder.finish()]);
  }

  /** Replaces the estimate by `sums` (a vec4f per pixel: Σ radiance, Σ luminance², as the path tracer adds them) of `samples` samples. */
  load(sums: Float32Array, samples: number): void {
    if (!this.value) throw new Error('ImageEstimate: resize() before load()');
    if (sums.length !== this.value.width * this.value.height * 4) throw new Error(`ImageEstimate: ${sums.length} floats for a ${this.value.width}×${this.value.height} image`);
    this.restart();
    this.device.queue.writeBuffer(this.value.accumulation, 0, sums.buffer, sums.byteOffset, sums.byteLength);
    this.sampleCount = samples;
  }

  /** Counts samples once they are submitted. */
  add(samples: number): void {
    this.sampleCount += samples;
  }

  destroy(): void {
    if (this.value) destroyImageTargets(this.value);
    this.value = undefined;
  }
}
