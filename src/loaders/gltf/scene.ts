/**
 * Scene assembly: walks the node hierarchy of the default scene (else the first), composing each
 * node's local transform onto its parent's, and turns what hangs on the nodes into the Lantern scene:
 * an Instance per node with a mesh (id = the node's index, so ids are stable across reloads), the
 * first camera reached as the view, every punctual light in world space.
 *
 * A node whose transform mirrors (negative determinant) keeps its matrix as it is: glTF 2.0 §3.7.4
 * says its triangles' winding is reversed, and that is the consumer's business (the flattener), as
 * the instance carries the whole transform.
 */
import type { Node } from '@gltf-transform/core';
import type { InstancedMesh, Light } from '@gltf-transform/extensions';
import { LanternError } from '../../errors.ts';
import { boundsOfPositions, isEmptyAabb, unionAabb, type Aabb } from '../../math/aabb.ts';
import { fromTrs, multiply, transformPoint, type Mat4 } from '../../math/mat4.ts';
import { withDefaultLight } from '../../scene/default-light.ts';
import { frameBounds } from '../../scene/framing.ts';
import type { Camera, Instance, Material, Mesh, PunctualLight, Scene } from '../../scene/types.ts';
import { SIBLING_RULE } from '../sibling-uri.ts';
import { convertCamera } from './cameras.ts';
import type { GltfSource } from './document.ts';
import { convertLight } from './lights.ts';
import { convertMaterial, defaultMaterial } from './materials.ts';
import { convertMesh } from './meshes.ts';
import { TextureTable } from './textures.ts';
import type { Warnings } from './warnings.ts';

export async function assembleScene(name: string, source: GltfSource, warnings: Warnings): Promise<Scene> {
  const { doc } = source;
  const root = doc.getRoot();
  const textures = new TextureTable(root.listTextures(), source.imageNames, source.imageMissing, warnings);

  // Materials in glTF order, converted when first used so unused ones cost no texture decoding.
  const gltfMaterials = root.listMaterials();
  const materials: Material[] = [];
  const materialIndex = new Map<unknown, number>();
  const materialId = (m: (typeof gltfMaterials)[number] | null): number => {
    const known = materialIndex.get(m);
    if (known !== undefined) return known;
    const converted = m ? convertMaterial(m, gltfMaterials.indexOf(m), textures, warnings) : defaultMaterial();
    materials.push(converted);
    materialIndex.set(m, materials.length - 1);
    return materials.length - 1;
  };

  const gltfScene = root.getDefaultScene() ?? root.listScenes()[0];
  if (!gltfScene) throw new LanternError(`${name} has no scene to show`, 'the file holds no nodes; export the scene, not only its assets');

  const gltfMeshes = root.listMeshes();
  const nodes = root.listNodes();
  const nodeIndex = new Map(nodes.map((n, i) => [n, i]));
  // Meshes converted on first use by a node, so meshes no node shows are skipped.
  const meshSlot = new Map<number, number | undefined>();
  const meshes: Mesh[] = [];
  const instances: Instance[] = [];
  const lights: PunctualLight[] = [];
  let camera: Camera | undefined;
  let extraIds = 0;

  /** Places one node's mesh, camera and light; returns its world-from-object transform for its children. */
  const visit = async (node: Node, parent: Mat4): Promise<Mat4> => {
    const worldFromObject = multiply(parent, node.getMatrix());
    const index = nodeIndex.get(node) ?? -1;
    const mesh = node.getMesh();
    if (mesh && node.getSkin()) warnings.add('skins are not applied: skinned meshes are shown in their bind pose, placed by their node');
    if (mesh?.listPrimitives().some((p) => p.listTargets().length > 0)) warnings.add('morph targets are not applied: meshes are shown in their base shape');
    if (mesh) {
      const m = gltfMeshes.indexOf(mesh);
      if (!meshSlot.has(m)) {
        const converted = await convertMesh(mesh, m, { materialId, warnings, missingData: source.missingData[m] ?? [] });
        if (converted) meshes.push(converted);
        meshSlot.set(m, converted ? meshes.length - 1 : undefined);
      }
      const slot = meshSlot.get(m);
      const nodeName = node.getName();
      const gpuInstances = node.getExtension<InstancedMesh>('EXT_mesh_gpu_instancing');
      // A placement past the float range (scales of 1e308 multiplied) has no place to be drawn.
      const outOfRange = () => warnings.add(`node ${index}'s transform is past the float range: the mesh it places is left out there`);
      if (slot !== undefined && gpuInstances) {
        // EXT_mesh_gpu_instancing: one placement per TRS row, each applied before the node's own
        // transform. Ids continue after the node indices, in file order, so they too are stable.
        for (const local of instanceTransforms(gpuInstances)) {
          const placed = multiply(worldFromObject, local);
          const id = nodes.length + extraIds++;
          if (placed.every(Number.isFinite)) instances.push({ id, ...(nodeName ? { name: nodeName } : {}), mesh: slot, worldFromObject: placed });
          else outOfRange();
        }
      } else if (slot !== undefined) {
        if (worldFromObject.every(Number.isFinite)) instances.push({ id: index, ...(nodeName ? { name: nodeName } : {}), mesh: slot, worldFromObject });
        else outOfRange();
      }
    }
    const cam = node.getCamera();
    if (cam && !camera) camera = convertCamera(cam, worldFromObject, warnings);
    const light = node.getExtension<Light>('KHR_lights_punctual');
    const placedLight = light ? convertLight(light, worldFromObject, `light ${lights.length}`, warnings) : undefined;
    if (placedLight) lights.push(placedLight);
    return worldFromObject;
  };
  // Depth first in file order with an explicit stack: recursion as deep as the node hierarchy
  // overflows the call stack on a chain of a few thousand nodes. A node reached twice (the
  // hierarchy must be trees) is placed once, so a cycle ends.
  const identity: Mat4 = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];
  const pending: Array<{ node: Node; parent: Mat4 }> = gltfScene.listChildren().map((node) => ({ node, parent: identity })).reverse();
  const placed = new Set<Node>();
  while (pending.length > 0) {
    const { node, parent } = pending.pop()!;
    if (placed.has(node)) {
      warnings.add(`node ${nodeIndex.get(node) ?? -1} is reached twice in the node hierarchy; it is placed once`);
      continue;
    }
    placed.add(node);
    const worldFromObject = await visit(node, parent);
    const children = node.listChildren();
    for (let i = children.length - 1; i >= 0; i--) pending.push({ node: children[i]!, parent: worldFromObject });
  }

  if (instances.length === 0) {
    const missing = [...new Set(source.missingData.flat().filter((u) => u !== undefined))];
    const refused = missing.filter((u) => warnings.refusal(u) !== undefined);
    if (refused.length > 0) {
      throw new LanternError(`${name}: nothing to show, the geometry is in ${refused.join(', ')}, which Lantern does not read (${warnings.refusal(refused[0]!)})`, `${SIBLING_RULE}: put the file in the model's folder and name it by a relative path`);
    }
    if (missing.length > 0) {
      throw new LanternError(`${name}: nothing to show, the geometry is in ${missing.join(', ')}, which is missing`, `put ${missing.join(', ')} next to ${name}`);
    }
    throw new LanternError(`${name} has no triangles to show`, 'the scene holds no triangle meshes (only points, lines, or nothing)');
  }
  if (materials.length === 0) materials.push(defaultMaterial());

  if (!camera) camera = frameBounds(worldBounds(meshes, instances));

  // The default sky where the model's own emitters and lights are too dim to light it (its exposure
  // comes with it), decided by what they deliver: scene/default-light.ts.
  return withDefaultLight({
    name,
    meshes,
    instances,
    materials,
    textures: textures.textures,
    camera,
    lights,
    metersPerUnit: 1,
    warnings: warnings.list,
  });
}

