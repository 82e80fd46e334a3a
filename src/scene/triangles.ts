/**
 * Flattens a Scene's instances into one world-space primitive list: the input of the BVH builder and
 * of GPU packing (a build product; the model is meshes + instances). Primitives are triangles and the
 * analytic spheres and capsules (Mesh.spheres, Mesh.capsules), in one list so that one BVH holds them
 * all. Primitive ids in the rest of Lantern ("source triangle index", "source primitive") are indices
 * into this list: instance order, and within an instance its mesh's triangles, then its spheres, then
 * its capsules.
 *
 * Every primitive takes 9 floats of `positions`, by kind (PRIMITIVE_KIND):
 * - triangle: v0 xyz, v1 xyz, v2 xyz;
 * - sphere: centre xyz, radius, then 5 zeros;
 * - capsule: a xyz, b xyz, radius, then 2 zeros.
 *
 * A transform with a negative determinant mirrors the mesh and with it the winding: such triangles
 * are written with v1 and v2 swapped so that (v1 − v0) × (v2 − v0) still points out of the front
 * face (glTF 2.0 §3.7.4: the determinant's sign decides the front-face winding). Spheres and capsules
 * need a similarity transform (scene/validate.ts checks): their radius scales by its uniform scale.
 */
import { determinant3, type Mat4 } from '../math/mat4.ts';
import type { Instance, Mesh, Scene } from './types.ts';

/** The primitive kinds of the flattened list (and of the GPU's TriangleHot flags, shaders/scene/types.wgsl). */
export const PRIMITIVE_KIND = { triangle: 0, sphere: 1, capsule: 2 } as const;
export type PrimitiveKindName = keyof typeof PRIMITIVE_KIND;
export const PRIMITIVE_KIND_NAMES: readonly PrimitiveKindName[] = ['triangle', 'sphere', 'capsule'];

/** Floats per primitive in TriangleList.positions. */
export const PRIMITIVE_FLOATS = 9;

export interface TriangleList {
  /** Primitives of every kind. */
  readonly count: number;
  /** 9 floats per primitive, world space (see the module comment for each kind's layout). */
  readonly positions: Float32Array;
  /** PRIMITIVE_KIND per primitive. */
  readonly kinds: Uint8Array;
  /** Material index per primitive. */
  readonly materialIds: Uint32Array;
  /** Which instance (index into Scene.instances) each primitive came from, and its index within the instance's mesh (among the primitives of its kind). */
  readonly instanceIds: Uint32Array;
  readonly meshTriangleIds: Uint32Array;
  /** Per instance: its first primitive in this list (primitives of one instance are contiguous). */
  readonly instanceFirstTriangle: Uint32Array;
  /** Per primitive: whether a triangle's v1 and v2 were swapped (a mirroring transform), so per-vertex data follows. */
  readonly swapped: Uint8Array;
  /** How many primitives of each kind. */
  readonly kindCounts: { readonly triangle: number; readonly sphere: number; readonly capsule: number };
}

export const meshTriangleCount = (mesh: Mesh): number => mesh.indices.length / 3;
export const meshSphereCount = (mesh: Mesh): number => mesh.spheres?.radii.length ?? 0;
export const meshCapsuleCount = (mesh: Mesh): number => mesh.capsules?.radii.length ?? 0;
export const meshPrimitiveCount = (mesh: Mesh): number => meshTriangleCount(mesh) + meshSphereCount(mesh) + meshCapsuleCount(mesh);

/** Primitives of every kind the scene draws (each mesh once per instance). */
export function scenePrimitiveCount(scene: Scene): number {
  return scene.instances.reduce((n, inst) => n + (scene.meshes[inst.mesh] ? meshPrimitiveCount(scene.meshes[inst.mesh]!) : 0), 0);
}

/** Triangles only. */
export function sceneTriangleCount(scene: Scene): number {
  return scene.instances.reduce((n, inst) => n + (scene.meshes[inst.mesh] ? meshTriangleCount(scene.meshes[inst.mesh]!) : 0), 0);
}

/** "1,200 primitives (1,000 triangles, 150 spheres, 50 capsules)", or "1,000 triangles" when there are only triangles. */
export function describePrimitives(list: Pick<TriangleList, 'count' | 'kindCounts'>): string {
  const n = (x: number) => x.toLocaleString('en-US');
  const { triangle, sphere, capsule } = list.kindCounts;
  if (sphere + capsule === 0) return `${n(triangle)} triangles`;
  return `${n(list.count)} primitives (${n(triangle)} triangles, ${n(sphere)} spheres, ${n(capsule)} capsules)`;
}

