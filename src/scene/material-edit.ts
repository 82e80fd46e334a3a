/**
 * Live material edits (the viewer's material panel and the links that carry its edits): the
 * constant factors a user may change on a material without changing its kind, its textures or its
 * coverage. Changing these only repacks the material records (and, for emission, the light table);
 * the BVH, the textures and the pipelines stay as they are. Pure.
 *
 * Each field maps onto what the kind has: `color` is a diffuse material's albedo, a metallic-roughness
 * material's base colour, a dielectric's tint; `emission` is emitted radiance (linear RGB, any kind).
 *
 * Animations (world/material-animation.ts) edit materials too, with fields no panel shows
 * (MaterialAnimationEdit): which texture a texture cycle shows, and how far a scrolling texture has
 * moved. Those need the textures packed ahead (gpu/pack/material-pack.ts packs every texture a
 * scene's animations can show, with texture references of their own), so a step of an animation
 * still only rewrites records.
 */
import { LanternError } from '../errors.ts';
import type { Vec3 } from '../math/vec3.ts';
import { coverageOf, type Material, type MaterialKind, type TextureRef } from './types.ts';

/** The constant factors a user may edit (the material panel, links). */
export interface MaterialFactorEdit {
  /** Albedo / base colour / tint, linear RGB in [0, 1]. */
  readonly color?: Vec3;
  /** Perceptual roughness in [0, 1]. */
  readonly roughness?: number;
  readonly metallic?: number;
  /** Index of refraction in [1, 10) (the range validate.ts accepts). */
  readonly ior?: number;
  readonly transmission?: number;
  /** Emitted radiance, linear RGB, each channel ≥ 0. */
  readonly emission?: Vec3;
}

/**
 * What animations change (world/material-animation.ts); never shown in panels or links. Texture
 * indices are into Scene.textures; a material may only be given textures its animation lists (the
 * packer placed those ahead; any other is a LanternError when the edit is packed).
 */
export interface MaterialAnimationEdit {
  /** The colour texture: a diffuse material's albedo texture, a metallic-roughness material's base colour texture. */
  readonly albedoTexture?: number;
  readonly emissionTexture?: number;
  /**
   * The offset of every texture use of the material (KHR_texture_transform's offset, in uv units:
   * uv' = T(offset) · R · S · uv), replacing the one it was loaded with.
   */
  readonly uvOffset?: readonly [number, number];
}

export interface MaterialEdit extends MaterialFactorEdit, MaterialAnimationEdit {}

/** The fields panels and links show. */
export type MaterialEditField = keyof MaterialFactorEdit;
export type MaterialAnimationField = keyof MaterialAnimationEdit;

/** The animation fields, apart from the panel's (MATERIAL_EDIT_FIELDS). */
export const MATERIAL_ANIMATION_FIELDS: readonly MaterialAnimationField[] = ['albedoTexture', 'emissionTexture', 'uvOffset'];

/** Every edit field, in the order panels and links show them. */
export const MATERIAL_EDIT_FIELDS: readonly MaterialEditField[] = ['color', 'roughness', 'metallic', 'ior', 'transmission', 'emission'];

/** Which fields each kind has (an emissive surface only emits; glass has no metallic or transmission factor: it transmits). */
export const EDITABLE_FIELDS: Readonly<Record<MaterialKind, readonly MaterialEditField[]>> = {
  diffuse: ['color', 'emission'],
  'metallic-roughness': ['color', 'roughness', 'metallic', 'ior', 'transmission', 'emission'],
  dielectric: ['color', 'roughness', 'ior', 'emission'],
  emissive: ['emission'],
};

/** The largest emitted radiance an edit may set per channel (far beyond any scene's lamps, short of overflow in f32 sums). */
export const MAX_EDIT_EMISSION = 1e6;

/** The valid range of each scalar field (inclusive, except ior's upper end). */
export const EDIT_RANGES = {
  roughness: [0, 1],
  metallic: [0, 1],
  ior: [1, 10],
  transmission: [0, 1],
} as const;

/** What is wrong with `edit` for a material of `kind`, or undefined when it may be applied. */
export function materialEditProblem(kind: MaterialKind, edit: MaterialEdit): string | undefined {
  const allowed = EDITABLE_FIELDS[kind];
  for (const field of MATERIAL_EDIT_FIELDS) {
    const value = edit[field];
    if (value === undefined) continue;
    if (!allowed.includes(field)) return `a ${kind} material has no ${field} (it has ${allowed.join(', ')})`;
    if (field === 'color' || field === 'emission') {
      const v = value as Vec3;
      const hi = field === 'color' ? 1 : MAX_EDIT_EMISSION;
      if (!Array.isArray(v) || v.length !== 3 || !v.every((c) => Number.isFinite(c) && c >= 0 && c <= hi)) return `${field} must be three numbers from 0 to ${hi}`;
      continue;
    }
    const [lo, hi] = EDIT_RANGES[field];
    const x = value as number;
    const inside = Number.isFinite(x) && x >= lo && (field === 'ior' ? x < hi : x <= hi);
    if (!inside) return `${field} ${x} is outside ${lo}–${hi}`;
  }
  return animationEditProblem(kind, edit);
}

