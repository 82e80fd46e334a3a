/**
 * Flattens a Scene's indexed meshes into one triangle list: the input of the BVH builder and of GPU
 * packing. Triangle ids in the rest of Lantern ("source triangle index") are indices into this list,
 * in mesh order then triangle order.
 */
import type { Scene } from './types.ts';

export interface TriangleList {
  readonly count: number;
  /** 9 floats per triangle: v0 xyz, v1 xyz, v2 xyz (world space). */
  readonly positions: Float32Array;
  /** Material index per triangle. */
  readonly materialIds: Uint32Array;
  /** Which mesh each triangle came from, and its index within that mesh. */
  readonly meshIds: Uint32Array;
  readonly meshTriangleIds: Uint32Array;
}

export function sceneTriangleCount(scene: Scene): number {
  return scene.meshes.reduce((n, m) => n + m.indices.length / 3, 0);
}

export function flattenTriangles(scene: Scene): TriangleList {
  const count = sceneTriangleCount(scene);
  const positions = new Float32Array(count * 9);
  const materialIds = new Uint32Array(count);
  const meshIds = new Uint32Array(count);
  const meshTriangleIds = new Uint32Array(count);
  let t = 0;
  scene.meshes.forEach((mesh, mi) => {
    const p = mesh.positions, idx = mesh.indices;
    for (let k = 0; k < idx.length / 3; k++, t++) {
      for (let c = 0; c < 3; c++) {
        const v = idx[k * 3 + c]! * 3;
        positions[t * 9 + c * 3] = p[v]!;
        positions[t * 9 + c * 3 + 1] = p[v + 1]!;
        positions[t * 9 + c * 3 + 2] = p[v + 2]!;
      }
      materialIds[t] = mesh.materialIds[k]!;
      meshIds[t] = mi;
      meshTriangleIds[t] = k;
    }
  });
  return { count, positions, materialIds, meshIds, meshTriangleIds };
}
