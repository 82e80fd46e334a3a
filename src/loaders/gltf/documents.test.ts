/**
 * The glTF loader over small documents built here with glTF-Transform, each holding one feature
 * with a known answer.
 */
import { Document, WebIO, type Extension } from '@gltf-transform/core';
import { EXTMeshGPUInstancing, EXTMeshoptCompression, KHRDracoMeshCompression, KHRLightsPunctual, KHRMaterialsDispersion, KHRMaterialsEmissiveStrength, KHRMaterialsIOR, KHRMaterialsSpecular, KHRMaterialsTransmission, KHRMaterialsVolume, KHRMeshQuantization, KHRTextureTransform } from '@gltf-transform/extensions';
import { createEncoderModule } from 'draco3dgltf';
import { MeshoptEncoder } from 'meshoptimizer/encoder';
import { describe, expect, it } from 'vitest';
import { LanternError } from '../../errors.ts';
import { encodePng } from '../../image/png.ts';
import { determinant3, transformPoint } from '../../math/mat4.ts';
import { cross } from '../../math/vec3.ts';
import type { MetallicRoughnessMaterial, Scene } from '../../scene/types.ts';
import { loadGltf } from './index.ts';

type ExtensionClass = typeof Extension;

/** Writes `doc` as .gltf + resources and loads it back through the resolver. */
async function load(doc: Document, extensions: ExtensionClass[] = [], drop: string[] = []): Promise<Scene> {
  const io = new WebIO().registerExtensions(extensions).registerDependencies({ 'meshopt.encoder': MeshoptEncoder });
  await MeshoptEncoder.ready;
  const { json, resources } = await io.writeJSON(doc);
  return loadGltf({ name: 'test.gltf', bytes: new TextEncoder().encode(JSON.stringify(json)) }, async (uri) => (drop.includes(uri) ? undefined : resources[uri]));
}

/** A document with one mesh of one primitive (triangle list unless `mode` says otherwise). */
function oneMesh(positions: number[], options: { indices?: number[]; mode?: number; normals?: number[]; uvs?: number[] } = {}) {
  const doc = new Document();
  const buffer = doc.createBuffer();
  const prim = doc.createPrimitive().setAttribute('POSITION', doc.createAccessor().setType('VEC3').setArray(new Float32Array(positions)).setBuffer(buffer));
  if (options.indices) prim.setIndices(doc.createAccessor().setType('SCALAR').setArray(new Uint32Array(options.indices)).setBuffer(buffer));
  if (options.normals) prim.setAttribute('NORMAL', doc.createAccessor().setType('VEC3').setArray(new Float32Array(options.normals)).setBuffer(buffer));
  if (options.uvs) prim.setAttribute('TEXCOORD_0', doc.createAccessor().setType('VEC2').setArray(new Float32Array(options.uvs)).setBuffer(buffer));
  if (options.mode !== undefined) prim.setMode(options.mode as 4);
  const mesh = doc.createMesh('m').addPrimitive(prim);
  const node = doc.createNode('n').setMesh(mesh);
  doc.createScene().addChild(node);
  return { doc, buffer, prim, mesh, node };
}

const QUAD = [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0];
const QUAD_INDICES = [0, 1, 2, 0, 2, 3];
const mr = (s: Scene, i = 0) => s.materials[i] as MetallicRoughnessMaterial;
const geometricNormal = (p: ArrayLike<number>, i: ArrayLike<number>, t: number) => {
  const v = (k: number) => [p[i[t * 3 + k]! * 3]!, p[i[t * 3 + k]! * 3 + 1]!, p[i[t * 3 + k]! * 3 + 2]!] as const;
  const [a, b, c] = [v(0), v(1), v(2)];
  return cross([b[0] - a[0], b[1] - a[1], b[2] - a[2]], [c[0] - a[0], c[1] - a[1], c[2] - a[2]]);
};

