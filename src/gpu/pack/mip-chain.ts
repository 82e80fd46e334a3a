/**
 * Mip chains for filtered textures, laid out in one image so that the atlas packs them as one
 * rectangle: level 0 at the left, levels 1, 2, … stacked top-down in a column to its right (the
 * classic mip layout). Each level halves the previous one (rounding down, at least one texel) with a
 * 2×2 box filter in linear light for sRGB colour (averaging encoded values darkens), and directly for
 * data. shaders/scene/materials.wgsl finds level k at x = w, y = Σ_{j=1}^{k-1} h_j, as here.
 */
import type { Texture } from '../../scene/types.ts';

/** Levels of a w × h texture down to 1 × 1. */
export function mipLevelCount(width: number, height: number): number {
  return Math.floor(Math.log2(Math.max(width, height))) + 1;
}

export const mipSize = (size: number, level: number): number => Math.max(1, size >> level);

/** The size of the image holding every level. */
export function mipChainSize(width: number, height: number): { width: number; height: number } {
  const levels = mipLevelCount(width, height);
  let column = 0;
  for (let k = 1; k < levels; k++) column += mipSize(height, k);
  return { width: levels > 1 ? width + mipSize(width, 1) : width, height: Math.max(height, column) };
}

const SRGB_TO_LINEAR = Float32Array.from({ length: 256 }, (_, c) => {
  const v = c / 255;
  return v <= 0.04045 ? v / 12.92 : ((v + 0.055) / 1.055) ** 2.4;
});

function linearToSrgbByte(v: number): number {
  const c = v <= 0.0031308 ? v * 12.92 : 1.055 * v ** (1 / 2.4) - 0.055;
  return Math.max(0, Math.min(255, Math.round(c * 255)));
}

/** Level k+1 of `src` (w × h RGBA8), box-filtered. */
function halve(src: Uint8Array, w: number, h: number, srgb: boolean): { data: Uint8Array; width: number; height: number } {
  const nw = Math.max(1, w >> 1), nh = Math.max(1, h >> 1);
  const out = new Uint8Array(nw * nh * 4);
  for (let y = 0; y < nh; y++) {
    for (let x = 0; x < nw; x++) {
      const xs = [Math.min(2 * x, w - 1), Math.min(2 * x + 1, w - 1)], ys = [Math.min(2 * y, h - 1), Math.min(2 * y + 1, h - 1)];
      for (let c = 0; c < 4; c++) {
        let sum = 0;
        for (const sy of ys) for (const sx of xs) {
          const v = src[(sy * w + sx) * 4 + c]!;
          sum += srgb && c < 3 ? SRGB_TO_LINEAR[v]! : v;
        }
        out[(y * nw + x) * 4 + c] = srgb && c < 3 ? linearToSrgbByte(sum / 4) : Math.round(sum / 4);
      }
    }
  }
  return { data: out, width: nw, height: nh };
}

/** The texture with its whole mip chain in one image (see the layout above). */
export function withMipChain(t: Texture): Texture {
  const levels = mipLevelCount(t.width, t.height);
  if (levels === 1) return t;
  const size = mipChainSize(t.width, t.height);
  const rgba = new Uint8Array(size.width * size.height * 4);
  const blit = (data: Uint8Array, w: number, h: number, x0: number, y0: number) => {
    for (let row = 0; row < h; row++) rgba.set(data.subarray(row * w * 4, (row + 1) * w * 4), ((y0 + row) * size.width + x0) * 4);
  };
  blit(t.rgba, t.width, t.height, 0, 0);
  const srgb = (t.encoding ?? 'srgb') === 'srgb';
  let level = { data: t.rgba, width: t.width, height: t.height };
  let y = 0;
  for (let k = 1; k < levels; k++) {
    level = halve(level.data, level.width, level.height, srgb);
    blit(level.data, level.width, level.height, t.width, y);
    y += level.height;
  }
  return { ...t, width: size.width, height: size.height, rgba };
}

/** A texture halved until its mip chain fits in a square of `side` (for textures larger than an atlas page allows). */
export function fitForMips(t: Texture, side: number): Texture {
  let out = t;
  const srgb = (t.encoding ?? 'srgb') === 'srgb';
  while (mipChainSize(out.width, out.height).width > side || mipChainSize(out.width, out.height).height > side) {
    const h = halve(out.rgba, out.width, out.height, srgb);
    out = { ...out, width: h.width, height: h.height, rgba: h.data };
  }
  return out;
}
