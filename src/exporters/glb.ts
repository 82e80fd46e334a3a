/**
 * Scene → binary glTF 2.0 (GLB), so a scene (a Doom map above all) opens in Blender or any glTF
 * viewer. Written with glTF-Transform (the document model and its GLB writer); textures embedded as
 * PNG with nearest filtering and repeat wrapping; emission as emissiveFactor × emissiveTexture with
 * KHR_materials_emissive_strength for radiance above 1; alpha masks as alphaMode MASK (cutoff 0.5);
 * the camera as a perspective camera node. Pure: returns bytes.
 *
 * Two things glTF cannot say: a sky panorama (emission looked up by view direction) is exported as
 * an ordinary emissive texture on the surface's uvs, and the torch is left out (no camera-attached
 * lights in glTF). Positions are scaled to metres when the scene knows its unit.
 */
import { Document, WebIO, type Material as GltfMaterial, type Texture as GltfTexture } from '@gltf-transform/core';
import { KHRMaterialsEmissiveStrength } from '@gltf-transform/extensions';
import { encodePng } from '../image/png.ts';
import { cross, normalize, type Vec3 } from '../math/vec3.ts';
import type { Scene } from '../scene/types.ts';

/** glTF sampler constants (WebGL enums). */
const NEAREST = 9728;
const REPEAT = 10497;

export interface GlbOptions {
  /** Metres per scene unit; defaults to the scene's own, else 1. */
  readonly metersPerUnit?: number;
  /** Written into asset.generator. */
  readonly generator?: string;
}

export async function sceneToGlb(scene: Scene, options: GlbOptions = {}): Promise<Uint8Array> {
  const scale = options.metersPerUnit ?? scene.metersPerUnit ?? 1;
  const doc = new Document();
  doc.getRoot().getAsset().generator = options.generator ?? 'Lantern';
  const emissiveStrength = doc.createExtension(KHRMaterialsEmissiveStrength);
  const buffer = doc.createBuffer();

  const textures: GltfTexture[] = (scene.textures ?? []).map((t) =>
    doc.createTexture(t.name).setMimeType('image/png').setImage(encodePng(t.width, t.height, t.rgba)).setURI(`${t.name}.png`),
  );

  const materials: GltfMaterial[] = scene.materials.map((m) => {
    const mat = doc.createMaterial(m.name).setBaseColorFactor([...m.albedo, 1]).setMetallicFactor(0).setRoughnessFactor(1).setDoubleSided(true);
    if (m.albedoTexture !== undefined) {
      mat.setBaseColorTexture(textures[m.albedoTexture]!);
      nearestRepeat(mat.getBaseColorTextureInfo());
    }
    if (m.alphaMode === 'mask') mat.setAlphaMode('MASK').setAlphaCutoff(0.5);
    const peak = Math.max(...m.emission);
    if (peak > 0) {
      mat.setEmissiveFactor(m.emission.map((e) => e / Math.max(peak, 1)) as unknown as Vec3 as [number, number, number]);
      if (peak > 1) mat.setExtension('KHR_materials_emissive_strength', emissiveStrength.createEmissiveStrength().setEmissiveStrength(peak));
      if (m.emissionTexture !== undefined) {
        mat.setEmissiveTexture(textures[m.emissionTexture]!);
        nearestRepeat(mat.getEmissiveTextureInfo());
      }
    }
    return mat;
  });

  const root = doc.createNode(scene.name);
  const gltfScene = doc.createScene(scene.name).addChild(root);
  doc.getRoot().setDefaultScene(gltfScene);

  scene.meshes.forEach((mesh) => {
    const triangleCount = mesh.indices.length / 3;
    // One primitive per material used by this mesh.
    const byMaterial = new Map<number, number[]>();
    for (let t = 0; t < triangleCount; t++) {
      const m = mesh.materialIds[t]!;
      let list = byMaterial.get(m);
      if (!list) byMaterial.set(m, (list = []));
      list.push(t);
    }
    const positions = mesh.positions.map((v) => v * scale);
    const position = doc.createAccessor(`${mesh.name} positions`).setType('VEC3').setArray(positions).setBuffer(buffer);
    const normal = mesh.normals ? doc.createAccessor(`${mesh.name} normals`).setType('VEC3').setArray(new Float32Array(mesh.normals)).setBuffer(buffer) : undefined;
    const uv = mesh.uvs ? doc.createAccessor(`${mesh.name} uvs`).setType('VEC2').setArray(new Float32Array(mesh.uvs)).setBuffer(buffer) : undefined;
    const gltfMesh = doc.createMesh(mesh.name);
    for (const [m, tris] of byMaterial) {
      const indices = new Uint32Array(tris.length * 3);
      tris.forEach((t, i) => indices.set(mesh.indices.subarray(t * 3, t * 3 + 3), i * 3));
      const primitive = doc
        .createPrimitive()
        .setAttribute('POSITION', position)
        .setIndices(doc.createAccessor().setType('SCALAR').setArray(indices).setBuffer(buffer))
        .setMaterial(materials[m]!);
      if (normal) primitive.setAttribute('NORMAL', normal);
      if (uv) primitive.setAttribute('TEXCOORD_0', uv);
      gltfMesh.addPrimitive(primitive);
    }
    root.addChild(doc.createNode(mesh.name).setMesh(gltfMesh));
  });

  // glTF cameras look down their local −z with +y up: build that rotation from forward and up.
  const c = scene.camera;
  const back = normalize([-c.forward[0], -c.forward[1], -c.forward[2]]);
  const right = normalize(cross(c.up, back));
  const up = cross(back, right);
  const camera = doc.createCamera('camera').setType('perspective').setYFov((c.vfovDegrees * Math.PI) / 180).setZNear(0.01).setZFar(10_000);
  gltfScene.addChild(
    doc
      .createNode('camera')
      .setCamera(camera)
      .setTranslation([c.position[0] * scale, c.position[1] * scale, c.position[2] * scale])
      .setRotation(quaternionFromBasis(right, up, back)),
  );

  return new WebIO().registerExtensions([KHRMaterialsEmissiveStrength]).writeBinary(doc);
}