describe('glTF loader on built documents', () => {
  it('decodes KHR_mesh_quantization’s normalized integer attributes', async () => {
    const doc = new Document();
    doc.createExtension(KHRMeshQuantization).setRequired(true);
    const buffer = doc.createBuffer();
    const prim = doc
      .createPrimitive()
      .setAttribute('POSITION', doc.createAccessor().setType('VEC3').setArray(new Int16Array([0, 0, 0, 32767, 0, 0, 0, -32767, 0])).setNormalized(true).setBuffer(buffer))
      .setAttribute('NORMAL', doc.createAccessor().setType('VEC3').setArray(new Int8Array([0, 0, 127, 0, 0, 127, 0, 0, 127])).setNormalized(true).setBuffer(buffer))
      .setAttribute('TEXCOORD_0', doc.createAccessor().setType('VEC2').setArray(new Uint16Array([0, 0, 65535, 0, 0, 32768])).setNormalized(true).setBuffer(buffer));
    doc.createScene().addChild(doc.createNode().setMesh(doc.createMesh().addPrimitive(prim)).setScale([2, 2, 2]));
    const s = await load(doc, [KHRMeshQuantization]);
    const m = s.meshes[0]!;
    expect([...m.positions]).toEqual([0, 0, 0, 1, 0, 0, 0, -1, 0]);
    expect([...m.normals!]).toEqual([0, 0, 1, 0, 0, 1, 0, 0, 1]);
    expect(m.uvs![2]).toBe(1);
    expect(m.uvs![5]).toBeCloseTo(0.5, 4);
    expect(transformPoint(s.instances[0]!.worldFromObject, [1, 0, 0])).toEqual([2, 0, 0]);
  });

  it('turns strips and fans into triangles that keep one winding', async () => {
    // A strip over a 2×1 row of unit quads in the z = 0 plane, top and bottom vertices alternating,
    // its first triangle counter-clockwise seen from +z: four triangles, all facing +z.
    const strip = oneMesh([0, 1, 0, 0, 0, 0, 1, 1, 0, 1, 0, 0, 2, 1, 0, 2, 0, 0], { mode: 5 });
    const fan = oneMesh([0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, -1, 1, 0], { mode: 6 });
    for (const [doc, count] of [[strip.doc, 4], [fan.doc, 3]] as const) {
      const m = (await load(doc)).meshes[0]!;
      expect(m.indices.length / 3).toBe(count);
      for (let t = 0; t < count; t++) expect(geometricNormal(m.positions, m.indices, t)[2]).toBeGreaterThan(0);
    }
  });

  it('reads buffers and images from data: URIs without asking the resolver', async () => {
    const positions = new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0]);
    const b64 = (bytes: Uint8Array) => btoa(String.fromCharCode(...bytes));
    const png = encodePng(1, 1, new Uint8Array([200, 10, 20, 255]));
    const json = {
      asset: { version: '2.0' },
      buffers: [{ byteLength: 36, uri: `data:application/octet-stream;base64,${b64(new Uint8Array(positions.buffer))}` }],
      bufferViews: [{ buffer: 0, byteLength: 36 }],
      accessors: [{ bufferView: 0, componentType: 5126, count: 3, type: 'VEC3', min: [0, 0, 0], max: [1, 1, 0] }],
      images: [{ uri: `data:image/png;base64,${b64(png)}` }],
      textures: [{ source: 0 }],
      materials: [{ pbrMetallicRoughness: { baseColorTexture: { index: 0 } } }],
      meshes: [{ primitives: [{ attributes: { POSITION: 0 }, material: 0 }] }],
      nodes: [{ mesh: 0 }],
      scenes: [{ nodes: [0] }],
    };
    const asked: string[] = [];
    const s = await loadGltf({ name: 'inline.gltf', bytes: new TextEncoder().encode(JSON.stringify(json)) }, async (uri) => {
      asked.push(uri);
      return undefined;
    });
    expect(asked).toEqual([]);
    expect([...s.meshes[0]!.positions]).toEqual([...positions]);
    expect([...s.textures![mr(s).baseColorTexture!.texture]!.rgba]).toEqual([200, 10, 20, 255]);
  });

  it('keeps KHR_texture_transform and its texCoord override on the TextureRef', async () => {
    const { doc } = oneMesh(QUAD, { indices: QUAD_INDICES, uvs: [0, 0, 1, 0, 1, 1, 0, 1] });
    const ext = doc.createExtension(KHRTextureTransform);
    const texture = doc.createTexture('t').setMimeType('image/png').setImage(encodePng(1, 1, new Uint8Array([1, 2, 3, 255])));
    const material = doc.createMaterial('m').setBaseColorTexture(texture).setEmissiveTexture(texture).setEmissiveFactor([1, 1, 1]);
    material.getBaseColorTextureInfo()!.setExtension('KHR_texture_transform', ext.createTransform().setOffset([0.25, 0.5]).setRotation(0.3).setScale([2, 3]).setTexCoord(1));
    doc.getRoot().listMeshes()[0]!.listPrimitives()[0]!.setMaterial(material);
    const s = await load(doc, [KHRTextureTransform]);
    expect(mr(s).baseColorTexture).toEqual({ texture: 0, texCoord: 1, transform: { offset: [0.25, 0.5], rotation: 0.3, scale: [2, 3] } });
    // The same image, the same encoding, no transform: one texture, a bare ref.
    expect(mr(s).emissionTexture).toEqual({ texture: 0 });
  });

  it('gives one image used as colour and as data two textures, sRGB and linear', async () => {
    const { doc, prim } = oneMesh(QUAD, { indices: QUAD_INDICES, uvs: [0, 0, 1, 0, 1, 1, 0, 1] });
    const texture = doc.createTexture('both').setMimeType('image/png').setImage(encodePng(1, 1, new Uint8Array([9, 9, 9, 255])));
    prim.setMaterial(doc.createMaterial().setBaseColorTexture(texture).setMetallicRoughnessTexture(texture));
    const s = await load(doc);
    const m = mr(s);
    expect(s.textures!.map((t) => t.encoding)).toEqual(['srgb', 'linear']);
    expect(s.textures![m.baseColorTexture!.texture]!.encoding).toBe('srgb');
    expect(s.textures![m.metallicRoughnessTexture!.texture]!.encoding).toBe('linear');
  });

  it('maps the material extensions one to one', async () => {
    const { doc, prim } = oneMesh(QUAD, { indices: QUAD_INDICES });
    const mat = doc.createMaterial('glass').setBaseColorFactor([0.5, 0.6, 0.7, 0.8]).setMetallicFactor(0.1).setRoughnessFactor(0.2).setEmissiveFactor([1, 0.5, 0]).setAlphaMode('BLEND').setDoubleSided(true);
    mat.setExtension('KHR_materials_emissive_strength', doc.createExtension(KHRMaterialsEmissiveStrength).createEmissiveStrength().setEmissiveStrength(4));
    mat.setExtension('KHR_materials_ior', doc.createExtension(KHRMaterialsIOR).createIOR().setIOR(1.33));
    mat.setExtension('KHR_materials_specular', doc.createExtension(KHRMaterialsSpecular).createSpecular().setSpecularFactor(0.7).setSpecularColorFactor([1, 0.9, 0.8]));
    mat.setExtension('KHR_materials_transmission', doc.createExtension(KHRMaterialsTransmission).createTransmission().setTransmissionFactor(0.9));
    mat.setExtension('KHR_materials_volume', doc.createExtension(KHRMaterialsVolume).createVolume().setThicknessFactor(0.05).setAttenuationDistance(2).setAttenuationColor([0.9, 0.5, 0.1]));
    prim.setMaterial(mat);
    const s = await load(doc, [KHRMaterialsEmissiveStrength, KHRMaterialsIOR, KHRMaterialsSpecular, KHRMaterialsTransmission, KHRMaterialsVolume]);
    const m = mr(s);
    expect(m).toMatchObject({ kind: 'metallic-roughness', name: 'glass', opacity: 0.8, metallic: 0.1, roughness: 0.2, emission: [4, 2, 0], ior: 1.33, specular: 0.7, transmission: 0.9, thickness: 0.05, attenuationDistance: 2, alphaMode: 'blend', doubleSided: true });
    m.baseColor.forEach((c, i) => expect(c).toBeCloseTo([0.5, 0.6, 0.7][i]!, 6));
    m.specularColor.forEach((c, i) => expect(c).toBeCloseTo([1, 0.9, 0.8][i]!, 6));
    m.attenuationColor.forEach((c, i) => expect(c).toBeCloseTo([0.9, 0.5, 0.1][i]!, 6));
    // The material emits, so the model is lit and no sky is added.
    expect(s.environment).toBeUndefined();
  });

  it('reads KHR_materials_dispersion (20/V_d) as an Abbe number, and none when it is 0', async () => {
    const { doc, prim } = oneMesh(QUAD, { indices: QUAD_INDICES });
    const mat = doc.createMaterial('flint');
    mat.setExtension('KHR_materials_dispersion', doc.createExtension(KHRMaterialsDispersion).createDispersion().setDispersion(0.5));
    prim.setMaterial(mat);
    expect(mr(await load(doc, [KHRMaterialsDispersion])).dispersion).toEqual({ kind: 'abbe', abbeNumber: 40 });
    mat.setExtension('KHR_materials_dispersion', doc.createExtension(KHRMaterialsDispersion).createDispersion().setDispersion(0));
    expect(mr(await load(doc, [KHRMaterialsDispersion])).dispersion).toBeUndefined();
  });

  it('gives a primitive without a material the spec’s default material', async () => {
    const s = await load(oneMesh(QUAD, { indices: QUAD_INDICES }).doc);
    expect(mr(s)).toMatchObject({ baseColor: [1, 1, 1], opacity: 1, metallic: 1, roughness: 1, doubleSided: false });
    expect(mr(s).alphaMode ?? 'opaque').toBe('opaque');
  });

  it('places punctual lights in world space and lights the scene with them alone', async () => {
    const { doc, node } = oneMesh(QUAD, { indices: QUAD_INDICES });
    const ext = doc.createExtension(KHRLightsPunctual);
    const spot = ext.createLight('spot').setType('spot').setColor([1, 0.5, 0.25]).setIntensity(30).setRange(10).setInnerConeAngle(0.2).setOuterConeAngle(0.5);
    const point = ext.createLight('bulb').setType('point').setIntensity(5);
    const sun = ext.createLight('sun').setType('directional').setIntensity(3);
    // A quarter turn about +x takes the light's −z to world +y; the parent moves it by (1, 2, 3).
    const s45 = Math.SQRT1_2;
    const holder = doc.createNode('spot').setRotation([s45, 0, 0, s45]).setExtension('KHR_lights_punctual', spot);
    node.addChild(holder);
    node.setTranslation([1, 2, 3]);
    doc.getRoot().listScenes()[0]!.addChild(doc.createNode('bulb').setTranslation([0, 5, 0]).setExtension('KHR_lights_punctual', point));
    doc.getRoot().listScenes()[0]!.addChild(doc.createNode('sun').setExtension('KHR_lights_punctual', sun));
    const s = await load(doc, [KHRLightsPunctual]);
    const [l, b, d] = s.lights!;
    expect(l).toMatchObject({ kind: 'spot', name: 'spot', position: [1, 2, 3], color: [1, 0.5, 0.25], intensity: 30, range: 10 });
    if (l?.kind !== 'spot') throw new Error('expected a spot light');
    expect(l.innerConeAngle).toBeCloseTo(0.2, 6);
    expect(l.outerConeAngle).toBeCloseTo(0.5, 6);
    expect(l.direction[1]).toBeCloseTo(1, 6);
    expect(b).toMatchObject({ kind: 'point', position: [0, 5, 0], intensity: 5, range: Infinity });
    expect(d).toMatchObject({ kind: 'directional', direction: [0, 0, -1], irradiance: 3 });
    expect(s.environment).toBeUndefined();
    expect(s.warnings).toEqual([]);
  });

  /**
   * A Cornell box in metres (0.55 m a side, open at the front, +z), its ceiling light 0.13 × 0.105 m of
   * the original measurements' radiance (17, 12, 4): emissiveFactor × KHR_materials_emissive_strength.
   */
  function openCornellBox(strength: number): Document {
    const doc = new Document();
    const buffer = doc.createBuffer();
    const white = doc.createMaterial('white').setBaseColorFactor([0.73, 0.73, 0.73, 1]).setMetallicFactor(0);
    const light = doc.createMaterial('light').setBaseColorFactor([0.78, 0.78, 0.78, 1]).setMetallicFactor(0).setEmissiveFactor([1, 12 / 17, 4 / 17]);
    light.setExtension('KHR_materials_emissive_strength', doc.createExtension(KHRMaterialsEmissiveStrength).createEmissiveStrength().setEmissiveStrength(strength));
    const s = 0.55, lx = 0.065, lz = 0.0525, ly = s - 0.001;
    const quad = (corners: number[], material: typeof white) =>
      doc
        .createPrimitive()
        .setAttribute('POSITION', doc.createAccessor().setType('VEC3').setArray(new Float32Array(corners)).setBuffer(buffer))
        .setIndices(doc.createAccessor().setType('SCALAR').setArray(new Uint32Array(QUAD_INDICES)).setBuffer(buffer))
        .setMaterial(material);
    const mesh = doc
      .createMesh('box')
      .addPrimitive(quad([0, 0, 0, s, 0, 0, s, 0, -s, 0, 0, -s], white)) // floor
      .addPrimitive(quad([0, s, 0, 0, s, -s, s, s, -s, s, s, 0], white)) // ceiling
      .addPrimitive(quad([0, 0, -s, s, 0, -s, s, s, -s, 0, s, -s], white)) // back
      .addPrimitive(quad([0, 0, 0, 0, 0, -s, 0, s, -s, 0, s, 0], white)) // left
      .addPrimitive(quad([s, 0, 0, s, s, 0, s, s, -s, s, 0, -s], white)) // right
      .addPrimitive(quad([s / 2 - lx, ly, -s / 2 + lz, s / 2 - lx, ly, -s / 2 - lz, s / 2 + lx, ly, -s / 2 - lz, s / 2 + lx, ly, -s / 2 + lz], light)); // light, facing down
    doc.createScene().addChild(doc.createNode('box').setMesh(mesh));
    return doc;
  }

  it('lights a Cornell box open at the front by its ceiling light alone: no sky', async () => {
    const s = await load(openCornellBox(17), [KHRMaterialsEmissiveStrength]);
    expect(s.environment).toBeUndefined();
    expect(s.camera.exposureStops ?? 0).toBe(0);
    expect(s.lightingNote).toMatch(/^its own lights light it \(\d+ % of the light of a default sky\); no sky is added$/);
  });

  it('gives a model whose only emitter is tiny and dim the default sky, and says why', async () => {
    // The same box with a light 1/1000 as strong: a pilot lamp, not a light.
    const s = await load(openCornellBox(0.017), [KHRMaterialsEmissiveStrength]);
    expect(s.environment).toMatchObject({ kind: 'sky' });
    expect(s.lightingNote).toMatch(/^its emitters give 0\.\d+ % of the light of a default sky; a default sky lights it$/);
    expect(s.warnings).toEqual([]);
  });

  it('composes the hierarchy: world = parent · child, applied to a known vertex', async () => {
    const { doc, node } = oneMesh(QUAD, { indices: QUAD_INDICES });
    const s45 = Math.SQRT1_2;
    // child: a quarter turn about +z; parent: scale 2 then move by (10, 0, 0).
    const parent = doc.createNode('parent').setTranslation([10, 0, 0]).setScale([2, 2, 2]);
    doc.getRoot().listScenes()[0]!.removeChild(node);
    doc.getRoot().listScenes()[0]!.addChild(parent);
    parent.addChild(node.setRotation([0, 0, s45, s45]));
    const s = await load(doc);
    const p = transformPoint(s.instances[0]!.worldFromObject, [1, 0, 0]);
    expect(p[0]).toBeCloseTo(10, 6);
    expect(p[1]).toBeCloseTo(2, 6);
    expect(p[2]).toBeCloseTo(0, 6);
    // The id is the node's index in the file (parent was created after the mesh node: index 1 vs 0).
    expect(s.instances[0]!.id).toBe(doc.getRoot().listNodes().indexOf(node));
  });

  it('keeps a mirroring node’s matrix as is (negative determinant), mesh untouched', async () => {
    const { doc, node } = oneMesh(QUAD, { indices: QUAD_INDICES });
    node.setScale([-1, 1, 1]);
    const s = await load(doc);
    const m = s.instances[0]!.worldFromObject;
    expect(determinant3(m)).toBeLessThan(0);
    expect(transformPoint(m, [1, 1, 0])).toEqual([-1, 1, 0]);
    expect([...s.meshes[0]!.indices]).toEqual(QUAD_INDICES);
  });

  it('leaves normals out when the file has none (flat), and flat-shades only the primitives without them', async () => {
    const plain = await load(oneMesh(QUAD, { indices: QUAD_INDICES }).doc);
    expect(plain.meshes[0]!.normals).toBeUndefined();

    const { doc, mesh, buffer } = oneMesh(QUAD, { indices: QUAD_INDICES, normals: [0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1] });
    // A second primitive, a triangle in the x = 0 plane facing +x, without normals.
    mesh.addPrimitive(doc.createPrimitive().setAttribute('POSITION', doc.createAccessor().setType('VEC3').setArray(new Float32Array([0, 0, 0, 0, 1, 0, 0, 0, 1])).setBuffer(buffer)));
    const m = (await load(doc)).meshes[0]!;
    expect(m.normals!.length).toBe(m.positions.length);
    expect([...m.normals!.slice(-3)]).toEqual([1, 0, 0]);
    expect(m.indices.length).toBe(9);
  });

  it('generates tangents whose bitangent cross(n, t)·w points where the normal map’s green does (−v, image up)', async () => {
    // A quad facing +z, uv (0, 0) at its top-left: image up (−v) is world +y, image right (+u) is +x.
    const { doc, prim } = oneMesh(QUAD, { indices: QUAD_INDICES, normals: [0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1], uvs: [0, 1, 1, 1, 1, 0, 0, 0] });
    const normalMap = doc.createTexture('n').setMimeType('image/png').setImage(encodePng(1, 1, new Uint8Array([128, 128, 255, 255])));
    prim.setMaterial(doc.createMaterial().setNormalTexture(normalMap));
    const m = (await load(doc)).meshes[0]!;
    for (let v = 0; v < m.positions.length / 3; v++) {
      const t = [m.tangents![v * 4]!, m.tangents![v * 4 + 1]!, m.tangents![v * 4 + 2]!] as const;
      expect(t[0]).toBeCloseTo(1, 5);
      const b = cross([0, 0, 1], t).map((x) => x * m.tangents![v * 4 + 3]!);
      expect(b[1]).toBeCloseTo(1, 5);
    }
  });

  it('places one instance per row of EXT_mesh_gpu_instancing, inside the node’s transform', async () => {
    const { doc, node, buffer } = oneMesh(QUAD, { indices: QUAD_INDICES });
    node.setTranslation([0, 0, 10]);
    const batch = doc.createExtension(EXTMeshGPUInstancing).createInstancedMesh()
      .setAttribute('TRANSLATION', doc.createAccessor().setType('VEC3').setArray(new Float32Array([1, 0, 0, 2, 0, 0, 3, 0, 0])).setBuffer(buffer));
    node.setExtension('EXT_mesh_gpu_instancing', batch);
    const s = await load(doc, [EXTMeshGPUInstancing]);
    expect(s.meshes).toHaveLength(1);
    expect(s.instances.map((i) => transformPoint(i.worldFromObject, [0, 0, 0]))).toEqual([[1, 0, 10], [2, 0, 10], [3, 0, 10]]);
    expect(new Set(s.instances.map((i) => i.id)).size).toBe(3);
  });

  it('reads EXT_meshopt_compression', async () => {
    const { doc } = oneMesh(QUAD, { indices: QUAD_INDICES, normals: [0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1] });
    doc.createExtension(EXTMeshoptCompression).setRequired(true).setEncoderOptions({ method: EXTMeshoptCompression.EncoderMethod.FILTER });
    const s = await load(doc, [EXTMeshoptCompression]);
    expect([...s.meshes[0]!.positions]).toEqual(QUAD);
    expect([...s.meshes[0]!.indices]).toEqual(QUAD_INDICES);
  });

  it('skips points and lines with one warning, and frames a camera when the file has none', async () => {
    const { doc, mesh, buffer } = oneMesh(QUAD, { indices: QUAD_INDICES });
    for (const mode of [0, 1]) mesh.addPrimitive(doc.createPrimitive().setMode(mode as 0).setAttribute('POSITION', doc.createAccessor().setType('VEC3').setArray(new Float32Array([0, 0, 0, 1, 1, 1])).setBuffer(buffer)));
    const s = await load(doc);
    expect(s.meshes[0]!.indices.length).toBe(6);
    expect(s.warnings!.filter((w) => w.includes('points and lines'))).toHaveLength(1);
    // No light: the default sky, said as information apart from the warnings.
    expect(s.lightingNote).toBe('the model has no light of its own; a default sky lights it');
    expect(s.warnings!.some((w) => /sky/.test(w))).toBe(false);
    // Framed: the camera looks at the quad's centre from outside it.
    const c = s.camera;
    const toCentre = [0.5 - c.position[0], 0.5 - c.position[1], 0 - c.position[2]];
    const along = toCentre[0]! * c.forward[0] + toCentre[1]! * c.forward[1] + toCentre[2]! * c.forward[2];
    expect(along / Math.hypot(...toCentre) / Math.hypot(...c.forward)).toBeCloseTo(1, 6);
  });

  it('shows an orthographic camera as a perspective one, with a warning', async () => {
    const { doc } = oneMesh(QUAD, { indices: QUAD_INDICES });
    const camera = doc.createCamera('top').setType('orthographic').setXMag(2).setYMag(2).setZNear(0.1).setZFar(100);
    doc.getRoot().listScenes()[0]!.addChild(doc.createNode('cam').setCamera(camera).setTranslation([0, 0, 5]));
    const s = await load(doc);
    expect(s.warnings!.some((w) => w.includes('orthographic'))).toBe(true);
    expect(s.camera.forward).toEqual([0, 0, -1]);
    // ymag 2 at the old position fills the stand-in's vertical half-angle.
    const back = s.camera.position[2] - 5;
    expect(2 / back).toBeCloseTo(Math.tan(((s.camera.vfovDegrees / 2) * Math.PI) / 180), 6);
  });

  it('drops only the primitives whose buffer is missing, naming the file once', async () => {
    const { doc, mesh } = oneMesh(QUAD, { indices: QUAD_INDICES });
    const other = doc.createBuffer('other').setURI('other.bin');
    for (let k = 0; k < 2; k++) {
      mesh.addPrimitive(doc.createPrimitive().setAttribute('POSITION', doc.createAccessor().setType('VEC3').setArray(new Float32Array([0, 0, 1, 1, 0, 1, 0, 1, 1])).setBuffer(other)));
    }
    const s = await load(doc, [], ['other.bin']);
    expect(s.meshes[0]!.indices.length).toBe(6);
    expect(s.warnings!.filter((w) => w.includes('other.bin'))).toHaveLength(1);
  });

  it('names a missing image once however many materials use it', async () => {
    const { doc, mesh, buffer } = oneMesh(QUAD, { indices: QUAD_INDICES, uvs: [0, 0, 1, 0, 1, 1, 0, 1] });
    const texture = doc.createTexture('gone').setMimeType('image/png').setImage(encodePng(1, 1, new Uint8Array(4))).setURI('gone.png');
    mesh.listPrimitives()[0]!.setMaterial(doc.createMaterial('a').setBaseColorTexture(texture));
    mesh.addPrimitive(doc.createPrimitive().setAttribute('POSITION', doc.createAccessor().setType('VEC3').setArray(new Float32Array(QUAD.slice(0, 9))).setBuffer(buffer)).setMaterial(doc.createMaterial('b').setBaseColorTexture(texture).setEmissiveTexture(texture)));
    const s = await load(doc, [], ['gone.png']);
    expect(s.warnings!.filter((w) => w.includes('gone.png'))).toEqual(['gone.png is missing: textures that use it are replaced by neutral ones']);
    expect(s.materials).toHaveLength(2);
  });

  it('refuses bytes that are not glTF with a one-line LanternError', async () => {
    for (const bytes of [new Uint8Array([1, 2, 3, 4, 5]), new TextEncoder().encode('{"meshes": []}'), new TextEncoder().encode('solid cube\nfacet normal 0 0 1')]) {
      const error = await loadGltf({ name: 'thing.gltf', bytes }, async () => undefined).catch((e: unknown) => e);
      expect(error).toBeInstanceOf(LanternError);
      expect((error as LanternError).userMessage).not.toContain('\n');
      expect((error as LanternError).message).toContain('thing.gltf is not a glTF file');
    }
  });

  it('reads KHR_draco_mesh_compression', async () => {
    const { doc } = oneMesh(QUAD, { indices: QUAD_INDICES, normals: [0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1] });
    doc.createExtension(KHRDracoMeshCompression).setRequired(true).setEncoderOptions({ method: KHRDracoMeshCompression.EncoderMethod.SEQUENTIAL, quantizationBits: { POSITION: 14 } });
    const io = new WebIO().registerExtensions([KHRDracoMeshCompression]).registerDependencies({ 'draco3d.encoder': await createEncoderModule() });
    const { json, resources } = await io.writeJSON(doc);
    expect(json.extensionsRequired).toContain('KHR_draco_mesh_compression');
    const s = await loadGltf({ name: 'draco.gltf', bytes: new TextEncoder().encode(JSON.stringify(json)) }, async (uri) => resources[uri]);
    const m = s.meshes[0]!;
    // Sequential encoding keeps vertex order; 14-bit quantization keeps positions within 1e-4 here.
    [...m.positions].forEach((x, i) => expect(x).toBeCloseTo(QUAD[i]!, 3));
    expect([...m.indices]).toEqual(QUAD_INDICES);
  });
});

