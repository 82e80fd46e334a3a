/**
 * Scene → binary glTF 2.0 (GLB), so a scene (a Doom map above all) opens in Blender or any glTF
 * viewer. Written with glTF-Transform (the document model and its GLB writer). The scene model maps
 * onto glTF almost one to one: meshes and instances become glTF meshes (one primitive per material)
 * and nodes with their matrices; materials by kind:
 * - diffuse: base colour = albedo, metallic 0, roughness 1;
 * - metallic-roughness: as it is, with KHR_materials_ior, _specular, _transmission, _volume where they
 *   differ from glTF's defaults;
 * - dielectric: transmission 1 with its ior, roughness, tint as base colour, and KHR_materials_volume
 *   (thickness > 0: the mesh bounds a refracting volume; attenuation);
 * - emissive: black base, metallic 0, roughness 1;
 * and for every kind emission as emissiveFactor × KHR_materials_emissive_strength (factors must stay
 * within [0, 1]), normal maps, alpha modes, sidedness. Textures are embedded as PNG with nearest
 * filtering (Doom's pixel art; the scene model has no filter setting) and repeat wrapping, each
 * reference with its KHR_texture_transform and uv set. Punctual lights through KHR_lights_punctual;
 * the camera as a perspective camera node. Pure: returns bytes.
 *
 * What glTF cannot say: a sky panorama (emission looked up by view direction) is exported as an
 * ordinary emissive texture on the surface's uvs; the environment and the torch are left out.
 * All nodes hang under one root node that scales scene units to metres when the scene knows its unit.
 */
import { Document, WebIO, type Material as GltfMaterial, type Texture as GltfTexture, type TextureInfo } from '@gltf-transform/core';
import {
  KHRLightsPunctual,
  KHRMaterialsEmissiveStrength,
  KHRMaterialsIOR,
  KHRMaterialsSpecular,
  KHRMaterialsTransmission,
  KHRMaterialsVolume,
  KHRTextureTransform,
} from '@gltf-transform/extensions';
import { encodePng } from '../image/png.ts';
import { cross, normalize, type Vec3 } from '../math/vec3.ts';
import type { Material, Mesh, PunctualLight, Scene, TextureRef } from '../scene/types.ts';
import { tessellateAnalytic } from '../scene/tessellate.ts';

/** glTF sampler constants (WebGL enums). */
const NEAREST = 9728;
const REPEAT = 10497;
/**
 * KHR_materials_volume's thickness only says "not thin-walled" to Lantern; glTF wants a distance (in
 * the mesh's own units) for rasterisers that fake refraction. One unit is an honest "some volume".
 */
const DIELECTRIC_THICKNESS = 1;

const EXTENSIONS = [KHRMaterialsEmissiveStrength, KHRMaterialsIOR, KHRMaterialsSpecular, KHRMaterialsTransmission, KHRMaterialsVolume, KHRTextureTransform, KHRLightsPunctual];

export interface GlbOptions {
  /** Metres per scene unit; defaults to the scene's own, else 1. */
  readonly metersPerUnit?: number;
  /** Written into asset.generator. */
  readonly generator?: string;
}

