/**
 * Image comparison for `lantern diff`: RMSE, relative MSE and SSIM between two linear RGB images
 * (float, 3 channels per pixel), and an error heat map.
 *
 * - RMSE: √(mean over pixels and channels of (a − b)²).
 * - relMSE: mean of (a − b)² / (b² + 0.01), b the reference (Rousselle et al. 2011): errors in dark
 *   regions count as much as in bright ones, and the ε keeps black pixels finite.
 * - SSIM (Wang et al. 2004): on luminance mapped to display range (L / (1 + L), then sRGB), an 11×11
 *   Gaussian window with σ = 1.5, K1 = 0.01, K2 = 0.03, dynamic range 1, averaged over the image.
 *   Written here rather than taken from ssim.js, which takes 8-bit RGBA and not HDR radiance.
 */
import { luminance } from '../math/vec3.ts';

export interface LinearRgbImage {
  readonly width: number;
  readonly height: number;
  /** 3 floats per pixel, row-major. */
  readonly rgb: Float32Array;
}

export interface ImageDifference {
  readonly rmse: number;
  readonly relMse: number;
  readonly ssim: number;
}

export const REL_MSE_EPSILON = 0.01;

/** Root mean squared difference over pixels and channels. */
export function rmse(a: Float32Array, b: Float32Array): number {
  let se = 0;
  for (let i = 0; i < a.length; i++) se += (a[i]! - b[i]!) ** 2;
  return Math.sqrt(se / a.length);
}

export function compareImages(a: LinearRgbImage, reference: LinearRgbImage): ImageDifference {
  if (a.width !== reference.width || a.height !== reference.height) {
    throw new RangeError(`images differ in size: ${a.width}×${a.height} and ${reference.width}×${reference.height}`);
  }
  let rel = 0;
  for (let i = 0; i < a.rgb.length; i++) rel += (a.rgb[i]! - reference.rgb[i]!) ** 2 / (reference.rgb[i]! ** 2 + REL_MSE_EPSILON);
  const n = a.rgb.length;
  return { rmse: rmse(a.rgb, reference.rgb), relMse: rel / n, ssim: ssim(displayLuminance(a), displayLuminance(reference), a.width, a.height) };
}

/** Luminance mapped to [0, 1) as a display would show it: Reinhard, then the sRGB transfer curve. */
export function displayLuminance(img: LinearRgbImage): Float32Array {
  const out = new Float32Array(img.width * img.height);
  for (let i = 0; i < out.length; i++) {
    const l = Math.max(luminance([img.rgb[i * 3]!, img.rgb[i * 3 + 1]!, img.rgb[i * 3 + 2]!]), 0);
    const m = l / (1 + l);
    out[i] = m <= 0.0031308 ? 12.92 * m : 1.055 * m ** (1 / 2.4) - 0.055;
  }
  return out;
}

const SSIM_RADIUS = 5;
const SSIM_SIGMA = 1.5;
const C1 = 0.01 ** 2;
const C2 = 0.03 ** 2;

/** Mean SSIM of two single-channel images in [0, 1], Gaussian-windowed (windows clipped at the borders). */
export function ssim(x: Float32Array, y: Float32Array, width: number, height: number): number {
  const kernel = Array.from({ length: 2 * SSIM_RADIUS + 1 }, (_, i) => Math.exp(-((i - SSIM_RADIUS) ** 2) / (2 * SSIM_SIGMA ** 2)));
  // Separable blur of x, y, x², y², xy: along rows, then along columns.
  const pass = (src: (i: number) => number, along: 'row' | 'column'): Float64Array => {
    const out = new Float64Array(width * height);
    const [n, stride] = along === 'row' ? [width, 1] : [height, width];
    for (let i = 0; i < width * height; i++) {
      const at = along === 'row' ? i % width : Math.floor(i / width);
      let s = 0, w = 0;
      for (let k = Math.max(-SSIM_RADIUS, -at); k <= Math.min(SSIM_RADIUS, n - 1 - at); k++) {
        s += kernel[k + SSIM_RADIUS]! * src(i + k * stride);
        w += kernel[k + SSIM_RADIUS]!;
      }
      out[i] = s / w;
    }
    return out;
  };
  const blur = (f: (i: number) => number): Float64Array => {
    const rows = pass(f, 'row');
    return pass((i) => rows[i]!, 'column');
  };
  const mx = blur((i) => x[i]!), my = blur((i) => y[i]!);
  const xx = blur((i) => x[i]! * x[i]!), yy = blur((i) => y[i]! * y[i]!), xy = blur((i) => x[i]! * y[i]!);
  let sum = 0;
  for (let i = 0; i < width * height; i++) {
    const vx = xx[i]! - mx[i]! ** 2, vy = yy[i]! - my[i]! ** 2, cxy = xy[i]! - mx[i]! * my[i]!;
    sum += ((2 * mx[i]! * my[i]! + C1) * (2 * cxy + C2)) / ((mx[i]! ** 2 + my[i]! ** 2 + C1) * (vx + vy + C2));
  }
  return sum / (width * height);
}

/**
 * A heat map of per-pixel relative error |a − b| / (b + 0.01) in luminance: black (none) through red
 * and yellow to white at `fullScale` (default 1: 100 %) or more. RGBA8, row-major.
 */
export function errorHeatmap(a: LinearRgbImage, reference: LinearRgbImage, fullScale = 1): Uint8Array {
  const n = a.width * a.height;
  const out = new Uint8Array(n * 4);
  for (let i = 0; i < n; i++) {
    const la = luminance([a.rgb[i * 3]!, a.rgb[i * 3 + 1]!, a.rgb[i * 3 + 2]!]);
    const lb = luminance([reference.rgb[i * 3]!, reference.rgb[i * 3 + 1]!, reference.rgb[i * 3 + 2]!]);
    const t = Math.min(Math.abs(la - lb) / (Math.abs(lb) + REL_MSE_EPSILON) / fullScale, 1) * 3;
    out[i * 4] = Math.round(255 * Math.min(t, 1));
    out[i * 4 + 1] = Math.round(255 * Math.min(Math.max(t - 1, 0), 1));
    out[i * 4 + 2] = Math.round(255 * Math.min(Math.max(t - 2, 0), 1));
    out[i * 4 + 3] = 255;
  }
  return out;
}
