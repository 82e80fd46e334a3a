/**
 * Reading the image's buffers back (Renderer.readAccumulation, readFrame, readRayCounts): the
 * accumulation as mean radiance with its per-pixel luminance variance, a frame's linear output, the
 * ray counters.
 */
import { readBuffer } from '../gpu/readback.ts';
import type { ImageTargets } from './image.ts';

export interface RayCounts {
  readonly extension: number;
  readonly shadow: number;
}

export interface Accumulation {
  readonly width: number;
  readonly height: number;
  readonly samples: number;
  /** Mean radiance, 3 floats per pixel, row-major, top row first. */
  readonly radiance: Float32Array;
  /** Per-pixel sample variance of luminance (unbiased), 1 float per pixel. */
  readonly luminanceVariance: Float32Array;
}

/** Linear radiance of a real-time frame. */
export interface LinearImage {
  readonly width: number;
  readonly height: number;
  /** 3 floats per pixel, row-major, top row first. */
  readonly radiance: Float32Array;
}

/** The estimate of `samples` samples in the accumulation buffer (radiance sums and luminance square sums). */
export async function readAccumulation(device: GPUDevice, targets: ImageTargets, samples: number): Promise<Accumulation> {
  return accumulationEstimate(new Float32Array(await readBuffer(device, targets.accumulation)), targets.width, targets.height, samples);
}

/** The estimate of `samples` samples from raw accumulation sums (a vec4f per pixel): what readAccumulation gives, computed on the CPU (lantern merge's EXR). */
export function accumulationEstimate(raw: Float32Array, width: number, height: number, samples: number): Accumulation {
  const n = width * height;
  const radiance = new Float32Array(n * 3);
  const luminanceVariance = new Float32Array(n);
  const inv = samples > 0 ? 1 / samples : 0;
  for (let i = 0; i < n; i++) {
    const r = raw[i * 4]! * inv, g = raw[i * 4 + 1]! * inv, b = raw[i * 4 + 2]! * inv;
    radiance[i * 3] = r;
    radiance[i * 3 + 1] = g;
    radiance[i * 3 + 2] = b;
    if (samples > 1) {
      const mean = 0.2126 * r + 0.7152 * g + 0.0722 * b;
      luminanceVariance[i] = Math.max(0, (raw[i * 4 + 3]! - samples * mean * mean) / (samples - 1));
    }
  }
  return { width, height, samples, radiance, luminanceVariance };
}

/** A frame's linear output (a vec4f per pixel) as rgb. */
export async function readLinear(device: GPUDevice, output: GPUBuffer, size: { readonly width: number; readonly height: number }): Promise<LinearImage> {
  const raw = new Float32Array(await readBuffer(device, output));
  const n = size.width * size.height;
  const radiance = new Float32Array(n * 3);
  for (let i = 0; i < n; i++) for (let c = 0; c < 3; c++) radiance[i * 3 + c] = raw[i * 4 + c]!;
  return { width: size.width, height: size.height, radiance };
}

/** Rays traced since the counters were cleared: two u64 as four u32. */
export async function readRayCounts(device: GPUDevice, targets: ImageTargets): Promise<RayCounts> {
  const w = new Uint32Array(await readBuffer(device, targets.rayCounters));
  return { extension: w[0]! + w[1]! * 2 ** 32, shadow: w[2]! + w[3]! * 2 ** 32 };
}