export function flattenTriangles(scene: Scene): TriangleList {
  const count = scenePrimitiveCount(scene);
  const kindCounts = { triangle: 0, sphere: 0, capsule: 0 };
  for (const inst of scene.instances) {
    const mesh = scene.meshes[inst.mesh]!;
    kindCounts.triangle += meshTriangleCount(mesh);
    kindCounts.sphere += meshSphereCount(mesh);
    kindCounts.capsule += meshCapsuleCount(mesh);
  }
  const list: TriangleList = {
    count,
    positions: new Float32Array(count * PRIMITIVE_FLOATS),
    kinds: new Uint8Array(count),
    materialIds: new Uint32Array(count),
    instanceIds: new Uint32Array(count),
    meshTriangleIds: new Uint32Array(count),
    instanceFirstTriangle: new Uint32Array(scene.instances.length),
    swapped: new Uint8Array(count),
    kindCounts,
  };
  let t = 0;
  scene.instances.forEach((instance, ii) => {
    list.instanceFirstTriangle[ii] = t;
    t = writeInstanceTriangles(scene, instance, ii, list, t);
  });
  return list;
}

/** The uniform scale of a similarity transform: the cube root of |det| of its linear part. */
export function uniformScaleOf(m: Mat4): number {
  return Math.cbrt(Math.abs(determinant3(m)));
}

/**
 * Writes one instance's world-space primitives into `list` from primitive `first` on (as flatten
 * does, and as an update after the instance moved does); returns the index after its last one.
 */
export function writeInstanceTriangles(scene: Scene, instance: Instance, instanceIndex: number, list: TriangleList, first: number): number {
  const mesh = scene.meshes[instance.mesh]!;
  const p = mesh.positions, idx = mesh.indices;
  const m: Mat4 = instance.worldFromObject;
  const mirror = determinant3(m) < 0;
  const m0 = m[0]!, m1 = m[1]!, m2 = m[2]!, m4 = m[4]!, m5 = m[5]!, m6 = m[6]!, m8 = m[8]!, m9 = m[9]!, m10 = m[10]!, m12 = m[12]!, m13 = m[13]!, m14 = m[14]!;
  const out = list.positions;
  const put = (o: number, x: number, y: number, z: number) => {
    out[o] = m0 * x + m4 * y + m8 * z + m12;
    out[o + 1] = m1 * x + m5 * y + m9 * z + m13;
    out[o + 2] = m2 * x + m6 * y + m10 * z + m14;
  };
  const record = (t: number, kind: number, k: number, material: number) => {
    list.kinds[t] = kind;
    list.materialIds[t] = instance.material ?? material;
    list.instanceIds[t] = instanceIndex;
    list.meshTriangleIds[t] = k;
    list.swapped[t] = kind === PRIMITIVE_KIND.triangle && mirror ? 1 : 0;
  };
  let t = first;
  for (let k = 0; k < idx.length / 3; k++, t++) {
    for (let c = 0; c < 3; c++) {
      // Corner c of the output takes corner c of the mesh, or the other of v1/v2 when mirrored.
      const src = mirror && c > 0 ? 3 - c : c;
      const v = idx[k * 3 + src]! * 3;
      put(t * 9 + c * 3, p[v]!, p[v + 1]!, p[v + 2]!);
    }
    record(t, PRIMITIVE_KIND.triangle, k, mesh.materialIds[k]!);
  }
  const scale = mesh.spheres || mesh.capsules ? uniformScaleOf(m) : 1;
  if (mesh.spheres) {
    const { centers, radii, materialIds } = mesh.spheres;
    for (let k = 0; k < radii.length; k++, t++) {
      const o = t * 9;
      put(o, centers[k * 3]!, centers[k * 3 + 1]!, centers[k * 3 + 2]!);
      out[o + 3] = radii[k]! * scale;
      out.fill(0, o + 4, o + 9);
      record(t, PRIMITIVE_KIND.sphere, k, materialIds[k]!);
    }
  }
  if (mesh.capsules) {
    const { endpoints, radii, materialIds } = mesh.capsules;
    for (let k = 0; k < radii.length; k++, t++) {
      const o = t * 9;
      put(o, endpoints[k * 6]!, endpoints[k * 6 + 1]!, endpoints[k * 6 + 2]!);
      put(o + 3, endpoints[k * 6 + 3]!, endpoints[k * 6 + 4]!, endpoints[k * 6 + 5]!);
      out[o + 6] = radii[k]! * scale;
      out[o + 7] = 0;
      out[o + 8] = 0;
      record(t, PRIMITIVE_KIND.capsule, k, materialIds[k]!);
    }
  }
  return t;
}
