import { existsSync, readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
// @ts-expect-error gltf-validator ships no types
import { validateBytes } from 'gltf-validator';
import { loadDoomMap } from '../loaders/doom/load.ts';
import { readWad, WadStack } from '../loaders/doom/wad.ts';
import { loadGltf } from '../loaders/gltf/index.ts';
import { determinant3, fromTrs, transformPoint, type Mat4 } from '../math/mat4.ts';
import type { Vec3 } from '../math/vec3.ts';
import type { MetallicRoughnessMaterial, Scene } from '../scene/types.ts';
import { quaternionFromBasis, sceneToGlb } from './glb.ts';

interface ValidationReport {
  issues: { numErrors: number; numWarnings: number; messages: { code: string; message: string; severity: number; pointer?: string }[] };
}

async function validate(glb: Uint8Array): Promise<ValidationReport> {
  return validateBytes(glb) as Promise<ValidationReport>;
}

const reload = async (glb: Uint8Array): Promise<Scene> => loadGltf({ name: 'export.glb', bytes: glb }, async () => undefined);

const s45 = Math.SQRT1_2;
const BLACK: Vec3 = [0, 0, 0];

/** Every material kind, textures with transforms and a second uv set, two instances of one mesh (one mirrored), all light kinds. */
const showcase: Scene = {
  name: 'showcase',
  meshes: [
    {
      name: 'quads',
      positions: new Float32Array([0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 0, 0, 3, 0, 0, 3, 1, 0, 2, 1, 0]),
      indices: new Uint32Array([0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7, 0, 1, 6, 0, 6, 7, 1, 4, 5, 1, 5, 2]),
      normals: new Float32Array(Array.from({ length: 8 }, () => [0, 0, 1]).flat()),
      uvs: new Float32Array([0, 1, 1, 1, 1, 0, 0, 0, 0, 1, 1, 1, 1, 0, 0, 0]),
      uvs1: new Float32Array([0, 0, 0.5, 0, 0.5, 0.5, 0, 0.5, 0.5, 0.5, 1, 0.5, 1, 1, 0.5, 1]),
      tangents: new Float32Array(Array.from({ length: 8 }, () => [1, 0, 0, 1]).flat()),
      materialIds: new Uint32Array([0, 1, 2, 3, 4, 4, 5, 5]),
    },
  ],
  instances: [
    { id: 7, name: 'left', mesh: 0, worldFromObject: fromTrs([-4, 0, 1], [0, 0, s45, s45], [1, 2, 1]) },
    { id: 9, name: 'mirrored', mesh: 0, worldFromObject: fromTrs([4, 0, 0], [0, 0, 0, 1], [-1, 1, 1]) },
  ],
  materials: [
    { kind: 'diffuse', name: 'masked', albedo: [0.8, 0.7, 0.6], emission: BLACK, albedoTexture: { texture: 0 }, alphaMode: 'mask', alphaCutoff: 0.3 },
    {
      kind: 'metallic-roughness',
      name: 'everything',
      baseColor: [0.5, 0.25, 0.125],
      opacity: 0.75,
      baseColorTexture: { texture: 0, texCoord: 1, transform: { offset: [0.5, 0.25], rotation: 0.5, scale: [2, 4] } },
      metallic: 0.25,
      roughness: 0.5,
      metallicRoughnessTexture: { texture: 1 },
      normalTexture: { texture: 2, scale: 0.5 },
      ior: 1.25,
      specular: 0.5,
      specularColor: [1, 0.5, 0.25],
      specularTexture: { texture: 1 },
      transmission: 0.5,
      transmissionTexture: { texture: 1, transform: { offset: [0, 0], rotation: 0, scale: [3, 3] } },
      thickness: 0.5,
      attenuationDistance: 2,
      attenuationColor: [0.5, 0.75, 1],
      emission: [0.5, 0.25, 0],
      alphaMode: 'blend',
      doubleSided: false,
    },
    { kind: 'dielectric', name: 'glass', ior: 1.5, roughness: 0.125, tint: [0.75, 1, 0.75], attenuationDistance: 4, attenuationColor: [0.5, 0.5, 1], emission: BLACK },
    { kind: 'emissive', name: 'glow', emission: [12, 6, 3], emissionTexture: { texture: 0 } },
    { kind: 'emissive', name: 'sky', emission: [1, 1, 1], emissionTexture: { texture: 0 }, emissionMapping: { kind: 'panorama', repeats: 4, horizonV: 0.5, vPerRadian: 1 } },
    { kind: 'diffuse', name: 'plain', albedo: [0.5, 0.5, 0.5], emission: BLACK },
  ],
  textures: [
    { name: 'CHECK', width: 2, height: 2, rgba: new Uint8Array([255, 0, 0, 255, 0, 0, 0, 0, 0, 0, 0, 0, 0, 255, 0, 255]) },
    { name: 'data', width: 1, height: 1, rgba: new Uint8Array([10, 20, 30, 40]), encoding: 'linear' },
    { name: 'normal', width: 1, height: 1, rgba: new Uint8Array([128, 128, 255, 255]), encoding: 'linear' },
  ],
  lights: [
    { kind: 'point', name: 'bulb', position: [1, 2, 3], color: [1, 0.5, 0.25], intensity: 20, range: Infinity },
    { kind: 'spot', name: 'spot', position: [0, 5, 0], direction: [0, -1, 0], color: [1, 1, 1], intensity: 50, range: 12, innerConeAngle: 0.25, outerConeAngle: 0.5 },
    { kind: 'directional', name: 'sun', direction: [0.6, -0.8, 0], color: [1, 0.9, 0.8], irradiance: 3 },
  ],
  camera: { position: [0.5, 0.5, 3], forward: [0, -0.6, -0.8], up: [0, 1, 0], vfovDegrees: 50 },
  metersPerUnit: 1,
};

/** World positions of every triangle corner of every instance, in instance then index order. */
function worldCorners(scene: Scene): Vec3[] {
  return scene.instances.flatMap((inst) => {
    const m = scene.meshes[inst.mesh]!;
    return [...m.indices].map((v) => transformPoint(inst.worldFromObject, [m.positions[v * 3]!, m.positions[v * 3 + 1]!, m.positions[v * 3 + 2]!]));
  });
}

/** Triangles of the scene as sorted lists of world corners, so primitive order does not matter. */
function worldTriangles(scene: Scene): string[] {
  const corners = worldCorners(scene);
  const out: string[] = [];
  for (let t = 0; t < corners.length; t += 3) out.push(corners.slice(t, t + 3).map((p) => p.map((x) => x.toFixed(4)).join(',')).join(' '));
  return out.sort();
}

const close = (a: readonly number[], b: readonly number[], digits = 5) => a.forEach((x, i) => expect(x).toBeCloseTo(b[i]!, digits));

describe('GLB export', () => {
  it('validates with no errors in the Khronos validator', async () => {
    const report = await validate(await sceneToGlb(showcase));
    // Severity 0 = error, 1 = warning (2 and 3 are hints such as an unused uv set on one primitive).
    expect(report.issues.messages.filter((m) => m.severity <= 1)).toEqual([]);
  });

  it('exports spheres and capsules tessellated, valid, beside the mesh\'s own triangles', async () => {
    const withShapes: Scene = {
      ...showcase,
      meshes: showcase.meshes.map((m, i) =>
        i === 0
          ? {
              ...m,
              spheres: { centers: new Float32Array([0, 1, 0]), radii: new Float32Array([0.5]), materialIds: new Uint32Array([0]) },
              capsules: { endpoints: new Float32Array([0, 0, 0, 1, 0, 0]), radii: new Float32Array([0.1]), materialIds: new Uint32Array([0]) },
            }
          : m,
      ),
    };
    const glb = await sceneToGlb(withShapes);
    const report = await validate(glb);
    expect(report.issues.messages.filter((m) => m.severity <= 1)).toEqual([]);
    const back = await reload(glb);
    const triangles = back.meshes.reduce((n, m) => n + m.indices.length / 3, 0);
    const before = showcase.meshes.reduce((n, m) => n + m.indices.length / 3, 0);
    // A 48-segment sphere and capsule add thousands of triangles.
    expect(triangles - before).toBeGreaterThan(2000);
  });

  it('round-trips meshes and instances to the same world-space triangles', async () => {
    const back = await reload(await sceneToGlb(showcase));
    expect(back.instances).toHaveLength(2);
    expect(back.instances.map((i) => i.name)).toEqual(['left', 'mirrored']);
    expect(back.meshes).toHaveLength(1);
    expect(worldTriangles(back)).toEqual(worldTriangles(showcase));
    expect(determinant3(back.instances[1]!.worldFromObject)).toBeLessThan(0);
    const mesh = back.meshes[0]!;
    expect(mesh.uvs1).toBeDefined();
    expect(mesh.tangents).toBeDefined();
  });

  it('round-trips every material kind with its parameters', async () => {
    const back = await reload(await sceneToGlb(showcase));
    const byName = new Map(back.materials.map((m) => [m.name, m as MetallicRoughnessMaterial]));
    const tex = (ref: { texture: number } | undefined) => back.textures![ref!.texture]!;

    const masked = byName.get('masked')!;
    expect(masked).toMatchObject({ metallic: 0, roughness: 1, alphaMode: 'mask', alphaCutoff: 0.3, doubleSided: true });
    close(masked.baseColor, [0.8, 0.7, 0.6]);
    expect([...tex(masked.baseColorTexture).rgba]).toEqual([...showcase.textures![0]!.rgba]);

    const all = byName.get('everything')!;
    const want = showcase.materials[1] as MetallicRoughnessMaterial;
    expect(all).toMatchObject({ opacity: 0.75, metallic: 0.25, roughness: 0.5, ior: 1.25, specular: 0.5, transmission: 0.5, thickness: 0.5, attenuationDistance: 2, alphaMode: 'blend', doubleSided: false });
    close(all.baseColor, want.baseColor);
    close(all.specularColor, want.specularColor);
    close(all.attenuationColor, want.attenuationColor);
    close(all.emission, want.emission);
    expect(all.baseColorTexture).toEqual(want.baseColorTexture);
    expect(all.transmissionTexture!.transform).toEqual(want.transmissionTexture!.transform);
    expect(all.normalTexture!.scale).toBe(0.5);
    expect([...tex(all.normalTexture).rgba]).toEqual([128, 128, 255, 255]);
    expect(tex(all.metallicRoughnessTexture).encoding).toBe('linear');
    expect([...tex(all.specularTexture).rgba]).toEqual([10, 20, 30, 40]);

    const glass = byName.get('glass')!;
    expect(glass).toMatchObject({ transmission: 1, ior: 1.5, roughness: 0.125, metallic: 0, attenuationDistance: 4 });
    expect(glass.thickness).toBeGreaterThan(0);
    close(glass.baseColor, [0.75, 1, 0.75]);
    close(glass.attenuationColor, [0.5, 0.5, 1]);

    const glow = byName.get('glow')!;
    close(glow.baseColor, [0, 0, 0]);
    close(glow.emission, [12, 6, 3]);
    expect([...tex(glow.emissionTexture).rgba]).toEqual([...showcase.textures![0]!.rgba]);
    // The panorama sky goes out as an ordinary emissive texture.
    expect(byName.get('sky')!.emissionTexture).toBeDefined();
  });

  it('round-trips punctual lights and the camera', async () => {
    const back = await reload(await sceneToGlb(showcase));
    const [bulb, spot, sun] = back.lights!;
    expect(bulb).toMatchObject({ kind: 'point', name: 'bulb', intensity: 20, range: Infinity });
    close((bulb as { position: Vec3 }).position, [1, 2, 3]);
    expect(spot).toMatchObject({ kind: 'spot', intensity: 50, range: 12 });
    if (spot?.kind !== 'spot' || sun?.kind !== 'directional') throw new Error('light kinds changed');
    close(spot.position, [0, 5, 0]);
    close(spot.direction, [0, -1, 0]);
    expect(spot.innerConeAngle).toBeCloseTo(0.25, 6);
    expect(spot.outerConeAngle).toBeCloseTo(0.5, 6);
    close(sun.direction, [0.6, -0.8, 0]);
    expect(sun.irradiance).toBe(3);
    close(back.camera.position, [0.5, 0.5, 3]);
    close(back.camera.forward, [0, -0.6, -0.8]);
    expect(back.camera.vfovDegrees).toBeCloseTo(50, 4);
    // Lights came along, so no default sky on the way back.
    expect(back.environment).toBeUndefined();
  });

  it('scales everything to metres at the root when the scene knows its unit', async () => {
    const mm: Scene = { ...showcase, metersPerUnit: 0.001 };
    const back = await reload(await sceneToGlb(mm));
    const corners = worldCorners(back), original = worldCorners(showcase);
    expect(corners).toHaveLength(original.length);
    corners.forEach((p, i) => close(p, original[i]!.map((x) => x * 0.001), 7));
    close((back.lights![0] as { position: Vec3 }).position, [0.001, 0.002, 0.003], 7);
    close(back.camera.position, [0.0005, 0.0005, 0.003], 7);
  });

  it('builds camera rotations that map local axes to the given basis', () => {
    const q = quaternionFromBasis([0, 0, 1], [0, 1, 0], [-1, 0, 0]);
    // Rotating local −z (the glTF camera's view direction) must give world +x.
    const m: Mat4 = fromTrs([0, 0, 0], q, [1, 1, 1]);
    close(transformPoint(m, [0, 0, -1]), [1, 0, 0], 6);
  });
});

const FREEDOOM1 = '/usr/share/games/doom/freedoom1.wad';

describe.skipIf(!existsSync(FREEDOOM1))('GLB export of freedoom1 E1M1', () => {
  it('validates with no errors and round-trips through the glTF loader', async () => {
    const { scene } = loadDoomMap(new WadStack([readWad(readFileSync(FREEDOOM1), 'freedoom1.wad')]), 'E1M1');
    const glb = await sceneToGlb(scene);
    const report = await validate(glb);
    expect(report.issues.numErrors, JSON.stringify(report.issues.messages.slice(0, 5))).toBe(0);
    const back = await reload(glb);
    // Every texture of a material on a surface goes out; the sprites' other rotations (there for the
    // billboard animator) are on no surface of this snapshot.
    const shown = new Set(scene.instances.flatMap((i) => (i.material !== undefined ? [i.material] : [...scene.meshes[i.mesh]!.materialIds])));
    const textures = new Set([...shown].flatMap((m) => {
      const material = scene.materials[m]!;
      return [material.emissionTexture, material.kind === 'diffuse' ? material.albedoTexture : undefined].flatMap((r) => (r ? [r.texture] : []));
    }));
    expect(textures.size).toBeLessThan(scene.textures!.length);
    expect(back.textures!.length).toBeGreaterThanOrEqual(textures.size);
    expect(back.materials.some((m) => m.emission.some((e) => e > 0))).toBe(true);
    // Each sprite goes out with the picture it shows (its instance's material), not its quad's.
    const sprites = new Set(scene.instances.filter((i) => i.material !== undefined).map((i) => scene.materials[i.material!]!.name));
    const names = new Set(back.materials.map((m) => m.name));
    expect(sprites.size).toBeGreaterThan(10);
    expect([...sprites].filter((n) => !names.has(n))).toEqual([]);
    expect(back.materials.some((m) => m.alphaMode === 'mask')).toBe(true);
    const count = (s: Scene) => s.instances.reduce((n, i) => n + s.meshes[i.mesh]!.indices.length / 3, 0);
    expect(count(back)).toBe(count(scene));
    // Doom units to metres: the map spans a few hundred metres, not kilometres.
    expect(Math.max(...worldCorners(back).map((p) => Math.abs(p[0])))).toBeLessThan(500);
  });
});