export async function sceneToGlb(scene: Scene, options: GlbOptions = {}): Promise<Uint8Array> {
  const unit = options.metersPerUnit ?? scene.metersPerUnit ?? 1;
  const doc = new Document();
  doc.getRoot().getAsset().generator = options.generator ?? 'Lantern';
  const ext = {
    emissiveStrength: doc.createExtension(KHRMaterialsEmissiveStrength),
    ior: doc.createExtension(KHRMaterialsIOR),
    specular: doc.createExtension(KHRMaterialsSpecular),
    transmission: doc.createExtension(KHRMaterialsTransmission),
    volume: doc.createExtension(KHRMaterialsVolume),
    textureTransform: doc.createExtension(KHRTextureTransform),
    lights: doc.createExtension(KHRLightsPunctual),
  };
  const buffer = doc.createBuffer();

  const textures: GltfTexture[] = (scene.textures ?? []).map((t, i) =>
    doc.createTexture(t.name).setMimeType('image/png').setImage(encodePng(t.width, t.height, t.rgba)).setURI(`texture-${i}.png`),
  );
  /** Points a material slot at a texture: sampler, uv set and transform from the reference. */
  const bind = (ref: TextureRef | undefined, set: (t: GltfTexture) => void, info: () => TextureInfo | null): void => {
    if (!ref) return;
    set(textures[ref.texture]!);
    const i = info()!;
    i.setMagFilter(NEAREST).setMinFilter(NEAREST).setWrapS(REPEAT).setWrapT(REPEAT).setTexCoord(ref.texCoord ?? 0);
    if (ref.transform) {
      const { offset, rotation, scale } = ref.transform;
      i.setExtension('KHR_texture_transform', ext.textureTransform.createTransform().setOffset([offset[0], offset[1]]).setRotation(rotation).setScale([scale[0], scale[1]]));
    }
  };

  const materials: GltfMaterial[] = scene.materials.map((m) => {
    const mat = doc.createMaterial(m.name).setDoubleSided(m.doubleSided ?? true);
    switch (m.kind) {
      case 'diffuse':
        mat.setBaseColorFactor([...m.albedo, 1]).setMetallicFactor(0).setRoughnessFactor(1);
        bind(m.albedoTexture, (t) => mat.setBaseColorTexture(t), () => mat.getBaseColorTextureInfo());
        break;
      case 'metallic-roughness':
        mat.setBaseColorFactor([...m.baseColor, m.opacity]).setMetallicFactor(m.metallic).setRoughnessFactor(m.roughness);
        bind(m.baseColorTexture, (t) => mat.setBaseColorTexture(t), () => mat.getBaseColorTextureInfo());
        bind(m.metallicRoughnessTexture, (t) => mat.setMetallicRoughnessTexture(t), () => mat.getMetallicRoughnessTextureInfo());
        if (m.ior !== 1.5) mat.setExtension('KHR_materials_ior', ext.ior.createIOR().setIOR(m.ior));
        if (m.specular !== 1 || m.specularColor.some((c) => c !== 1) || m.specularTexture || m.specularColorTexture) {
          const s = ext.specular.createSpecular().setSpecularFactor(m.specular).setSpecularColorFactor([...m.specularColor]);
          bind(m.specularTexture, (t) => s.setSpecularTexture(t), () => s.getSpecularTextureInfo());
          bind(m.specularColorTexture, (t) => s.setSpecularColorTexture(t), () => s.getSpecularColorTextureInfo());
          mat.setExtension('KHR_materials_specular', s);
        }
        if (m.transmission > 0 || m.transmissionTexture) {
          const t = ext.transmission.createTransmission().setTransmissionFactor(m.transmission);
          bind(m.transmissionTexture, (tex) => t.setTransmissionTexture(tex), () => t.getTransmissionTextureInfo());
          mat.setExtension('KHR_materials_transmission', t);
        }
        // glTF ignores attenuation on a thin wall (thickness 0), so the volume goes out only with thickness.
        if (m.thickness > 0) mat.setExtension('KHR_materials_volume', volume(ext.volume, m.thickness, m.attenuationDistance, m.attenuationColor));
        break;
      case 'dielectric':
        mat.setBaseColorFactor([...m.tint, 1]).setMetallicFactor(0).setRoughnessFactor(m.roughness);
        mat.setExtension('KHR_materials_transmission', ext.transmission.createTransmission().setTransmissionFactor(1));
        mat.setExtension('KHR_materials_ior', ext.ior.createIOR().setIOR(m.ior));
        mat.setExtension('KHR_materials_volume', volume(ext.volume, DIELECTRIC_THICKNESS, m.attenuationDistance, m.attenuationColor));
        break;
      case 'emissive':
        mat.setBaseColorFactor([0, 0, 0, 1]).setMetallicFactor(0).setRoughnessFactor(1);
        break;
    }
    emission(mat, m, ext.emissiveStrength);
    bind(m.emissionTexture, (t) => mat.setEmissiveTexture(t), () => mat.getEmissiveTextureInfo());
    if (m.normalTexture) {
      bind(m.normalTexture, (t) => mat.setNormalTexture(t), () => mat.getNormalTextureInfo());
      mat.setNormalScale(m.normalTexture.scale ?? 1);
    }
    // A volume's back faces are its inside; glTF says such materials are single-sided, and Lantern
    // treats a transmitting material's back faces as surfaces either way, so nothing changes for it.
    if (mat.getExtension('KHR_materials_volume')) mat.setDoubleSided(false);
    if (m.alphaMode === 'mask') mat.setAlphaMode('MASK').setAlphaCutoff(m.alphaCutoff ?? 0.5);
    else if (m.alphaMode === 'blend') mat.setAlphaMode('BLEND');
    return mat;
  });

  const root = doc.createNode(scene.name).setScale([unit, unit, unit]);
  const gltfScene = doc.createScene(scene.name).addChild(root);
  doc.getRoot().setDefaultScene(gltfScene);

  // One primitive per material used by a mesh (or all of them `override`'s), all sharing the mesh's vertex accessors.
  const addPrimitives = (gltfMesh: ReturnType<typeof doc.createMesh>, mesh: Mesh, override?: number) => {
    const triangleCount = mesh.indices.length / 3;
    const byMaterial = new Map<number, number[]>();
    for (let t = 0; t < triangleCount; t++) {
      const m = override ?? mesh.materialIds[t]!;
      let list = byMaterial.get(m);
      if (!list) byMaterial.set(m, (list = []));
      list.push(t);
    }
    const accessor = (name: string, type: 'VEC2' | 'VEC3' | 'VEC4', data: Float32Array | undefined) =>
      data && doc.createAccessor(`${mesh.name} ${name}`).setType(type).setArray(new Float32Array(data)).setBuffer(buffer);
    const attributes = {
      POSITION: accessor('positions', 'VEC3', mesh.positions),
      NORMAL: accessor('normals', 'VEC3', mesh.normals),
      TEXCOORD_0: accessor('uvs', 'VEC2', mesh.uvs),
      TEXCOORD_1: accessor('uvs1', 'VEC2', mesh.uvs1),
      TANGENT: accessor('tangents', 'VEC4', mesh.tangents),
    };
    for (const [m, tris] of byMaterial) {
      const indices = new Uint32Array(tris.length * 3);
      tris.forEach((t, i) => indices.set(mesh.indices.subarray(t * 3, t * 3 + 3), i * 3));
      const primitive = doc.createPrimitive().setIndices(doc.createAccessor().setType('SCALAR').setArray(indices).setBuffer(buffer)).setMaterial(materials[m]!);
      for (const [semantic, a] of Object.entries(attributes)) if (a) primitive.setAttribute(semantic, a);
      gltfMesh.addPrimitive(primitive);
    }
  };

  // glTF materials belong to primitives, not nodes: an instance whose material replaces its mesh's
  // (Instance.material: a Doom sprite's current rotation) gets a glTF mesh of its own per material.
  const gltfMeshes = new Map<string, ReturnType<typeof doc.createMesh>>();
  const gltfMeshOf = (index: number, override?: number) => {
    const key = `${index}:${override ?? ''}`;
    let gltfMesh = gltfMeshes.get(key);
    if (gltfMesh) return gltfMesh;
    const mesh = scene.meshes[index]!;
    gltfMesh = doc.createMesh(override === undefined ? mesh.name : `${mesh.name} (${scene.materials[override]?.name ?? override})`);
    if (mesh.indices.length > 0) addPrimitives(gltfMesh, mesh, override);
    // glTF has no spheres: analytic spheres and capsules go out tessellated, with their own accessors.
    const tessellated = tessellateAnalytic(mesh);
    if (tessellated) addPrimitives(gltfMesh, tessellated, override);
    gltfMeshes.set(key, gltfMesh);
    return gltfMesh;
  };

  for (const instance of scene.instances) {
    const node = doc.createNode(instance.name ?? `${scene.meshes[instance.mesh]?.name ?? 'mesh'} ${instance.id}`);
    node.setMesh(gltfMeshOf(instance.mesh, instance.material)).setMatrix([...instance.worldFromObject] as Parameters<typeof node.setMatrix>[0]);
    root.addChild(node);
  }

  for (const light of scene.lights ?? []) root.addChild(lightNode(doc, ext.lights, light));

  // glTF cameras look down their local −z with +y up: build that rotation from forward and up.
  const c = scene.camera;
  const back = normalize([-c.forward[0], -c.forward[1], -c.forward[2]]);
  const right = normalize(cross(c.up, back));
  const up = cross(back, right);
  const camera = doc.createCamera('camera').setType('perspective').setYFov((c.vfovDegrees * Math.PI) / 180).setZNear(0.01).setZFar(10_000);
  root.addChild(doc.createNode('camera').setCamera(camera).setTranslation([...c.position]).setRotation(quaternionFromBasis(right, up, back)));

  return new WebIO().registerExtensions(EXTENSIONS).writeBinary(doc);
}

