/**
 * Packing animated materials (world/material-animation.ts): every texture a cycle can show is in
 * the atlas with a texture reference of the material's own from the start, so a texture swap
 * rewrites one record to point at the new texture's atlas rectangle, and a uv offset rewrites the
 * material's own references alone. Checked on the packed bytes.
 */
import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../../expect-lantern-error.ts';
import { IDENTITY } from '../../math/mat4.ts';
import { editMaterials, LIGHT_BUFFERS, prepareScene, type PreparedScene } from '../../renderer/prepare.ts';
import { diffuse, type Scene, type Texture } from '../../scene/types.ts';
import { sceneLayouts } from './scene-pack.ts';

const solid = (name: string, r: number, g: number, b: number): Texture => ({ name, width: 4, height: 2, rgba: new Uint8Array(Array.from({ length: 8 }, () => [r, g, b, 255]).flat()), filter: 'nearest' });

/** Two triangles: material 0 (a cycle over textures 0–2, emitting through them), material 1 (texture 0, still); material 2 scrolls texture 3. */
function scene(): Scene {
  return {
    name: 'animated',
    meshes: [
      {
        name: 'quad',
        positions: new Float32Array([0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0]),
        indices: new Uint32Array([0, 1, 2, 0, 2, 3, 0, 1, 2]),
        uvs: new Float32Array([0, 0, 1, 0, 1, 1, 0, 1]),
        materialIds: new Uint32Array([0, 1, 2]),
      },
    ],
    instances: [{ id: 0, mesh: 0, worldFromObject: IDENTITY }],
    materials: [
      diffuse('cycling', [1, 1, 1], [3, 3, 3], { albedoTexture: { texture: 0 }, emissionTexture: { texture: 0 } }),
      diffuse('still', [1, 1, 1], [0, 0, 0], { albedoTexture: { texture: 0 } }),
      diffuse('scrolling', [1, 1, 1], [0, 0, 0], { albedoTexture: { texture: 3 } }),
    ],
    textures: [solid('red', 200, 10, 10), solid('green', 10, 200, 10), solid('blue', 10, 10, 200), solid('grey', 90, 90, 90)],
    camera: { position: [0.5, 0.5, 3], forward: [0, 0, -1], up: [0, 1, 0], vfovDegrees: 40 },
    dynamics: {
      materialAnimations: {
        cycles: [{ material: 0, frames: [0, 1, 2], emissionFrames: [0, 1, 2], secondsPerFrame: 8 / 35 }],
        scrolls: [{ material: 2, velocity: [35 / 4, 0], stepSeconds: 1 / 35 }],
      },
    },
  };
}

const layouts = sceneLayouts();
const u32 = (buf: ArrayBuffer, at: number) => new DataView(buf).getUint32(at, true);
const f32 = (buf: ArrayBuffer, at: number) => new DataView(buf).getFloat32(at, true);
const fieldAt = (layout: typeof layouts.material, i: number, field: string) => i * layout.stride + layout.fields.get(field)!.offset;

/** The texture reference a material's field points at, read from the packed bytes. */
function refOf(p: PreparedScene, material: number, field = 'base_color_texture') {
  const r = u32(p.packed.materials, fieldAt(layouts.material, material, field));
  const at = (f: string) => fieldAt(layouts.textureRef, r, f);
  const refs = p.packed.texture_refs;
  return {
    index: r,
    origin: [u32(refs, at('origin')), u32(refs, at('origin') + 4)] as const,
    size: [u32(refs, at('size')), u32(refs, at('size') + 4)] as const,
    page: u32(refs, at('page')),
    transformU: [0, 1, 2].map((k) => f32(refs, at('transform_u') + 4 * k)),
  };
}

/** The texels of the atlas rectangle a reference names, as RGBA bytes. */
function texelsOf(p: PreparedScene, ref: ReturnType<typeof refOf>): number[] {
  const atlas = p.packed.atlas;
  const page = atlas.pages[ref.page]!;
  const out: number[] = [];
  for (let y = 0; y < ref.size[1]; y++) for (let x = 0; x < ref.size[0]; x++) {
    const at = ((ref.origin[1] + y) * atlas.pageSize + ref.origin[0] + x) * 4;
    out.push(...page.subarray(at, at + 4));
  }
  return out;
}

describe('animated materials, packed', () => {
  it('a texture swap points the record at the new texture\'s atlas rectangle and touches nothing else', () => {
    const s = scene();
    const prepared = prepareScene(s);
    expect(texelsOf(prepared, refOf(prepared, 0))).toEqual(Array.from(s.textures![0]!.rgba));
    for (const frame of [1, 2, 0]) {
      const { prepared: live, lightsChanged, textureRefsChanged } = editMaterials(prepared, new Map([[0, { albedoTexture: frame, emissionTexture: frame }]]));
      expect(texelsOf(live, refOf(live, 0))).toEqual(Array.from(s.textures![frame]!.rgba));
      expect(texelsOf(live, refOf(live, 0, 'emission_texture'))).toEqual(Array.from(s.textures![frame]!.rgba));
      // The still material sharing texture 0 keeps its reference; nothing but the record changed.
      expect(refOf(live, 1)).toEqual(refOf(prepared, 1));
      expect([lightsChanged, textureRefsChanged]).toEqual([false, false]);
      expect(live.packed.texture_refs).toBe(prepared.packed.texture_refs);
      expect(live.packed.atlas).toBe(prepared.packed.atlas);
      for (const name of LIGHT_BUFFERS) expect(live.packed[name]).toBe(prepared.packed[name]);
    }
  });

  it('a cycle\'s material has references of its own; the still material sharing its first frame does not move with it', () => {
    const prepared = prepareScene(scene());
    expect(refOf(prepared, 0).index).not.toBe(refOf(prepared, 1).index);
    expect(texelsOf(prepared, refOf(prepared, 0))).toEqual(texelsOf(prepared, refOf(prepared, 1)));
  });

  it('a uv offset rewrites the scrolling material\'s own references (texture_refs changes) and no other', () => {
    const prepared = prepareScene(scene());
    const { prepared: live, textureRefsChanged } = editMaterials(prepared, new Map([[2, { uvOffset: [0.25, 0] }]]));
    expect(textureRefsChanged).toBe(true);
    expect(refOf(live, 2).transformU).toEqual([1, 0, 0.25]);
    expect(refOf(prepared, 2).transformU).toEqual([1, 0, 0]);
    const before = new Uint8Array(prepared.packed.texture_refs), after = new Uint8Array(live.packed.texture_refs);
    const changed = new Set<number>();
    for (let i = 0; i < before.length; i++) if (before[i] !== after[i]) changed.add(Math.floor(i / layouts.textureRef.stride));
    expect([...changed]).toEqual([refOf(live, 2).index]);
    // The same offset again changes nothing more.
    expect(editMaterials(live, new Map([[2, { uvOffset: [0.25, 0] }]])).textureRefsChanged).toBe(false);
  });

  it('refuses textures an animation does not list and uv offsets on materials without their own references', () => {
    const prepared = prepareScene(scene());
    expectLanternError(() => editMaterials(prepared, new Map([[0, { albedoTexture: 3 }]])), /shows texture 3 in its base_color_texture, which its animation does not list/);
    expectLanternError(() => editMaterials(prepared, new Map([[1, { albedoTexture: 1 }]])), /only animated materials/);
    expectLanternError(() => editMaterials(prepared, new Map([[1, { uvOffset: [0.5, 0] }]])), /only animated materials/);
  });
});
