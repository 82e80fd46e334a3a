import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../../expect-lantern-error.ts';
import { builtinScene } from '../../loaders/builtin/index.ts';
import { prepareScene } from '../../renderer/prepare.ts';
import { SHADER_MODULES } from '../../shaders/index.ts';
import { sceneLayouts, type PackedScene } from './scene-pack.ts';
import { packSceneTextures, RECORD_TEXTURES, recordTextureSize, sceneTextureRowShift, texelCoord, texelsPerRecord, type SceneTexture } from './scene-textures.ts';

/** Record i of a record texture, read back texel by texel at the coordinates the WGSL computes. */
function readRecord(t: SceneTexture, rowShift: number, perRecord: number, i: number, stride: number): Uint8Array {
  const out = new Uint8Array(perRecord * 16);
  for (let j = 0; j < perRecord; j++) {
    const { x, y } = texelCoord(i * perRecord + j, rowShift);
    expect(x).toBeLessThan(t.width);
    expect(y).toBeLessThan(t.height);
    out.set(t.data.subarray((y * t.width + x) * 16, (y * t.width + x + 1) * 16), j * 16);
  }
  expect([...out.subarray(stride)].every((b) => b === 0)).toBe(true);
  return out.subarray(0, stride);
}

function expectRoundTrip(packed: PackedScene, limit: number, rowShift?: number): number {
  const st = packSceneTextures(packed, { maxTextureDimension2D: limit, ...(rowShift === undefined ? {} : { rowShift }) });
  if (rowShift !== undefined) expect(st.rowShift).toBe(rowShift);
  const layouts = sceneLayouts();
  let checked = 0;
  for (const r of RECORD_TEXTURES) {
    const t = st.textures.find((x) => x.name === r.name)!;
    expect(t.format).toBe('rgba32uint');
    expect(Math.max(t.width, t.height)).toBeLessThanOrEqual(limit);
    const bytes = new Uint8Array(packed[r.name]);
    const perRecord = st.texelsPerRecord[r.name];
    const s = layouts[r.layout].stride;
    expect(perRecord).toBe(Math.ceil(s / 16));
    for (let i = 0; i < bytes.byteLength / s; i++) {
      expect(readRecord(t, st.rowShift, perRecord, i, s)).toEqual(bytes.subarray(i * s, (i + 1) * s));
      checked++;
    }
  }
  return checked;
}

describe('scene textures', () => {
  it('declare the texels per record the WGSL decoder assumes', () => {
    const wgsl = SHADER_MODULES.get('scene/bindings-textures')!;
    const st = packSceneTextures(prepareScene(builtinScene('cornell')).packed);
    const constants: Record<string, string> = { bvh_nodes: 'BVH_NODE_TEXELS', triangles_hot: 'TRIANGLE_HOT_TEXELS', triangles_shading: 'TRIANGLE_SHADING_TEXELS', materials: 'MATERIAL_TEXELS', light_slots: 'LIGHT_SLOT_TEXELS', texture_refs: 'TEXTURE_REF_TEXELS' };
    for (const r of RECORD_TEXTURES) {
      const m = new RegExp(`const ${constants[r.name]}: u32 = (\\d+)u;`).exec(wgsl);
      expect(Number(m?.[1]), r.name).toBe(st.texelsPerRecord[r.name]);
      expect(wgsl).toContain(`@group(0) @binding(${r.binding}) var ${r.name}: texture_2d<u32>;`);
    }
    expect(st.rowShift).toBe(11);
    expect(texelsPerRecord(20)).toBe(2);
    expect(texelsPerRecord(32)).toBe(2);
  });

  it('hold every record at its index (Cornell box, one row and rows of 16)', () => {
    const packed = prepareScene(builtinScene('cornell')).packed;
    expect(expectRoundTrip(packed, 2048)).toBeGreaterThan(30);
    expect(expectRoundTrip(packed, 2048, 4)).toBeGreaterThan(30);
  });

  it('hold every record at its index (the dungeon: moving instances, textures, rows of 2048)', () => {
    const packed = prepareScene(builtinScene('dungeon')).packed;
    const st = packSceneTextures(packed);
    expect(st.textures.find((t) => t.name === 'bvh_nodes')!.height).toBeGreaterThan(1);
    expect(expectRoundTrip(packed, 2048)).toBeGreaterThan(1000);
  });

  it('list every texture of group 0 once, at its binding', () => {
    const st = packSceneTextures(prepareScene(builtinScene('materials')).packed);
    expect(st.textures.map((t) => t.binding).sort((a, b) => a - b)).toEqual([1, 2, 3, 4, 5, 6, 7, 9, 10, 12, 13, 15, 16]);
    for (const t of st.textures) {
      const bytes = t.format === 'rgba32uint' ? 16 : 4;
      expect(t.data.byteLength, t.name).toBe(t.width * t.height * t.depthOrLayers * bytes);
    }
    const shared = SHADER_MODULES.get('scene/bindings-shared')!;
    for (const t of st.textures.filter((x) => x.binding > 6)) expect(shared).toContain(`@group(0) @binding(${t.binding}) var ${t.name}: texture_2d${t.array ? '_array' : ''}<`);
  });

  it('choose 2048-wide rows, wider only where the device allows and the scene needs them', () => {
    expect(sceneTextureRowShift([10], 2048)).toBe(11);
    expect(sceneTextureRowShift([2048 * 2048], 2048)).toBe(11);
    expect(sceneTextureRowShift([2048 * 2048 + 1], 2048)).toBeUndefined();
    expect(sceneTextureRowShift([2048 * 2048 + 1], 8192)).toBe(11);
    expect(sceneTextureRowShift([4096 * 3000], 4096)).toBe(12);
    expect(sceneTextureRowShift([4096 * 4097], 4096)).toBeUndefined();
    expect(sceneTextureRowShift([100], 64)).toBe(6);
    expect(recordTextureSize(5, 11)).toEqual({ width: 5, height: 1 });
    expect(recordTextureSize(0, 11)).toEqual({ width: 1, height: 1 });
    expect(recordTextureSize(4097, 11)).toEqual({ width: 2048, height: 3 });
  });

  it('refuse a scene that does not fit, with the numbers', () => {
    const packed = prepareScene(builtinScene('dungeon')).packed;
    expectLanternError(() => packSceneTextures(packed, { maxTextureDimension2D: 64, label: 'dungeon' }), /^(bvh_nodes|triangles_\w+) of scene 'dungeon' needs [\d,]+ texels, [\d,]+ rows of 64: more than the 64 × 64 texels a texture may have here$/);
    expectLanternError(() => packSceneTextures(prepareScene(builtinScene('cornell')).packed, { maxTextureDimension2D: 512 }), /^bsdf_tables is 1,024 × \d+ texels, more than the 512 a side a texture may have here$/);
  });
});
