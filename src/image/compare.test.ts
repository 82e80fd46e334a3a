import { describe, expect, it } from 'vitest';
import { compareImages, displayLuminance, errorHeatmap, ssim, type LinearRgbImage } from './compare.ts';

const image = (width: number, height: number, f: (i: number) => number): LinearRgbImage => ({ width, height, rgb: Float32Array.from({ length: width * height * 3 }, (_, i) => f(i)) });

describe('image comparison', () => {
  it('computes RMSE and relative MSE as written out by hand', () => {
    // Two pixels: reference (1, 1, 1) and (0, 0, 0); the image is 0.5 above it everywhere.
    const ref = image(2, 1, (i) => (i < 3 ? 1 : 0));
    const a = image(2, 1, (i) => (i < 3 ? 1.5 : 0.5));
    const d = compareImages(a, ref);
    expect(d.rmse).toBeCloseTo(0.5, 6);
    // (0.25 / 1.01 · 3 + 0.25 / 0.01 · 3) / 6
    expect(d.relMse).toBeCloseTo((0.25 / 1.01 + 0.25 / 0.01) / 2, 5);
  });

  it('gives SSIM 1 for identical images and less for noise, with the textbook value for a constant offset', () => {
    const ref = image(16, 16, (i) => ((i / 3) % 16) / 16);
    expect(compareImages(ref, ref)).toEqual({ rmse: 0, relMse: 0, ssim: 1 });
    const noisy = image(16, 16, (i) => ref.rgb[i]! * (1 + 0.5 * Math.sin(i * 12.9898)));
    expect(compareImages(noisy, ref).ssim).toBeLessThan(0.95);
    // Two constant images μx, μy: SSIM = (2μxμy + C1) / (μx² + μy² + C1).
    const x = new Float32Array(64).fill(0.5), y = new Float32Array(64).fill(0.25);
    expect(ssim(x, y, 8, 8)).toBeCloseTo((2 * 0.5 * 0.25 + 1e-4) / (0.25 + 0.0625 + 1e-4), 6);
  });

  it('maps luminance to display range and colours the heat map by relative error', () => {
    const l = displayLuminance(image(1, 1, () => 1));
    expect(l[0]).toBeCloseTo(1.055 * 0.5 ** (1 / 2.4) - 0.055, 6);
    const ref = image(3, 1, () => 1);
    const a = image(3, 1, (i) => [1, 1.1, 3][Math.floor(i / 3)]!);
    const heat = errorHeatmap(a, ref);
    expect([...heat.slice(0, 4)]).toEqual([0, 0, 0, 255]);
    expect(heat[4]).toBeGreaterThan(0); // 10 %: dark red
    expect(heat[5]).toBe(0);
    expect([...heat.slice(8, 12)]).toEqual([255, 255, 255, 255]); // 200 %: white
  });

  it('SSIM a few rows at a time equals the whole-image blur, bit for bit, at any size', () => {
    // The whole-image form it replaced: five blurred images, rows then columns, clipped windows.
    const reference = (x: Float32Array, y: Float32Array, width: number, height: number) => {
      const kernel = Array.from({ length: 11 }, (_, i) => Math.exp(-((i - 5) ** 2) / (2 * 1.5 ** 2)));
      const pass = (src: (i: number) => number, along: 'row' | 'column') => {
        const out = new Float64Array(width * height);
        const [n, stride] = along === 'row' ? [width, 1] : [height, width];
        for (let i = 0; i < width * height; i++) {
          const at = along === 'row' ? i % width : Math.floor(i / width);
          let s = 0, w = 0;
          for (let k = Math.max(-5, -at); k <= Math.min(5, n - 1 - at); k++) (s += kernel[k + 5]! * src(i + k * stride)), (w += kernel[k + 5]!);
          out[i] = s / w;
        }
        return out;
      };
      const blur = (f: (i: number) => number) => { const rows = pass(f, 'row'); return pass((i) => rows[i]!, 'column'); };
      const mx = blur((i) => x[i]!), my = blur((i) => y[i]!), xx = blur((i) => x[i]! * x[i]!), yy = blur((i) => y[i]! * y[i]!), xy = blur((i) => x[i]! * y[i]!);
      let sum = 0;
      for (let i = 0; i < width * height; i++) {
        const vx = xx[i]! - mx[i]! ** 2, vy = yy[i]! - my[i]! ** 2, cxy = xy[i]! - mx[i]! * my[i]!;
        sum += ((2 * mx[i]! * my[i]! + 1e-4) * (2 * cxy + 9e-4)) / ((mx[i]! ** 2 + my[i]! ** 2 + 1e-4) * (vx + vy + 9e-4));
      }
      return sum / (width * height);
    };
    let seed = 3;
    const random = () => ((seed = (Math.imul(seed, 1103515245) + 12345) >>> 0) / 2 ** 32);
    for (const [w, h] of [[1, 1], [3, 2], [11, 11], [12, 30], [40, 7], [64, 64]] as const) {
      const x = Float32Array.from({ length: w * h }, random), y = Float32Array.from(x, (v) => v * (0.8 + 0.4 * random()));
      expect(ssim(x, y, w, h)).toBe(reference(x, y, w, h));
      const a = image(w, h, () => 4 * random()), b = image(w, h, () => 4 * random());
      expect(compareImages(a, b).ssim).toBe(reference(displayLuminance(a), displayLuminance(b), w, h));
    }
  });

  it('refuses images of different sizes', () => {
    expect(() => compareImages(image(2, 1, () => 0), image(1, 2, () => 0))).toThrow(/differ in size/);
  });
});
