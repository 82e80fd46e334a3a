/**
 * renderer/prepare.ts editMaterials: the edited records, and for emission the light table, are
 * byte for byte what preparing the edited scene from scratch packs; nothing else is rebuilt.
 */
import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../expect-lantern-error.ts';
import { builtinScene } from '../loaders/builtin/index.ts';
import { applyMaterialEdit, type MaterialEdit } from '../scene/material-edit.ts';
import { diffuse, metallicRoughness, type Scene } from '../scene/types.ts';
import { IDENTITY } from '../math/mat4.ts';
import { editMaterials, LIGHT_BUFFERS, prepareScene } from './prepare.ts';

const bytes = (b: ArrayBuffer) => Array.from(new Uint8Array(b));
const edited = (scene: Scene, edits: ReadonlyMap<number, MaterialEdit>): Scene => ({ ...scene, materials: scene.materials.map((m, i) => (edits.has(i) ? applyMaterialEdit(m, edits.get(i)!) : m)) });

/** The Cornell box with its floor made a glTF metallic-roughness material (index 0). */
function cornellWithGltfFloor(): Scene {
  const base = builtinScene('cornell');
  return { ...base, materials: base.materials.map((m, i) => (i === 0 ? metallicRoughness('floor', { baseColor: [0.8, 0.8, 0.8], roughness: 0.6, metallic: 0 }) : m)) };
}

describe('editMaterials', () => {
  it.each([
    ['a diffuse colour', new Map<number, MaterialEdit>([[1, { color: [0.1, 0.2, 0.9] }]])],
    ['every factor of a metallic-roughness material', new Map<number, MaterialEdit>([[0, { color: [0.9, 0.6, 0.3], roughness: 0.15, metallic: 0.7, ior: 1.8, transmission: 0.2 }]])],
    ["the light's emission", new Map<number, MaterialEdit>([[3, { emission: [30, 10, 2] }]])],
    ['a wall that starts to glow', new Map<number, MaterialEdit>([[2, { emission: [2, 4, 2] }]])],
    ['the light switched off', new Map<number, MaterialEdit>([[3, { emission: [0, 0, 0] }]])],
  ])('%s packs what preparing the edited scene packs', (_, edits) => {
    const scene = cornellWithGltfFloor();
    const prepared = prepareScene(scene);
    const { prepared: live, lightsChanged } = editMaterials(prepared, edits);
    const fresh = prepareScene(edited(scene, edits));
    expect(bytes(live.packed.materials)).toEqual(bytes(fresh.packed.materials));
    for (const name of LIGHT_BUFFERS) expect(bytes(live.packed[name]), name).toEqual(bytes(fresh.packed[name]));
    expect(lightsChanged).toBe([...edits.values()].some((e) => e.emission !== undefined));
    // The geometry is the same objects: nothing was built again.
    expect(live.bvh).toBe(prepared.bvh);
    expect(live.triangles).toBe(prepared.triangles);
    expect(live.packed.atlas).toBe(prepared.packed.atlas);
    expect(live.packed.texture_refs).toBe(prepared.packed.texture_refs);
    if (!lightsChanged) expect(live.packed.bvh_nodes).toBe(prepared.packed.bvh_nodes);
    expect(live.scene.materials[[...edits.keys()][0]!]).toEqual(fresh.scene.materials[[...edits.keys()][0]!]);
    // The original is untouched (the viewer keeps it until the edit is applied).
    expect(bytes(prepared.packed.materials)).toEqual(bytes(prepareScene(scene).packed.materials));
  });

  it('grows the light table when an emitter appears and shrinks it when one goes dark', () => {
    const prepared = prepareScene(builtinScene('cornell'));
    const glow = editMaterials(prepared, new Map([[2, { emission: [1, 1, 1] }]])).prepared;
    expect(glow.packed.counts.lights).toBeGreaterThan(prepared.packed.counts.lights);
    expect(glow.packed.light_slots.byteLength).toBeGreaterThan(prepared.packed.light_slots.byteLength);
    const dark = editMaterials(prepared, new Map([[3, { emission: [0, 0, 0] }]])).prepared;
    expect(dark.packed.counts.lights).toBe(0);
  });

  it('makes a sphere an emitter: its light enters the table as a fresh preparation puts it there', () => {
    const base = builtinScene('cornell');
    const scene: Scene = {
      ...base,
      meshes: [...base.meshes, { name: 'ball', positions: new Float32Array(0), indices: new Uint32Array(0), materialIds: new Uint32Array(0), spheres: { centers: new Float32Array([278, 100, 280]), radii: new Float32Array([60]), materialIds: new Uint32Array([4]) } }],
      instances: [...base.instances, { id: 99, mesh: base.meshes.length, worldFromObject: IDENTITY }],
      materials: [...base.materials, diffuse('ball', [0.5, 0.5, 0.5])],
    };
    const edits = new Map<number, MaterialEdit>([[4, { emission: [3, 2, 1] }]]);
    const prepared = prepareScene(scene);
    const live = editMaterials(prepared, edits).prepared;
    const fresh = prepareScene(edited(scene, edits));
    expect(live.packed.counts.lights).toBe(prepared.packed.counts.lights + 1);
    for (const name of ['materials', ...LIGHT_BUFFERS] as const) expect(bytes(live.packed[name]), name).toEqual(bytes(fresh.packed[name]));
  });

  it('refuses a material that does not exist, a field its kind lacks and values out of range', () => {
    const prepared = prepareScene(builtinScene('cornell'));
    expectLanternError(() => editMaterials(prepared, new Map([[9, { color: [1, 1, 1] }]])), /no material 9/);
    expectLanternError(() => editMaterials(prepared, new Map([[0, { metallic: 1 }]])), /diffuse material has no metallic/);
    expectLanternError(() => editMaterials(prepared, new Map([[0, { color: [1.5, 0, 0] }]])), /color must be three numbers from 0 to 1/);
    expectLanternError(() => editMaterials(prepared, new Map([[3, { emission: [-1, 0, 0] }]])), /emission/);
  });
});
