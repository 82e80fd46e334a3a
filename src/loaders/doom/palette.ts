/**
 * PLAYPAL (https://doomwiki.org/wiki/PLAYPAL): 14 palettes of 256 RGB triples; the first is the
 * normal one, the others are the damage/pickup/radiation-suit tints, which a renderer of still maps
 * never needs. The values are display values, what the game wrote straight to the VGA DAC, so they
 * are kept as sRGB-encoded 8-bit in textures: the GPU decodes sRGB to linear reflectance when it
 * samples them (scene/types.ts, Texture).
 */
import { LanternError } from '../../errors.ts';
import type { WadStack } from './wad.ts';

export interface Palette {
  /** 256 RGB triples, 768 bytes. */
  readonly rgb: Uint8Array;
  /**
   * The same colours as opaque RGBA packed in 32-bit words in the platform's byte order, so that
   * `new Uint32Array(rgba.buffer)[i] = packed[index]` writes bytes R, G, B, 255: one store per pixel
   * when decoding pictures.
   */
  readonly packed: Uint32Array;
}

const PALETTE_BYTES = 768;

export function readPalette(stack: WadStack): Palette {
  const bytes = stack.lump('PLAYPAL');
  if (!bytes) {
    throw new LanternError(`${stack.describe()}: no PLAYPAL lump (the colour palette)`, 'load the IWAD first, then any PWADs: iwad.wad+pwad.wad');
  }
  if (bytes.length < PALETTE_BYTES) {
    throw new LanternError(`${stack.describe()}: the PLAYPAL lump has ${bytes.length} bytes, fewer than one 768-byte palette`);
  }
  return paletteFromRgb(bytes.slice(0, PALETTE_BYTES));
}

export function paletteFromRgb(rgb: Uint8Array): Palette {
  const packed = new Uint32Array(256);
  const bytes = new Uint8Array(packed.buffer);
  for (let i = 0; i < 256; i++) {
    bytes[i * 4] = rgb[i * 3]!;
    bytes[i * 4 + 1] = rgb[i * 3 + 1]!;
    bytes[i * 4 + 2] = rgb[i * 3 + 2]!;
    bytes[i * 4 + 3] = 255;
  }
  return { rgb, packed };
}
