import { existsSync, readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { WebIO } from '@gltf-transform/core';
import { KHRMaterialsEmissiveStrength, type EmissiveStrength } from '@gltf-transform/extensions';
// @ts-expect-error gltf-validator ships no types
import { validateBytes } from 'gltf-validator';
import { builtinScene } from '../loaders/builtin/index.ts';
import { loadDoomMap } from '../loaders/doom/load.ts';
import { readWad, WadStack } from '../loaders/doom/wad.ts';
import type { Scene } from '../scene/types.ts';
import { quaternionFromBasis, sceneToGlb } from './glb.ts';

interface ValidationReport {
  issues: { numErrors: number; numWarnings: number; messages: { code: string; message: string; severity: number; pointer?: string }[] };
}

async function validate(glb: Uint8Array): Promise<ValidationReport> {
  return validateBytes(glb) as Promise<ValidationReport>;
}

const textured: Scene = {
  name: 'textured',
  meshes: [
    {
      name: 'quad',
      positions: new Float32Array([0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0]),
      indices: new Uint32Array([0, 1, 2, 0, 2, 3]),
      uvs: new Float32Array([0, 1, 1, 1, 1, 0, 0, 0]),
      materialIds: new Uint32Array([0, 1]),
    },
  ],
  materials: [
    { name: 'masked', albedo: [1, 1, 1], emission: [0, 0, 0], albedoTexture: 0, alphaMode: 'mask' },
    { name: 'glow', albedo: [1, 1, 1], emission: [12, 6, 3], emissionTexture: 0 },
  ],
  textures: [{ name: 'CHECK', width: 2, height: 2, rgba: new Uint8Array([255, 0, 0, 255, 0, 0, 0, 0, 0, 0, 0, 0, 0, 255, 0, 255]) }],
  camera: { position: [0.5, 0.5, 3], forward: [0, 0, -1], up: [0, 1, 0], vfovDegrees: 50 },
};

describe('GLB export', () => {
  it.each([
    ['cornell', builtinScene('cornell')],
    ['a textured, masked, emissive scene', textured],
  ])('%s validates with no errors and round-trips', async (_, scene) => {
    const glb = await sceneToGlb(scene);
    const report = await validate(glb);
    expect(report.issues.messages.filter((m) => m.severity === 0)).toEqual([]);

    const doc = await new WebIO().registerExtensions([KHRMaterialsEmissiveStrength]).readBinary(glb);
    const root = doc.getRoot();
    expect(root.listMaterials().map((m) => m.getName())).toEqual(scene.materials.map((m) => m.name));
    expect(root.listTextures()).toHaveLength(scene.textures?.length ?? 0);
    const triangles = root.listMeshes().flatMap((m) => m.listPrimitives()).reduce((n, p) => n + p.getIndices()!.getCount() / 3, 0);
    expect(triangles).toBe(scene.meshes.reduce((n, m) => n + m.indices.length / 3, 0));
    expect(root.listCameras()).toHaveLength(1);
  });

  it('keeps emission above 1 through KHR_materials_emissive_strength, and masks as MASK', async () => {
    const doc = await new WebIO().registerExtensions([KHRMaterialsEmissiveStrength]).readBinary(await sceneToGlb(textured));
    const [masked, glow] = doc.getRoot().listMaterials();
    expect(masked!.getAlphaMode()).toBe('MASK');
    expect(masked!.getAlphaCutoff()).toBe(0.5);
    const strength = glow!.getExtension<EmissiveStrength>('KHR_materials_emissive_strength')!.getEmissiveStrength();
    expect(glow!.getEmissiveFactor().map((f) => f * strength)).toEqual([12, 6, 3]);
    expect(glow!.getEmissiveTexture()?.getName()).toBe('CHECK');
  });

  it('scales positions to metres when the scene knows its unit', async () => {
    const doc = await new WebIO().readBinary(await sceneToGlb(builtinScene('cornell')));
    const position = doc.getRoot().listMeshes()[0]!.listPrimitives()[0]!.getAttribute('POSITION')!;
    expect(position.getMax([0, 0, 0])[1]).toBeCloseTo(0.5488, 4);
  });

  it('builds camera rotations that map local axes to the given basis', () => {
    const q = quaternionFromBasis([0, 0, 1], [0, 1, 0], [-1, 0, 0]);
    // Rotating local −z (the glTF camera's view direction) must give world +x.
    const [x, y, z, w] = q;
    const v = [0, 0, -1];
    const t = [2 * (y * v[2]! - z * v[1]!), 2 * (z * v[0]! - x * v[2]!), 2 * (x * v[1]! - y * v[0]!)];
    const r = [v[0]! + w * t[0]! + (y * t[2]! - z * t[1]!), v[1]! + w * t[1]! + (z * t[0]! - x * t[2]!), v[2]! + w * t[2]! + (x * t[1]! - y * t[0]!)];
    expect(r[0]).toBeCloseTo(1, 6);
    expect(r[1]).toBeCloseTo(0, 6);
    expect(r[2]).toBeCloseTo(0, 6);
  });
});

const FREEDOOM1 = '/usr/share/games/doom/freedoom1.wad';

describe.skipIf(!existsSync(FREEDOOM1))('GLB export of freedoom1 E1M1', () => {
  it('validates with no errors and round-trips through a glTF reader', async () => {
    const { scene } = loadDoomMap(new WadStack([readWad(readFileSync(FREEDOOM1), 'freedoom1.wad')]), 'E1M1');
    const glb = await sceneToGlb(scene);
    const report = await validate(glb);
    expect(report.issues.numErrors, JSON.stringify(report.issues.messages.slice(0, 5))).toBe(0);
    const doc = await new WebIO().registerExtensions([KHRMaterialsEmissiveStrength]).readBinary(glb);
    const root = doc.getRoot();
    expect(root.listTextures()).toHaveLength(scene.textures!.length);
    expect(root.listMaterials().filter((m) => m.getEmissiveFactor().some((f) => f > 0)).length).toBeGreaterThan(0);
    expect(root.listMaterials().some((m) => m.getAlphaMode() === 'MASK')).toBe(true);
    const triangles = root.listMeshes().flatMap((m) => m.listPrimitives()).reduce((n, p) => n + p.getIndices()!.getCount() / 3, 0);
    expect(triangles).toBe(scene.meshes.reduce((n, m) => n + m.indices.length / 3, 0));
    // Doom units to metres: the map spans a few hundred metres, not kilometres.
    const extent = root.listMeshes().flatMap((m) => m.listPrimitives()).map((p) => p.getAttribute('POSITION')!.getMax([0, 0, 0])[0]);
    expect(Math.max(...extent.map((x) => x ?? 0))).toBeLessThan(500);
  });
});
