import { describe, expect, it } from 'vitest';
import type { Texture } from '../../scene/types.ts';
import { mipChainSize, mipLevelCount, withMipChain } from './mip-chain.ts';

function texture(width: number, height: number, texel: (x: number, y: number) => number[], encoding: 'srgb' | 'linear'): Texture {
  const rgba = new Uint8Array(width * height * 4);
  for (let y = 0; y < height; y++) for (let x = 0; x < width; x++) rgba.set(texel(x, y), (y * width + x) * 4);
  return { name: 't', width, height, rgba, encoding };
}

const at = (t: Texture, x: number, y: number) => Array.from(t.rgba.subarray((y * t.width + x) * 4, (y * t.width + x) * 4 + 4));

describe('mip chains', () => {
  it('lays levels out beside level 0, halving down to one texel', () => {
    expect(mipLevelCount(8, 4)).toBe(4);
    expect(mipChainSize(8, 4)).toEqual({ width: 12, height: 4 }); // levels 4×2, 2×1, 1×1 in a column of height 4
    expect(mipChainSize(16, 1)).toEqual({ width: 24, height: 4 }); // levels of height 1 stack past level 0's height
    expect(mipChainSize(1, 1)).toEqual({ width: 1, height: 1 });
  });

  it('averages colour in linear light and data as stored', () => {
    // A black-and-white checker: its mean is linear 0.5, which sRGB encodes as 188, not 128.
    const checker = (x: number, y: number) => ((x + y) % 2 === 0 ? [255, 255, 255, 255] : [0, 0, 0, 255]);
    const colour = withMipChain(texture(4, 4, checker, 'srgb'));
    expect(colour.width).toBe(6);
    expect(at(colour, 4, 0)).toEqual([188, 188, 188, 255]); // level 1, texel (0, 0)
    expect(at(colour, 4, 2)).toEqual([188, 188, 188, 255]); // level 2 (1×1) below it
    const data = withMipChain(texture(4, 4, checker, 'linear'));
    expect(at(data, 4, 0)).toEqual([128, 128, 128, 255]);
    // Level 0 is untouched.
    expect(at(colour, 1, 0)).toEqual([0, 0, 0, 255]);
  });
});
