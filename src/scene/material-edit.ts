/**
 * Live material edits (the viewer's material panel and the links that carry its edits): the
 * constant factors a user may change on a material without changing its kind, its textures or its
 * coverage. Changing these only repacks the material records (and, for emission, the light table);
 * the BVH, the textures and the pipelines stay as they are. Pure.
 *
 * Each field maps onto what the kind has: `color` is a diffuse material's albedo, a metallic-roughness
 * material's base colour, a dielectric's tint; `emission` is emitted radiance (linear RGB, any kind).
 */
import { LanternError } from '../errors.ts';
import type { Vec3 } from '../math/vec3.ts';
import type { Material, MaterialKind } from './types.ts';

export interface MaterialEdit {
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

export type MaterialEditField = keyof MaterialEdit;

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
  return undefined;
}

/** The material with the edit applied; a field the kind lacks or a value out of range is a LanternError. */
export function applyMaterialEdit(material: Material, edit: MaterialEdit): Material {
  const problem = materialEditProblem(material.kind, edit);
  if (problem) throw new LanternError(`cannot edit material '${material.name}': ${problem}`);
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
