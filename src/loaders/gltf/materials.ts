/**
 * glTF materials → Lantern's 'metallic-roughness' kind, which was shaped after glTF's model
 * (glTF 2.0 Appendix B plus KHR_materials_ior, _specular, _transmission, _volume, _dispersion), so the mapping is
 * one to one: factors as they are, textures as TextureRefs with their KHR_texture_transform.
 *
 * Left out on purpose: occlusionTexture (a path tracer computes occlusion), thickness textures
 * (Lantern's thickness is a constant; it only switches refraction on), and extensions Lantern's
 * model has no place for (clearcoat, sheen, iridescence, anisotropy...): those are named once in a
 * warning so a user knows why a model looks plainer than in a raster viewer.
 */
import type { Material as GltfMaterial } from '@gltf-transform/core';
import type { Dispersion, EmissiveStrength, IOR, Specular, Transmission, Volume } from '@gltf-transform/extensions';
import { metallicRoughness, type MetallicRoughnessMaterial, type NormalTextureRef } from '../../scene/types.ts';
import type { TextureTable } from './textures.ts';
import type { Warnings } from './warnings.ts';

/** Extensions this file reads; any other material extension is reported as ignored. */
const HANDLED = new Set([
  'KHR_materials_dispersion',
  'KHR_materials_emissive_strength',
  'KHR_materials_ior',
  'KHR_materials_specular',
  'KHR_materials_transmission',
  'KHR_materials_volume',
]);

/**
 * glTF 2.0 §3.9.6: a primitive without a material uses "a material with no properties specified",
 * i.e. every default: white base colour, metallic 1, roughness 1, single-sided, opaque.
 */
export function defaultMaterial(): MetallicRoughnessMaterial {
  return metallicRoughness('glTF default material', { doubleSided: false });
}

export function convertMaterial(m: GltfMaterial, index: number, textures: TextureTable, warnings: Warnings): MetallicRoughnessMaterial {
  const name = m.getName() || `material ${index}`;
  const [r, g, b, a] = m.getBaseColorFactor();
  const strength = m.getExtension<EmissiveStrength>('KHR_materials_emissive_strength')?.getEmissiveStrength() ?? 1;
  const emissive = m.getEmissiveFactor();
  const ior = m.getExtension<IOR>('KHR_materials_ior');
  const specular = m.getExtension<Specular>('KHR_materials_specular');
  const transmission = m.getExtension<Transmission>('KHR_materials_transmission');
  const volume = m.getExtension<Volume>('KHR_materials_volume');
  // KHR_materials_dispersion stores 20/V_d (0: none); it acts on volumetric refraction only.
  const dispersionFactor = m.getExtension<Dispersion>('KHR_materials_dispersion')?.getDispersion() ?? 0;

  for (const ext of m.listExtensions()) {
    const extName = ext.extensionName;
    if (!HANDLED.has(extName)) warnings.add(`${extName} is not supported: materials that use it render without it`);
  }

  const normalRef = textures.ref(m.getNormalTexture(), m.getNormalTextureInfo(), 'normal', name);
  const normalTexture: NormalTextureRef | undefined = normalRef && { ...normalRef, scale: m.getNormalScale() };

  const alphaMode = m.getAlphaMode();
  const optional = {
    baseColorTexture: textures.ref(m.getBaseColorTexture(), m.getBaseColorTextureInfo(), 'color', name),
    metallicRoughnessTexture: textures.ref(m.getMetallicRoughnessTexture(), m.getMetallicRoughnessTextureInfo(), 'data', name),
    emissionTexture: textures.ref(m.getEmissiveTexture(), m.getEmissiveTextureInfo(), 'color', name),
    normalTexture,
    specularTexture: specular ? textures.ref(specular.getSpecularTexture(), specular.getSpecularTextureInfo(), 'data', name) : undefined,
    specularColorTexture: specular ? textures.ref(specular.getSpecularColorTexture(), specular.getSpecularColorTextureInfo(), 'color', name) : undefined,
    transmissionTexture: transmission ? textures.ref(transmission.getTransmissionTexture(), transmission.getTransmissionTextureInfo(), 'data', name) : undefined,
    dispersion: dispersionFactor > 0 ? { kind: 'abbe' as const, abbeNumber: 20 / dispersionFactor } : undefined,
  };
  const material: MetallicRoughnessMaterial = {
    kind: 'metallic-roughness',
    name,
    baseColor: [r, g, b],
    opacity: a,
    metallic: m.getMetallicFactor(),
    roughness: m.getRoughnessFactor(),
    emission: [emissive[0] * strength, emissive[1] * strength, emissive[2] * strength],
    ior: ior?.getIOR() ?? 1.5,
    specular: specular?.getSpecularFactor() ?? 1,
    specularColor: specular ? [...specular.getSpecularColorFactor()] : [1, 1, 1],
    transmission: transmission?.getTransmissionFactor() ?? 0,
    thickness: volume?.getThicknessFactor() ?? 0,
    attenuationDistance: volume?.getAttenuationDistance() ?? Infinity,
    attenuationColor: volume ? [...volume.getAttenuationColor()] : [1, 1, 1],
    alphaMode: alphaMode === 'MASK' ? 'mask' : alphaMode === 'BLEND' ? 'blend' : 'opaque',
    ...(alphaMode === 'MASK' ? { alphaCutoff: m.getAlphaCutoff() } : {}),
    doubleSided: m.getDoubleSided(),
  };
  // Only the slots that are filled: the model's optional fields are absent, not undefined.
  const filled = Object.fromEntries(Object.entries(optional).filter(([, v]) => v !== undefined));
  return { ...material, ...filled };
}

/** Whether a material uses a normal map (its primitives then need tangents). */
export const usesNormalMap = (m: GltfMaterial | null): boolean => m?.getNormalTexture() != null;
