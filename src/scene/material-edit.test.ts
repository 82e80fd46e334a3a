import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../expect-lantern-error.ts';
import { applyMaterialEdit, EDITABLE_FIELDS, editableValues, editChangesEmission, materialEditProblem, mergeMaterialEdits } from './material-edit.ts';
import { diffuse, metallicRoughness, type Material } from './types.ts';

const glass: Material = { kind: 'dielectric', name: 'glass', ior: 1.5, roughness: 0, tint: [1, 1, 1], attenuationDistance: Infinity, attenuationColor: [1, 1, 1], emission: [0, 0, 0] };
const lamp: Material = { kind: 'emissive', name: 'lamp', emission: [5, 5, 5] };

describe('material edits', () => {
  it('apply each field to what the kind calls it, and read back the same values', () => {
    const gltf = metallicRoughness('metal', { baseColor: [0.5, 0.5, 0.5], roughness: 0.5, metallic: 1 });
    const samples: [Material, Parameters<typeof applyMaterialEdit>[1]][] = [
      [diffuse('wall', [0.5, 0.5, 0.5]), { color: [0.2, 0.3, 0.4], emission: [1, 0, 0] }],
      [gltf, { color: [0.9, 0.1, 0.1], roughness: 0.2, metallic: 0.3, ior: 1.7, transmission: 0.4, emission: [0, 2, 0] }],
      [glass, { color: [0.8, 0.9, 1], roughness: 0.1, ior: 1.33, emission: [0, 0, 0] }],
      [lamp, { emission: [10, 8, 6] }],
    ];
    for (const [m, edit] of samples) {
      const edited = applyMaterialEdit(m, edit);
      expect(edited.kind).toBe(m.kind);
      expect(editableValues(edited)).toEqual(edit);
      expect(Object.keys(editableValues(m)).sort()).toEqual([...EDITABLE_FIELDS[m.kind]].sort());
    }
    // Untouched fields stay.
    const partial = applyMaterialEdit(gltf, { roughness: 0.9 });
    expect(partial).toEqual({ ...gltf, roughness: 0.9 });
  });

  it('refuse fields a kind lacks and values out of range', () => {
    expectLanternError(() => applyMaterialEdit(lamp, { color: [1, 1, 1] }), /material 'lamp'.*emissive material has no color/);
    expectLanternError(() => applyMaterialEdit(glass, { metallic: 0.5 }), /no metallic/);
    expect(materialEditProblem('metallic-roughness', { roughness: -0.1 })).toMatch(/roughness -0.1 is outside 0–1/);
    expect(materialEditProblem('metallic-roughness', { ior: 10 })).toMatch(/ior 10 is outside/);
    expect(materialEditProblem('metallic-roughness', { ior: 0.99 })).toMatch(/ior/);
    expect(materialEditProblem('diffuse', { color: [1, 1, NaN] })).toMatch(/color/);
    expect(materialEditProblem('diffuse', { emission: [2e6, 0, 0] })).toMatch(/emission/);
    expect(materialEditProblem('dielectric', { ior: 1.0 })).toBeUndefined();
  });

  it('merge later fields over earlier ones and tell emission changes apart', () => {
    expect(mergeMaterialEdits({ color: [1, 0, 0], roughness: 0.5 }, { roughness: 0.2, emission: [1, 1, 1] })).toEqual({ color: [1, 0, 0], roughness: 0.2, emission: [1, 1, 1] });
    expect(editChangesEmission(lamp, { emission: [5, 5, 5] })).toBe(false);
    expect(editChangesEmission(lamp, { emission: [5, 5, 6] })).toBe(true);
    expect(editChangesEmission(lamp, { color: [1, 1, 1] })).toBe(false);
  });

  it('swap an animated material\'s textures and move every texture use\'s uv offset, keeping rotation and scale', () => {
    const wall = diffuse('NUKAGE1', [1, 1, 1], [2, 2, 2], { albedoTexture: { texture: 3 }, emissionTexture: { texture: 4 } });
    const swapped = applyMaterialEdit(wall, { albedoTexture: 5, emissionTexture: 6, uvOffset: [0.25, 0] });
    expect(swapped).toEqual({
      ...wall,
      albedoTexture: { texture: 5, transform: { offset: [0.25, 0], rotation: 0, scale: [1, 1] } },
      emissionTexture: { texture: 6, transform: { offset: [0.25, 0], rotation: 0, scale: [1, 1] } },
    });
    const gltf = metallicRoughness('m', { baseColorTexture: { texture: 1, transform: { offset: [0.1, 0.2], rotation: 0.5, scale: [2, 3] } }, normalTexture: { texture: 2 } });
    const moved = applyMaterialEdit(gltf, { uvOffset: [0.5, 0.75], albedoTexture: 7 });
    expect(moved.kind === 'metallic-roughness' && moved.baseColorTexture).toEqual({ texture: 7, transform: { offset: [0.5, 0.75], rotation: 0.5, scale: [2, 3] } });
    expect(moved.normalTexture).toEqual({ texture: 2, transform: { offset: [0.5, 0.75], rotation: 0, scale: [1, 1] } });
    expect(moved.emissionTexture).toBeUndefined();
    // Animation fields are not panel fields: a material's editable values never show them.
    expect(Object.keys(editableValues(swapped)).sort()).toEqual(['color', 'emission']);
  });

  it('refuse texture swaps a material cannot take and malformed animation fields', () => {
    expectLanternError(() => applyMaterialEdit(diffuse('plain', [1, 1, 1]), { albedoTexture: 2 }), /no colour texture to swap/);
    expectLanternError(() => applyMaterialEdit(diffuse('plain', [1, 1, 1]), { emissionTexture: 2 }), /no emission texture to swap/);
    expectLanternError(() => applyMaterialEdit(lamp, { albedoTexture: 0 }), /emissive material has no colour texture/);
    expect(materialEditProblem('diffuse', { albedoTexture: 1.5 })).toMatch(/albedoTexture must be a texture index/);
    expect(materialEditProblem('diffuse', { uvOffset: [0, Infinity] })).toMatch(/uvOffset must be two finite numbers/);
  });
});
