/**
 * The glTF loader over the Khronos sample models in ../shared/assets/gltf (see its README.md): what
 * each model is known to hold, and that the files its MISSING.txt lists are named once each.
 */
import { existsSync, readFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { LanternError } from '../../errors.ts';
import { transformPoint } from '../../math/mat4.ts';
import type { MetallicRoughnessMaterial, Scene } from '../../scene/types.ts';
import { loadGltf } from './index.ts';

/** ../shared/assets/gltf beside the checkout (or beside the worktrees' folder), or LANTERN_GLTF_ASSETS. */
const ROOT = join(import.meta.dirname, '../../..');
const ASSETS =
  process.env['LANTERN_GLTF_ASSETS'] ??
  [join(ROOT, '../shared/assets/gltf'), join(ROOT, '../../shared/assets/gltf')].find((p) => existsSync(p)) ??
  join(ROOT, '../shared/assets/gltf');
const present = existsSync(ASSETS);
if (!present) console.warn(`glTF sample tests skipped: ${ASSETS} is absent`);

/** Each model is loaded once for all the tests that look at it (the large ones take seconds). */
const loaded = new Map<string, Promise<Scene>>();
function loadSample(path: string): Promise<Scene> {
  let scene = loaded.get(path);
  if (!scene) loaded.set(path, (scene = loadUncached(path)));
  return scene;
}

async function loadUncached(path: string): Promise<Scene> {
  const file = join(ASSETS, path);
  return loadGltf({ name: path.split('/').pop()!, bytes: readFileSync(file) }, async (uri) => {
    const sibling = join(dirname(file), decodeURIComponent(uri));
    return existsSync(sibling) ? readFileSync(sibling) : undefined;
  });
}

/** The file names a model's MISSING.txt lists (lines after the first that end in an extension). */
function missingFiles(model: string): string[] {
  return readFileSync(join(ASSETS, model, 'MISSING.txt'), 'utf8')
    .split('\n')
    .slice(1)
    .map((l) => l.trim().split(' ')[0] ?? '')
    .filter((l) => /\.\w+$/.test(l));
}

const triangles = (s: Scene) => s.meshes.reduce((n, m) => n + m.indices.length / 3, 0);
const mr = (s: Scene, i = 0) => s.materials[i] as MetallicRoughnessMaterial;

describe.skipIf(!present)('glTF sample models', () => {
  it('Duck: the .gltf (with .bin and .png) and the .glb give the same scene', async () => {
    const a = await loadSample('Duck/glTF/Duck.gltf');
    const b = await loadSample('Duck/glTF-Binary/Duck.glb');
    expect(triangles(a)).toBe(4212);
    expect(b.meshes).toEqual(a.meshes);
    expect(b.instances).toEqual(a.instances);
    expect(b.materials).toEqual(a.materials);
    for (const key of ['position', 'forward', 'up'] as const) b.camera[key].forEach((x, i) => expect(x).toBeCloseTo(a.camera[key][i]!, 12));
    expect(b.camera.vfovDegrees).toBeCloseTo(a.camera.vfovDegrees, 12);
    // Same pixels; names differ only because the GLB's image is embedded and unnamed.
    expect(b.textures!.map((t) => [t.width, t.height, t.encoding, t.rgba])).toEqual(a.textures!.map((t) => [t.width, t.height, t.encoding, t.rgba]));
    expect(a.warnings).toEqual([]);
    expect(a.lightingNote).toBe('the model has no light of its own; a default sky lights it');
    expect(a.environment).toEqual({ kind: 'sky', sunElevationDeg: 40, sunAzimuthDeg: 30, turbidity: 3, groundAlbedo: 0.3, intensity: 1 });
    expect(a.metersPerUnit).toBe(1);
  });

  it('DamagedHelmet: JPEG textures with colour ones in sRGB and data ones linear, generated tangents', async () => {
    const s = await loadSample('DamagedHelmet/glTF-Binary/DamagedHelmet.glb');
    expect(triangles(s)).toBe(15452);
    const m = mr(s);
    const tex = (ref: { texture: number } | undefined) => s.textures![ref!.texture]!;
    expect(tex(m.baseColorTexture).encoding).toBe('srgb');
    expect(tex(m.emissionTexture).encoding).toBe('srgb');
    expect(tex(m.metallicRoughnessTexture).encoding).toBe('linear');
    expect(tex(m.normalTexture).encoding).toBe('linear');
    expect(tex(m.baseColorTexture)).toMatchObject({ width: 2048, height: 2048 });
    // Every triangle emits, but the emissive texture is black outside a few glowing details: they
    // give about half a percent of a sky's light, so the default sky lights the helmet (it opened
    // black before), and says so as information, not as a warning.
    expect(m.emission).toEqual([1, 1, 1]);
    expect(s.environment).toMatchObject({ kind: 'sky' });
    expect(s.lightingNote).toMatch(/^its emitters give 0\.[3-9]\d? % of the light of a default sky; a default sky lights it$/);
    expect(s.warnings).toEqual([]);
    // The file has no TANGENT: MikkTSpace tangents are unit, orthogonal to the normal, signed ±1.
    const mesh = s.meshes[0]!;
    const t = mesh.tangents!, n = mesh.normals!;
    expect(t.length / 4).toBe(mesh.positions.length / 3);
    for (let v = 0; v < t.length / 4; v += 97) {
      expect(Math.hypot(t[v * 4]!, t[v * 4 + 1]!, t[v * 4 + 2]!)).toBeCloseTo(1, 3);
      expect(Math.abs(t[v * 4]! * n[v * 3]! + t[v * 4 + 1]! * n[v * 3 + 1]! + t[v * 4 + 2]! * n[v * 3 + 2]!)).toBeLessThan(1e-3);
      expect(Math.abs(t[v * 4 + 3]!)).toBe(1);
    }
  });

  it.each([
    ['FlightHelmet', 'FlightHelmet/glTF/FlightHelmet.gltf'],
    ['Lantern', 'Lantern/glTF/Lantern.gltf'],
    ['BoomBox', 'BoomBox/glTF/BoomBox.gltf'],
  ])('%s names each missing file once and still loads, with neutral textures in their place', async (model, path) => {
    const s = await loadSample(path);
    const missing = missingFiles(model);
    expect(missing.length).toBeGreaterThan(0);
    for (const file of missing) {
      expect(s.warnings!.filter((w) => w.includes(file)), file).toHaveLength(1);
      const fallbacks = s.textures!.filter((t) => t.name.startsWith(file));
      expect(fallbacks.length).toBeGreaterThan(0);
      for (const t of fallbacks) expect([t.width, t.height]).toEqual([1, 1]);
    }
    expect(triangles(s)).toBeGreaterThan(1000);
    // Only the files listed as missing are warned about as missing.
    expect(s.warnings!.filter((w) => w.includes('is missing')).length).toBe(missing.length);
  });

  it('a missing normal map becomes a flat normal and a missing colour texture white', async () => {
    const s = await loadSample('FlightHelmet/glTF/FlightHelmet.gltf');
    const normal = s.textures!.find((t) => t.name.startsWith('FlightHelmet_Materials_LeatherPartsMat_Normal.png'))!;
    const colour = s.textures!.find((t) => t.name.startsWith('FlightHelmet_Materials_LeatherPartsMat_BaseColor.png'))!;
    expect([...normal.rgba]).toEqual([128, 128, 255, 255]);
    expect([...colour.rgba]).toEqual([255, 255, 255, 255]);
  });

  it('Cameras: the first camera reached is the view, looking down the node’s −Z', async () => {
    const s = await loadSample('Cameras/glTF/Cameras.gltf');
    expect(s.camera.position).toEqual([0.5, 0.5, 3]);
    expect(s.camera.forward).toEqual([0, 0, -1]);
    expect(s.camera.up).toEqual([0, 1, 0]);
    expect(s.camera.vfovDegrees).toBeCloseTo((0.7 * 180) / Math.PI, 10);
  });

  it('AnimatedCube: the node’s rotation (half a turn about +y) places the mesh', async () => {
    const s = await loadSample('AnimatedCube/glTF/AnimatedCube.gltf');
    expect(s.instances).toHaveLength(1);
    const inst = s.instances[0]!;
    expect(inst.id).toBe(0);
    const p = transformPoint(inst.worldFromObject, [1, 1, 1]);
    expect(p[0]).toBeCloseTo(-1, 6);
    expect(p[1]).toBeCloseTo(1, 6);
    expect(p[2]).toBeCloseTo(-1, 6);
  });

  it('BoxAnimated: one instance per mesh node, ids = node indices in scene order, through the hierarchy', async () => {
    for (const path of ['BoxAnimated/glTF/BoxAnimated.gltf', 'BoxAnimated/glTF-Binary/BoxAnimated.glb']) {
      const s = await loadSample(path);
      // scene.nodes = [3, 0]; node 0 → 1 → 2 carries mesh 0, node 3 carries mesh 1.
      expect(s.instances.map((i) => i.id)).toEqual([3, 2]);
      expect(s.meshes[s.instances[1]!.mesh]!.indices.length).toBe(186);
      expect(triangles(s)).toBe(254);
    }
  });

  it('AlphaBlendModeTest: alpha modes and cutoffs', async () => {
    const s = await loadSample('AlphaBlendModeTest/glTF/AlphaBlendModeTest.gltf');
    const byName = new Map(s.materials.map((m) => [m.name, m]));
    expect(byName.get('MatBlend')!.alphaMode).toBe('blend');
    expect(byName.get('MatOpaque')!.alphaMode).toBe('opaque');
    expect(byName.get('MatCutoff25')).toMatchObject({ alphaMode: 'mask', alphaCutoff: 0.25, doubleSided: true });
    expect(byName.get('MatCutoff75')).toMatchObject({ alphaMode: 'mask', alphaCutoff: 0.75 });
    expect(byName.get('MatCutoffDefault')).toMatchObject({ alphaMode: 'mask', alphaCutoff: 0.5 });
    expect(byName.get('MatBed')).toMatchObject({ alphaMode: 'opaque', doubleSided: false });
  });

  it('MetalRoughSpheres: its .bin is absent, so the load fails naming that file', async () => {
    const error = await loadSample('MetalRoughSpheres/glTF/MetalRoughSpheres.gltf').catch((e: unknown) => e);
    expect(error).toBeInstanceOf(LanternError);
    expect((error as LanternError).message).toContain('MetalRoughSpheres0.bin');
  });
});