function animationEditProblem(kind: MaterialKind, edit: MaterialAnimationEdit): string | undefined {
  const index = (x: number) => Number.isInteger(x) && x >= 0;
  if (edit.albedoTexture !== undefined) {
    if (kind !== 'diffuse' && kind !== 'metallic-roughness') return `a ${kind} material has no colour texture to swap`;
    if (!index(edit.albedoTexture)) return `albedoTexture must be a texture index, not ${edit.albedoTexture}`;
  }
  if (edit.emissionTexture !== undefined && !index(edit.emissionTexture)) return `emissionTexture must be a texture index, not ${edit.emissionTexture}`;
  const uv = edit.uvOffset;
  if (uv !== undefined && !(Array.isArray(uv) && uv.length === 2 && uv.every((c) => Number.isFinite(c)))) return 'uvOffset must be two finite numbers';
  return undefined;
}

/** `ref` with its texture and transform offset changed as the edit says (undefined stays undefined). */
function editRef<R extends TextureRef>(ref: R | undefined, edit: MaterialAnimationEdit, texture?: number): R | undefined {
  if (!ref) return undefined;
  let out: R = texture === undefined ? ref : { ...ref, texture };
  if (edit.uvOffset) {
    const t = ref.transform;
    out = { ...out, transform: { offset: [edit.uvOffset[0], edit.uvOffset[1]], rotation: t?.rotation ?? 0, scale: t?.scale ?? [1, 1] } };
  }
  return out;
}

/** The texture uses of `m` with an animation edit applied (texture swaps and uv offsets). */
function applyAnimationEdit(m: Material, edit: MaterialAnimationEdit): Material {
  if (edit.albedoTexture === undefined && edit.emissionTexture === undefined && edit.uvOffset === undefined) return m;
  if (edit.albedoTexture !== undefined && coverageOf(m).texture === undefined) {
    throw new LanternError(`cannot edit material '${m.name}': it has no colour texture to swap for texture ${edit.albedoTexture}`);
  }
  if (edit.emissionTexture !== undefined && m.emissionTexture === undefined) {
    throw new LanternError(`cannot edit material '${m.name}': it has no emission texture to swap for texture ${edit.emissionTexture}`);
  }
  const common = { emissionTexture: editRef(m.emissionTexture, edit, edit.emissionTexture), normalTexture: editRef(m.normalTexture, edit) };
  const strip = <T extends object>(o: T): T => Object.fromEntries(Object.entries(o).filter(([, v]) => v !== undefined)) as T;
  switch (m.kind) {
    case 'diffuse':
      return { ...m, ...strip({ ...common, albedoTexture: editRef(m.albedoTexture, edit, edit.albedoTexture) }) };
    case 'metallic-roughness':
      return {
        ...m,
        ...strip({
          ...common,
          baseColorTexture: editRef(m.baseColorTexture, edit, edit.albedoTexture),
          metallicRoughnessTexture: editRef(m.metallicRoughnessTexture, edit),
          specularTexture: editRef(m.specularTexture, edit),
          specularColorTexture: editRef(m.specularColorTexture, edit),
          transmissionTexture: editRef(m.transmissionTexture, edit),
        }),
      };
    case 'dielectric':
    case 'emissive':
      return { ...m, ...strip(common) };
  }
}

/** The material with the edit applied; a field the kind lacks or a value out of range is a LanternError. */
export function applyMaterialEdit(original: Material, edit: MaterialEdit): Material {
  const problem = materialEditProblem(original.kind, edit);
  if (problem) throw new LanternError(`cannot edit material '${original.name}': ${problem}`);
  const material = applyAnimationEdit(original, edit);
  const emission = edit.emission ?? material.emission;
  switch (material.kind) {
    case 'diffuse':
      return { ...material, emission, albedo: edit.color ?? material.albedo };
    case 'metallic-roughness':
      return {
        ...material,
        emission,
        baseColor: edit.color ?? material.baseColor,
        roughness: edit.roughness ?? material.roughness,
        metallic: edit.metallic ?? material.metallic,
        ior: edit.ior ?? material.ior,
        transmission: edit.transmission ?? material.transmission,
      };
    case 'dielectric':
      return { ...material, emission, tint: edit.color ?? material.tint, roughness: edit.roughness ?? material.roughness, ior: edit.ior ?? material.ior };
    case 'emissive':
      return { ...material, emission };
  }
}

/** The current values of every field the material's kind has (what a panel starts from). */
export function editableValues(material: Material): MaterialEdit {
  switch (material.kind) {
    case 'diffuse':
      return { color: material.albedo, emission: material.emission };
    case 'metallic-roughness':
      return { color: material.baseColor, roughness: material.roughness, metallic: material.metallic, ior: material.ior, transmission: material.transmission, emission: material.emission };
    case 'dielectric':
      return { color: material.tint, roughness: material.roughness, ior: material.ior, emission: material.emission };
    case 'emissive':
      return { emission: material.emission };
  }
}

/** Two edits merged, the later winning field by field. */
export function mergeMaterialEdits(a: MaterialEdit, b: MaterialEdit): MaterialEdit {
  return { ...a, ...Object.fromEntries(Object.entries(b).filter(([, v]) => v !== undefined)) };
}

/** Whether the edit changes the material's emission (then the light table must be packed again). */
export function editChangesEmission(material: Material, edit: MaterialEdit): boolean {
  return edit.emission !== undefined && edit.emission.some((c, i) => c !== material.emission[i]);
}