function nearestRepeat(info: ReturnType<GltfMaterial['getBaseColorTextureInfo']>): void {
  info?.setMagFilter(NEAREST).setMinFilter(NEAREST).setWrapS(REPEAT).setWrapT(REPEAT);
}

/** Unit quaternion [x, y, z, w] of the rotation whose matrix has columns x, y, z. */
export function quaternionFromBasis(x: Vec3, y: Vec3, z: Vec3): [number, number, number, number] {
  const [m00, m10, m20] = x, [m01, m11, m21] = y, [m02, m12, m22] = z;
  const trace = m00 + m11 + m22;
  let q: [number, number, number, number];
  if (trace > 0) {
    const s = 0.5 / Math.sqrt(trace + 1);
    q = [(m21 - m12) * s, (m02 - m20) * s, (m10 - m01) * s, 0.25 / s];
  } else if (m00 > m11 && m00 > m22) {
    const s = 2 * Math.sqrt(1 + m00 - m11 - m22);
    q = [0.25 * s, (m01 + m10) / s, (m02 + m20) / s, (m21 - m12) / s];
  } else if (m11 > m22) {
    const s = 2 * Math.sqrt(1 + m11 - m00 - m22);
    q = [(m01 + m10) / s, 0.25 * s, (m12 + m21) / s, (m02 - m20) / s];
  } else {
    const s = 2 * Math.sqrt(1 + m22 - m00 - m11);
    q = [(m02 + m20) / s, (m12 + m21) / s, 0.25 * s, (m10 - m01) / s];
  }
  const n = Math.hypot(...q);
  return q.map((v) => v / n) as [number, number, number, number];
}
