/**
 * Material edits in the page's links (view-params.ts): one `mat` parameter per edited material,
 * compact and versioned:
 *
 *   mat=1:<index>:<name>:<field>=<values>;<field>=<values>…
 *
 * `1` is the encoding's version; <index> is the material's index in the scene; <name> its name
 * (URI-encoded), checked when the link is applied so that an edit never lands on another material
 * of a changed scene; fields are c (colour: r,g,b), r (roughness), m (metallic), i (IOR),
 * t (transmission), e (emission: r,g,b radiance). Example: mat=1:1:red:c=0.1,0.2,0.9;e=0,0,0.
 * Pure; a malformed entry is reported and skipped, never thrown.
 */
import type { Vec3 } from '../math/vec3.ts';
import { materialEditProblem, MATERIAL_EDIT_FIELDS, type MaterialEdit, type MaterialEditField } from '../scene/material-edit.ts';

/** An edit a link carries: which material (index, and the name it had), and the edited fields. */
export interface MaterialOverride {
  readonly index: number;
  readonly name: string;
  readonly edit: MaterialEdit;
}

export const MATERIAL_LINK_PARAM = 'mat';
export const MATERIAL_LINK_VERSION = '1';

/** The one-letter key of each field. */
const KEYS: Readonly<Record<MaterialEditField, string>> = { color: 'c', roughness: 'r', metallic: 'm', ior: 'i', transmission: 't', emission: 'e' };
const FIELD_OF_KEY = new Map(Object.entries(KEYS).map(([field, key]) => [key, field as MaterialEditField]));
const isTriple = (f: MaterialEditField) => f === 'color' || f === 'emission';

const round = (v: number) => Number(v.toPrecision(6));

export function formatMaterialOverride(o: MaterialOverride): string {
  const fields = MATERIAL_EDIT_FIELDS.filter((f) => o.edit[f] !== undefined).map((f) => {
    const v = o.edit[f]!;
    return `${KEYS[f]}=${(typeof v === 'number' ? [v] : v).map(round).join(',')}`;
  });
  return [MATERIAL_LINK_VERSION, String(o.index), encodeURIComponent(o.name), fields.join(';')].join(':');
}

/** One `mat` value read back, or the problem with it (in words for the page's warning line). */
export function parseMaterialOverride(raw: string): { ok: true; value: MaterialOverride } | { ok: false; problem: string } {
  const fail = (why: string) => ({ ok: false as const, problem: `${MATERIAL_LINK_PARAM}=${raw}: ${why}` });
  const parts = raw.split(':');
  if (parts[0] !== MATERIAL_LINK_VERSION) return fail(`not a material edit of version ${MATERIAL_LINK_VERSION} (${MATERIAL_LINK_VERSION}:index:name:fields)`);
  if (parts.length !== 4) return fail('expected version:index:name:fields');
  const [, indexText, encodedName, fieldsText] = parts as [string, string, string, string];
  const index = Number(indexText);
  if (indexText === '' || !Number.isInteger(index) || index < 0) return fail(`the material index '${indexText}' is not a whole number ≥ 0`);
  let name: string;
  try {
    name = decodeURIComponent(encodedName);
  } catch {
    return fail('the material name is not URI-encoded text');
  }
  const edit: Record<string, number | Vec3> = {};
  for (const item of fieldsText.split(';')) {
    if (item === '') continue;
    const [key, values, extra] = item.split('=');
    const field = FIELD_OF_KEY.get(key ?? '');
    if (!field || values === undefined || extra !== undefined) return fail(`'${item}' is not one of ${Object.values(KEYS).join(', ')} with a value`);
    if (field in edit) return fail(`${key} is given twice`);
    const numbers = values.split(',').map((v) => (v.trim() === '' ? NaN : Number(v)));
    const count = isTriple(field) ? 3 : 1;
    if (numbers.length !== count || !numbers.every(Number.isFinite)) return fail(`${key} takes ${count === 3 ? 'three numbers' : 'a number'}`);
    edit[field] = count === 3 ? (numbers as unknown as Vec3) : numbers[0]!;
  }
  if (Object.keys(edit).length === 0) return fail('no field is edited');
  // Ranges are checked here (every field is allowed to some kind); the kind is checked when applied.
  const problem = materialEditProblem('metallic-roughness', edit);
  if (problem) return fail(problem);
  return { ok: true, value: { index, name, edit } };
}
