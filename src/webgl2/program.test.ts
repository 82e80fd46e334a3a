import { describe, expect, it } from 'vitest';
import { reflectLinked, structLayout } from '../gpu/wgsl/reflect.ts';
import { blockLayoutProblems } from './program.ts';
import { checkTexturesFit, textureMisfit } from './textures.ts';

const WGSL = `
struct Inner { a: vec3f, b: f32 }
struct P { v: vec3f, s: f32, m: mat3x3f, n: u32, inner: Inner, sampler: u32, p0: u32 }
@group(0) @binding(0) var<uniform> p: P;
@fragment fn f() -> @location(0) vec4f { return vec4f(p.v, p.s); }
`;
const layout = structLayout(reflectLinked({ entry: 't', code: WGSL, modules: ['t'], lineMap: [] }).defs, 'P');
const B = 'P_block_0Fragment', I = '_group_0_binding_0_fs';
const member = (path: string, offset: number) => ({ name: `${B}.${I}.${path}`, offset });

describe('a std140 block against its WGSL struct', () => {
  it('agrees where the driver reports WGSL offsets (a vec3 and a scalar in one 16 bytes, mat3 columns 16 apart, a nested struct, names naga renamed)', () => {
    expect(blockLayoutProblems([member('v', 0), member('s', 12), member('m', 16), member('n', 64), member('inner.a', 80), member('inner.b', 92), member('sampler_', 96), member('p0_', 100)], B, I, layout)).toEqual([]);
  });

  it('names a member at another offset, one outside its field, and one WGSL lacks', () => {
    expect(blockLayoutProblems([member('s', 16), member('inner.b', 40), member('extra', 96), member('sampler_', 104)], B, I, layout)).toEqual([
      's at byte 16, WGSL has 12',
      'inner.b at byte 40, outside WGSL\'s inner (80..96)',
      'extra is no field of the WGSL struct',
      'sampler_ at byte 104, WGSL has 96',
    ]);
  });
});

describe('scene textures against WebGL2 limits', () => {
  const limits = { maxTextureSize: 2048, maxArrayTextureLayers: 256, maxTextureImageUnits: 16, maxUniformBlockSize: 16384, maxFragmentUniformBlocks: 12 };
  it('lets a texture at the limits through and refuses one over them, with the numbers', () => {
    expect(textureMisfit({ name: 'bvh_nodes', width: 2048, height: 2048, depthOrLayers: 1 }, limits)).toBeUndefined();
    expect(textureMisfit({ name: 'bvh_nodes', width: 2048, height: 2049, depthOrLayers: 1 }, limits)).toBe('bvh_nodes is 2048 × 2049 texels, this GPU\'s WebGL2 allows 2048 × 2048');
    expect(() => checkTexturesFit([{ name: 'atlas', group: 0, binding: 8, format: 'rgba8unorm', width: 1024, height: 1024, depthOrLayers: 300, data: new Uint8Array(0) }], limits, 'E1M1')).toThrow(
      "the scene 'E1M1' does not fit WebGL2's texture limits: atlas has 300 layers, this GPU's WebGL2 allows 256",
    );
  });
});
