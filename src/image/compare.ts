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
  const ssimValue = ssimOfRows(a.width, a.height, (y, out) => displayLuminanceRow(a, y, out), (y, out) => displayLuminanceRow(reference, y, out));
  return { rmse: rmse(a.rgb, reference.rgb), relMse: rel / n, ssim: ssimValue };
}

/** Luminance mapped to [0, 1) as a display would show it: Reinhard, then the sRGB transfer curve. */
export function displayLuminance(img: LinearRgbImage): Float32Array {
  const out = new Float32Array(img.width * img.height);
  for (let y = 0; y < img.height; y++) displayLuminanceRow(img, y, out.subarray(y * img.width, (y + 1) * img.width));
  return out;
}

/** Row y of displayLuminance, into `out` (width floats). */
function displayLuminanceRow({ width, rgb }: LinearRgbImage, y: number, out: Float32Array): void {
  for (let x = 0, p = 3 * y * width; x < width; x++, p += 3) {
    // luminance() of math/vec3.ts, inlined: this runs over every pixel of both images.
    const l = Math.max(0.2126 * rgb[p]! + 0.7152 * rgb[p + 1]! + 0.0722 * rgb[p + 2]!, 0);
    const m = l / (1 + l);
    // m^(1/2.4) as exp(log(m) / 2.4): within an ulp of **, and a third of its time over 67 million pixels.
    out[x] = m <= 0.0031308 ? 12.92 * m : 1.055 * Math.exp(Math.log(m) / 2.4) - 0.055;
  }
}

const SSIM_RADIUS = 5;
const SSIM_SIGMA = 1.5;
const C1 = 0.01 ** 2;
const C2 = 0.03 ** 2;

/** Mean SSIM of two single-channel images in [0, 1], Gaussian-windowed (windows clipped at the borders). */
export function ssim(x: Float32Array, y: Float32Array, width: number, height: number): number {
  return ssimOfRows(width, height, (row, out) => out.set(x.subarray(row * width, (row + 1) * width)), (row, out) => out.set(y.subarray(row * width, (row + 1) * width)));
}

/**
 * ssim() over images given a row at a time (`rowX(y, out)` fills `out` with row y). The separable
 * blur of x, y, x², y² and xy runs along each row as it arrives, and down the columns over a ring of
 * the last 2·SSIM_RADIUS + 1 blurred rows, so the memory is a few rows whatever the height: the
 * five blurred images of floats once took 1.3 GB for an 8192×4096 pair (and `lantern diff` over
 * 2 GB and 60 s). Each pixel's sums are taken in the same order as a whole-image blur would.
 */
function ssimOfRows(width: number, height: number, rowX: (y: number, out: Float32Array) => void, rowY: (y: number, out: Float32Array) => void): number {
  const taps = 2 * SSIM_RADIUS + 1;
  const kernel = Float64Array.from({ length: taps }, (_, i) => Math.exp(-((i - SSIM_RADIUS) ** 2) / (2 * SSIM_SIGMA ** 2)));
  // The sum of the kernel's taps inside the image, for a window centred at `at` of `n`.
  const weight = (at: number, n: number) => {
    let w = 0;
    for (let k = Math.max(-SSIM_RADIUS, -at); k <= Math.min(SSIM_RADIUS, n - 1 - at); k++) w += kernel[k + SSIM_RADIUS]!;
    return w;
  };
  const rowWeight = Float64Array.from({ length: width }, (_, x) => weight(x, width));
  // The row-blurred x, y, x², y², xy of the last `taps` rows, five floats a pixel side by side (the
  // column pass then reads one stream a row, not five); row r at ring slot r % taps.
  const ring = new Float64Array(taps * width * 5);
  const xs = new Float32Array(width), ys = new Float32Array(width);
  const blurRow = (row: number) => {
    rowX(row, xs);
    rowY(row, ys);
    const base = (row % taps) * width * 5;
    for (let x = 0; x < width; x++) {
      let sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
      for (let k = Math.max(-SSIM_RADIUS, -x); k <= Math.min(SSIM_RADIUS, width - 1 - x); k++) {
        const w = kernel[k + SSIM_RADIUS]!, a = xs[x + k]!, b = ys[x + k]!;
        sx += w * a;
        sy += w * b;
        sxx += w * (a * a);
        syy += w * (b * b);
        sxy += w * (a * b);
      }
      const w = rowWeight[x]!, at = base + 5 * x;
      ring[at] = sx / w;
      ring[at + 1] = sy / w;
      ring[at + 2] = sxx / w;
      ring[at + 3] = syy / w;
      ring[at + 4] = sxy / w;
    }
  };
  // The column pass for one output row: the ring slots and kernel taps of its window.
  const slots = new Int32Array(taps), weights = new Float64Array(taps);
  let total = 0;
  let blurred = 0;
  for (let row = 0; row < height; row++) {
    const last = Math.min(height - 1, row + SSIM_RADIUS);
    while (blurred <= last) blurRow(blurred++);
    let n = 0;
    for (let k = Math.max(-SSIM_RADIUS, -row); k <= last - row; k++, n++) {
      slots[n] = ((row + k) % taps) * width * 5;
      weights[n] = kernel[k + SSIM_RADIUS]!;
    }
    const w = weight(row, height);
    for (let x = 0; x < width; x++) {
      let sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
      for (let t = 0; t < n; t++) {
        const at = slots[t]! + 5 * x, kw = weights[t]!;
        sx += kw * ring[at]!;
        sy += kw * ring[at + 1]!;
        sxx += kw * ring[at + 2]!;
        syy += kw * ring[at + 3]!;
        sxy += kw * ring[at + 4]!;
      }
      const ux = sx / w, uy = sy / w;
      const vx = sxx / w - ux ** 2, vy = syy / w - uy ** 2, cxy = sxy / w - ux * uy;
      total += ((2 * ux * uy + C1) * (2 * cxy + C2)) / ((ux ** 2 + uy ** 2 + C1) * (vx + vy + C2));
    }
  }
  return total / (width * height);
}

/**
 * A heat map of per-pixel relative error |a − b| / (b + 0.01) in luminance: black (none) through red
 * and yellow to white at `fullScale` (default 1: 100 %) or more. RGBA8, row-major.
 */
export function errorHeatmap(a: LinearRgbImage, reference: LinearRgbImage, fullScale = 1): Uint8Array {
  const n = a.width * a.height;
  const out = new Uint8Array(n * 4);
  for (let i = 0; i < n; i++) {
    // luminance() of math/vec3.ts, inlined (as in displayLuminanceRow).
    const la = 0.2126 * a.rgb[i * 3]! + 0.7152 * a.rgb[i * 3 + 1]! + 0.0722 * a.rgb[i * 3 + 2]!;
    const lb = 0.2126 * reference.rgb[i * 3]! + 0.7152 * reference.rgb[i * 3 + 1]! + 0.0722 * reference.rgb[i * 3 + 2]!;
    const t = Math.min(Math.abs(la - lb) / (Math.abs(lb) + REL_MSE_EPSILON) / fullScale, 1) * 3;
    out[i * 4] = Math.round(255 * Math.min(t, 1));
    out[i * 4 + 1] = Math.round(255 * Math.min(Math.max(t - 1, 0), 1));
    out[i * 4 + 2] = Math.round(255 * Math.min(Math.max(t - 2, 0), 1));
    out[i * 4 + 3] = 255;
  }
  return out;
}
