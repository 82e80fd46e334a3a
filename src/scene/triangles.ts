/**
 * Flattens a Scene's instances into one world-space triangle list: the input of the BVH builder and
 * of GPU packing (a build product; the model is meshes + instances). Triangle ids in the rest of
 * Lantern ("source triangle index") are indices into this list, in instance order then mesh triangle
 * order.
 *
 * A transform with a negative determinant mirrors the mesh and with it the winding: such triangles
 * are written with v1 and v2 swapped so that (v1 − v0) × (v2 − v0) still points out of the front
 * face (glTF 2.0 §3.7.4: the determinant's sign decides the front-face winding).
 */
import { determinant3, type Mat4 } from '../math/mat4.ts';
import type { Instance, Scene } from './types.ts';

export interface TriangleList {
  readonly count: number;
  /** 9 floats per triangle: v0 xyz, v1 xyz, v2 xyz (world space). */
  readonly positions: Float32Array;
  /** Material index per triangle. */
  readonly materialIds: Uint32Array;
  /** Which instance (index into Scene.instances) each triangle came from, and its index within the instance's mesh. */
  readonly instanceIds: Uint32Array;
  readonly meshTriangleIds: Uint32Array;
  /** Per instance: its first triangle in this list (triangles of one instance are contiguous). */
  readonly instanceFirstTriangle: Uint32Array;
  /** Per triangle: whether v1 and v2 were swapped (a mirroring transform), so per-vertex data follows. */
  readonly swapped: Uint8Array;
}

export function sceneTriangleCount(scene: Scene): number {
  return scene.instances.reduce((n, inst) => n + (scene.meshes[inst.mesh]?.indices.length ?? 0) / 3, 0);
}

export function flattenTriangles(scene: Scene): TriangleList {
  const count = sceneTriangleCount(scene);
  const list: TriangleList = {
    count,
    positions: new Float32Array(count * 9),
    materialIds: new Uint32Array(count),
    instanceIds: new Uint32Array(count),
    meshTriangleIds: new Uint32Array(count),
    instanceFirstTriangle: new Uint32Array(scene.instances.length),
    swapped: new Uint8Array(count),
  };
  let t = 0;
  scene.instances.forEach((instance, ii) => {
    list.instanceFirstTriangle[ii] = t;
    t = writeInstanceTriangles(scene, instance, ii, list, t);
  });
  return list;
}

/**
 * Writes one instance's world-space triangles into `list` from triangle `first` on (as flatten does,
 * and as an update after the instance moved does); returns the index after its last triangle.
 */
export function writeInstanceTriangles(scene: Scene, instance: Instance, instanceIndex: number, list: TriangleList, first: number): number {
  const mesh = scene.meshes[instance.mesh]!;
  const p = mesh.positions, idx = mesh.indices;
  const m: Mat4 = instance.worldFromObject;
  const mirror = determinant3(m) < 0;
  const m0 = m[0]!, m1 = m[1]!, m2 = m[2]!, m4 = m[4]!, m5 = m[5]!, m6 = m[6]!, m8 = m[8]!, m9 = m[9]!, m10 = m[10]!, m12 = m[12]!, m13 = m[13]!, m14 = m[14]!;
  const out = list.positions;
  let t = first;
  for (let k = 0; k < idx.length / 3; k++, t++) {
    for (let c = 0; c < 3; c++) {
      // Corner c of the output takes corner c of the mesh, or the other of v1/v2 when mirrored.
      const src = mirror && c > 0 ? 3 - c : c;
      const v = idx[k * 3 + src]! * 3;
      const x = p[v]!, y = p[v + 1]!, z = p[v + 2]!;
      out[t * 9 + c * 3] = m0 * x + m4 * y + m8 * z + m12;
      out[t * 9 + c * 3 + 1] = m1 * x + m5 * y + m9 * z + m13;
      out[t * 9 + c * 3 + 2] = m2 * x + m6 * y + m10 * z + m14;
    }
    list.materialIds[t] = instance.material ?? mesh.materialIds[k]!;
    list.instanceIds[t] = instanceIndex;
    list.meshTriangleIds[t] = k;
    list.swapped[t] = mirror ? 1 : 0;
  }
  return t;
}
