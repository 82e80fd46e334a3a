/**
 * Packs a scene's textures into the pages of one 2D array texture (shelf packing, tallest first).
 * Shaders address a texture by its rectangle and wrap coordinates inside it themselves, which is why
 * no border is needed: lookups are nearest-texel textureLoad calls that never leave the rectangle.
 */
import { LanternError } from '../../errors.ts';
import type { Texture } from '../../scene/types.ts';

export interface AtlasRect {
  readonly page: number;
  readonly x: number;
  readonly y: number;
  readonly width: number;
  readonly height: number;
}

export interface TextureAtlas {
  /** Side of every (square) page in texels. */
  readonly pageSize: number;
  /** RGBA8 texels of each page, row-major (sRGB-encoded colour, as the textures came). */
  readonly pages: Uint8Array[];
  /** Where each input texture went, in input order. */
  readonly rects: AtlasRect[];
}

/** Pages never exceed this side (64 MiB of RGBA8): more layers beat one giant page. */
export const MAX_PAGE_SIDE = 4096;

/** Shelf layout of textures on pages of the given side, without copying texels. */
function layout(textures: readonly Texture[], side: number): { rects: AtlasRect[]; pages: number } {
  const order = textures.map((_, i) => i).sort((a, b) => textures[b]!.height - textures[a]!.height || textures[b]!.width - textures[a]!.width);
  const rects: AtlasRect[] = new Array(textures.length);
  let page = 0, x = 0, y = 0, shelf = 0;
  for (const i of order) {
    const t = textures[i]!;
    if (x + t.width > side) {
      x = 0;
      y += shelf;
      shelf = 0;
    }
    if (y + t.height > side) {
      page++;
      x = 0;
      y = 0;
      shelf = 0;
    }
    rects[i] = { page, x, y, width: t.width, height: t.height };
    x += t.width;
    shelf = Math.max(shelf, t.height);
  }
  return { rects, pages: textures.length === 0 ? 1 : page + 1 };
}

/**
 * The atlas with the smallest page (a power of two) that holds every texture on one page, or pages
 * of the largest allowed side when one page cannot. `maxSide` is the device's maxTextureDimension2D.
 */
export function packTextureAtlas(textures: readonly Texture[], maxSide: number): TextureAtlas {
  for (const t of textures) {
    if (!(Number.isInteger(t.width) && Number.isInteger(t.height) && t.width > 0 && t.height > 0) || t.rgba.length !== t.width * t.height * 4) {
      throw new LanternError(`texture '${t.name}' has ${t.rgba.length} bytes for ${t.width}×${t.height} RGBA texels`);
    }
  }
  const limit = Math.min(maxSide, MAX_PAGE_SIDE);
  const big = textures.find((t) => t.width > limit || t.height > limit);
  if (big) throw new LanternError(`texture '${big.name}' (${big.width}×${big.height}) is larger than the ${limit}×${limit} texels an atlas page may hold`);
  if (textures.length === 0) return { pageSize: 1, pages: [new Uint8Array(4)], rects: [] };

  // Start at the smallest power of two that holds the largest side (a texture wider than its page
  // would otherwise be placed on a page of one, overflowing it), then grow until one page holds all.
  let side = 16;
  const largest = textures.reduce((m, t) => Math.max(m, t.width, t.height), 0);
  while (side < largest) side *= 2;
  let placed = layout(textures, side);
  while (placed.pages > 1 && side < limit) {
    side *= 2;
    placed = layout(textures, side);
  }
  const pages = Array.from({ length: placed.pages }, () => new Uint8Array(side * side * 4));
  textures.forEach((t, i) => {
    const r = placed.rects[i]!;
    const dst = pages[r.page]!;
    for (let row = 0; row < t.height; row++) {
      dst.set(t.rgba.subarray(row * t.width * 4, (row + 1) * t.width * 4), ((r.y + row) * side + r.x) * 4);
    }
  });
  return { pageSize: side, pages, rects: placed.rects };
}

/** Mean colour of a texture, decoded from sRGB to linear, over opaque texels (alpha ≥ 0.5). */
export function meanLinearColor(t: Texture): [number, number, number] {
  let r = 0, g = 0, b = 0, n = 0;
  for (let i = 0; i < t.width * t.height; i++) {
    if (t.rgba[i * 4 + 3]! < 128) continue;
    r += SRGB_TO_LINEAR[t.rgba[i * 4]!]!;
    g += SRGB_TO_LINEAR[t.rgba[i * 4 + 1]!]!;
    b += SRGB_TO_LINEAR[t.rgba[i * 4 + 2]!]!;
    n++;
  }
  return n === 0 ? [0, 0, 0] : [r / n, g / n, b / n];
}

/** The sRGB electro-optical transfer function (IEC 61966-2-1) for each 8-bit code. */
const SRGB_TO_LINEAR = Float64Array.from({ length: 256 }, (_, c) => {
  const v = c / 255;
  return v <= 0.04045 ? v / 12.92 : ((v + 0.055) / 1.055) ** 2.4;
});