/** Emission as a factor in [0, 1] times a strength (KHR_materials_emissive_strength) when above 1. */
function emission(mat: GltfMaterial, m: Material, strength: KHRMaterialsEmissiveStrength): void {
  const peak = Math.max(...m.emission);
  if (!(peak > 0)) return;
  const scale = Math.max(peak, 1);
  mat.setEmissiveFactor([m.emission[0] / scale, m.emission[1] / scale, m.emission[2] / scale]);
  if (peak > 1) mat.setExtension('KHR_materials_emissive_strength', strength.createEmissiveStrength().setEmissiveStrength(peak));
}

function volume(ext: KHRMaterialsVolume, thickness: number, attenuationDistance: number, attenuationColor: Vec3) {
  const v = ext.createVolume().setThicknessFactor(thickness).setAttenuationColor([...attenuationColor]);
  // glTF's default attenuation distance is +Infinity and it must be written as absent, not a number.
  if (Number.isFinite(attenuationDistance)) v.setAttenuationDistance(attenuationDistance);
  return v;
}

/** A node holding the light, at its position, turned so its local −z is the light's direction. */
function lightNode(doc: Document, ext: KHRLightsPunctual, light: PunctualLight) {
  const l = ext.createLight(light.name).setType(light.kind).setColor([...light.color]);
  const node = doc.createNode(light.name);
  if (light.kind === 'directional') l.setIntensity(light.irradiance);
  else {
    l.setIntensity(light.intensity).setRange(Number.isFinite(light.range) ? light.range : null);
    node.setTranslation([...light.position]);
  }
  if (light.kind === 'spot') l.setInnerConeAngle(light.innerConeAngle).setOuterConeAngle(light.outerConeAngle);
  if (light.kind !== 'point') {
    const back = normalize([-light.direction[0], -light.direction[1], -light.direction[2]]);
    // Any right angle to the direction will do; avoid the one parallel to it.
    const helper: Vec3 = Math.abs(back[1]) < 0.9 ? [0, 1, 0] : [1, 0, 0];
    const right = normalize(cross(helper, back));
    node.setRotation(quaternionFromBasis(right, cross(back, right), back));
  }
  return node.setExtension('KHR_lights_punctual', l);
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