/** The per-instance transforms of EXT_mesh_gpu_instancing (absent attributes: identity parts), one at a time: a million rows are a million matrices. */
function* instanceTransforms(batch: InstancedMesh): Generator<Mat4> {
  const t = batch.getAttribute('TRANSLATION'), r = batch.getAttribute('ROTATION'), s = batch.getAttribute('SCALE');
  const count = t?.getCount() ?? r?.getCount() ?? s?.getCount() ?? 0;
  for (let i = 0; i < count; i++) {
    const tr = t ? (t.getElement(i, [0, 0, 0]) as [number, number, number]) : ([0, 0, 0] as const);
    const q = r ? (r.getElement(i, [0, 0, 0, 1]) as [number, number, number, number]) : ([0, 0, 0, 1] as const);
    const sc = s ? (s.getElement(i, [1, 1, 1]) as [number, number, number]) : ([1, 1, 1] as const);
    yield fromTrs(tr, q, sc);
  }
}

/** The world-space box of all instances: each mesh's object box, its eight corners transformed. */
function worldBounds(meshes: readonly Mesh[], instances: readonly Instance[]): Aabb {
  const objectBounds = meshes.map((m) => boundsOfPositions(m.positions));
  let bounds: Aabb = { min: [Infinity, Infinity, Infinity], max: [-Infinity, -Infinity, -Infinity] };
  for (const inst of instances) {
    const b = objectBounds[inst.mesh]!;
    if (isEmptyAabb(b)) continue;
    for (const x of [b.min[0], b.max[0]]) {
      for (const y of [b.min[1], b.max[1]]) {
        for (const z of [b.min[2], b.max[2]]) {
          const p = transformPoint(inst.worldFromObject, [x, y, z]);
          bounds = unionAabb(bounds, { min: p, max: p });
        }
      }
    }
  }
  return bounds;
}
