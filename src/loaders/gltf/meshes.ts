/**
 * glTF meshes → Lantern meshes: one Lantern Mesh per glTF mesh, its primitives concatenated with a
 * material id per triangle. Attributes are read through glTF-Transform's accessors, which decode
 * KHR_mesh_quantization's normalized integers (and meshopt-compressed data) to floats.
 *
 * glTF 2.0 §3.7.2.1 rules followed here: a primitive without NORMAL gets flat normals; one without
 * TANGENT that is normal-mapped gets MikkTSpace tangents (tangents.ts). Strips and fans become
 * triangle lists; points and lines are not surfaces and are skipped.
 */
import type { Accessor, Mesh as GltfMesh, Material as GltfMaterial, Primitive } from '@gltf-transform/core';
import type { Mesh } from '../../scene/types.ts';
import { usesNormalMap } from './materials.ts';
import { generateTangents } from './tangents.ts';
import type { Warnings } from './warnings.ts';

/** glTF primitive.mode values (WebGL enums). */
const MODE = { POINTS: 0, LINES: 1, LINE_LOOP: 2, LINE_STRIP: 3, TRIANGLES: 4, TRIANGLE_STRIP: 5, TRIANGLE_FAN: 6 } as const;

/** One primitive's triangles, unindexed attributes per vertex. */
interface Part {
  positions: Float32Array;
  normals?: Float32Array;
  uvs?: Float32Array;
  uvs1?: Float32Array;
  tangents?: Float32Array;
  indices: Uint32Array;
  materialId: number;
}

export interface MeshContext {
  /** Scene material index of a glTF material (null: the default material). */
  materialId(m: GltfMaterial | null): number;
  warnings: Warnings;
  /** Per primitive of this mesh: the missing file it needs, if any (document.ts). */
  missingData: readonly (string | undefined)[];
}

/** The Lantern mesh of one glTF mesh, or undefined when none of its primitives has triangles. */
export async function convertMesh(mesh: GltfMesh, index: number, ctx: MeshContext): Promise<Mesh | undefined> {
  const name = mesh.getName() || `mesh ${index}`;
  const parts: Part[] = [];
  const primitives = mesh.listPrimitives();
  for (let p = 0; p < primitives.length; p++) {
    if (ctx.missingData[p] !== undefined) continue; // warned once per file in document.ts
    const part = await convertPrimitive(primitives[p]!, name, ctx);
    if (part) parts.push(part);
  }
  if (parts.length === 0) return undefined;
  return concatenate(name, parts);
}

async function convertPrimitive(prim: Primitive, meshName: string, ctx: MeshContext): Promise<Part | undefined> {
  const mode = prim.getMode();
  if (mode !== MODE.TRIANGLES && mode !== MODE.TRIANGLE_STRIP && mode !== MODE.TRIANGLE_FAN) {
    ctx.warnings.add('points and lines in the model are not surfaces and are not rendered');
    return undefined;
  }
  const position = prim.getAttribute('POSITION');
  if (!position) {
    ctx.warnings.add(`mesh '${meshName}' has a primitive without positions; it is left out`);
    return undefined;
  }
  const vertexCount = position.getCount();
  const order = prim.getIndices();
  const raw = order ? new Uint32Array(order.getArray() ?? []) : sequence(vertexCount);
  const indices = triangulate(raw, mode);
  if (indices.length === 0) return undefined;
  let largest = 0;
  for (let k = 0; k < indices.length; k++) largest = Math.max(largest, indices[k]!);
  if (largest >= vertexCount) {
    ctx.warnings.add(`mesh '${meshName}' has indices past its ${vertexCount} vertices; the primitive is left out`);
    return undefined;
  }

  const material = prim.getMaterial();
  let part: Part = {
    positions: readFloats(position, 3),
    indices,
    materialId: ctx.materialId(material),
  };
  // Every attribute must have POSITION's count (glTF 2.0 §3.7.2.1); one that does not (a damaged
  // file: the fuzzer found it) would be read past its end, so it is left out with a warning.
  const attribute = (semantic: string) => {
    const a = prim.getAttribute(semantic);
    if (!a || a.getCount() === vertexCount) return a ?? undefined;
    ctx.warnings.add(`mesh '${meshName}' has ${a.getCount()} ${semantic} values for ${vertexCount} vertices; ${semantic} is ignored there`);
    return undefined;
  };
  const normal = attribute('NORMAL');
  const uv0 = attribute('TEXCOORD_0');
  const uv1 = attribute('TEXCOORD_1');
  const tangent = attribute('TANGENT');
  if (normal) part.normals = normalizeAll(readFloats(normal, 3));
  if (uv0) part.uvs = readFloats(uv0, 2);
  if (uv1) part.uvs1 = readFloats(uv1, 2);
  if (tangent) part.tangents = readFloats(tangent, 4);

  if (usesNormalMap(material) && !part.tangents) {
    const set = material?.getNormalTextureInfo()?.getTexCoord() === 1 ? part.uvs1 : part.uvs;
    if (!set) {
      ctx.warnings.add(`mesh '${meshName}' is normal-mapped but has no texture coordinates; the normal map is ignored there`);
    } else {
      if (!part.normals) part = flatShaded(part);
      const uvs = set === part.uvs1 ? part.uvs1! : part.uvs!;
      const extra = [part.uvs, part.uvs1].filter((a): a is Float32Array => a !== undefined && a !== uvs);
      const out = await generateTangents({ positions: part.positions, normals: part.normals!, uvs, extra: extra.map((data) => ({ data, size: 2 })), indices: part.indices });
      const remap = (a: Float32Array | undefined) => (a === undefined ? undefined : a === uvs ? out.uvs : out.extra[extra.indexOf(a)]);
      const uvsOut = remap(part.uvs), uvs1Out = remap(part.uvs1);
      part = { positions: out.positions, normals: out.normals, tangents: out.tangents, indices: out.indices, materialId: part.materialId };
      if (uvsOut) part.uvs = uvsOut;
      if (uvs1Out) part.uvs1 = uvs1Out;
    }
  }
  return part;
}

/** Triangle list from TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN, without index-degenerate triangles. */
export function triangulate(order: Uint32Array, mode: number): Uint32Array {
  // At most one triangle per three corners (a list) or per corner after the first two (strip, fan).
  const out = new Uint32Array(mode === MODE.TRIANGLES ? order.length - (order.length % 3) : Math.max(0, order.length - 2) * 3);
  let n = 0;
  const push = (a: number, b: number, c: number) => {
    // Strips use repeated indices to restart; such triangles have no area and no front.
    if (a !== b && b !== c && a !== c) {
      out[n++] = a;
      out[n++] = b;
      out[n++] = c;
    }
  };
  if (mode === MODE.TRIANGLES) {
    for (let i = 0; i + 2 < order.length; i += 3) push(order[i]!, order[i + 1]!, order[i + 2]!);
  } else if (mode === MODE.TRIANGLE_STRIP) {
    // glTF 2.0 §3.7.2.1: triangle i is (i, i+1, i+2) for even i and (i+1, i, i+2) for odd i, so all
    // share one winding.
    for (let i = 0; i + 2 < order.length; i++) {
      if (i % 2 === 0) push(order[i]!, order[i + 1]!, order[i + 2]!);
      else push(order[i + 1]!, order[i]!, order[i + 2]!);
    }
  } else {
    // Fan: (i+1, i+2, 0).
    for (let i = 0; i + 2 < order.length; i++) push(order[i + 1]!, order[i + 2]!, order[0]!);
  }
  return n === out.length ? out : out.slice(0, n);
}

/** 0, 1, …, n − 1: the order of a primitive without indices. */
function sequence(n: number): Uint32Array {
  const out = new Uint32Array(n);
  for (let i = 0; i < n; i++) out[i] = i;
  return out;
}

function readFloats(accessor: Accessor, size: number): Float32Array {
  const count = accessor.getCount();
  // Plain floats of the right width (the common case) are copied whole; quantized or normalized
  // integers (KHR_mesh_quantization) and other widths go element by element through glTF-Transform.
  const array = accessor.getArray();
  if (array instanceof Float32Array && accessor.getElementSize() === size && array.length === count * size) return array.slice();
  const out = new Float32Array(count * size);
  const element = new Array<number>(accessor.getElementSize()).fill(0);
  for (let i = 0; i < count; i++) {
    accessor.getElement(i, element);
    for (let k = 0; k < size; k++) out[i * size + k] = element[k] ?? 0;
  }
  return out;
}

/** Quantized normals decode to nearly unit length; the model promises unit normals. */
function normalizeAll(n: Float32Array): Float32Array {
  for (let i = 0; i < n.length; i += 3) {
    const l = Math.hypot(n[i]!, n[i + 1]!, n[i + 2]!) || 1;
    n[i]! /= l;
    n[i + 1]! /= l;
    n[i + 2]! /= l;
  }
  return n;
}

/** Every triangle gets its own three vertices carrying its face normal (glTF: flat normals when NORMAL is absent). */
function flatShaded(part: Part): Part {
  const n = part.indices.length;
  const gather = (a: Float32Array, size: number): Float32Array => {
    const out = new Float32Array(n * size);
    for (let c = 0; c < n; c++) out.set(a.subarray(part.indices[c]! * size, part.indices[c]! * size + size), c * size);
    return out;
  };
  const positions = gather(part.positions, 3);
  const normals = new Float32Array(n * 3);
  for (let t = 0; t < n; t += 3) {
    const o = t * 3;
    const e1 = [positions[o + 3]! - positions[o]!, positions[o + 4]! - positions[o + 1]!, positions[o + 5]! - positions[o + 2]!];
    const e2 = [positions[o + 6]! - positions[o]!, positions[o + 7]! - positions[o + 1]!, positions[o + 8]! - positions[o + 2]!];
    const c = [e1[1]! * e2[2]! - e1[2]! * e2[1]!, e1[2]! * e2[0]! - e1[0]! * e2[2]!, e1[0]! * e2[1]! - e1[1]! * e2[0]!];
    const l = Math.hypot(c[0]!, c[1]!, c[2]!) || 1;
    for (let k = 0; k < 3; k++) normals.set([c[0]! / l, c[1]! / l, c[2]! / l], o + k * 3);
  }
  const out: Part = { positions, normals, indices: Uint32Array.from({ length: n }, (_, i) => i), materialId: part.materialId };
  if (part.uvs) out.uvs = gather(part.uvs, 2);
  if (part.uvs1) out.uvs1 = gather(part.uvs1, 2);
  if (part.tangents) out.tangents = gather(part.tangents, 4);
  return out;
}

/**
 * Joins parts into one mesh. An attribute some parts lack is filled so all vertices have it: normals
 * by flat shading those parts (absent everywhere, the mesh keeps none: the renderer's geometric
 * normal is the flat normal), uvs with zeros, tangents with +x (unused there: no normal map).
 */
function concatenate(name: string, input: Part[]): Mesh {
  const anyNormals = input.some((p) => p.normals);
  const parts = anyNormals ? input.map((p) => (p.normals ? p : flatShaded(p))) : input;
  // One part is the mesh as it is (a copy would double a large mesh's memory for a moment).
  if (parts.length === 1) {
    const { materialId, positions, indices, normals, uvs, uvs1, tangents } = parts[0]!;
    return { name, positions, indices, materialIds: new Uint32Array(indices.length / 3).fill(materialId), ...(normals ? { normals } : {}), ...(uvs ? { uvs } : {}), ...(uvs1 ? { uvs1 } : {}), ...(tangents ? { tangents } : {}) };
  }
  const vertexCount = parts.reduce((n, p) => n + p.positions.length / 3, 0);
  const indexCount = parts.reduce((n, p) => n + p.indices.length, 0);
  const positions = new Float32Array(vertexCount * 3);
  const normals = anyNormals ? new Float32Array(vertexCount * 3) : undefined;
  const uvs = parts.some((p) => p.uvs) ? new Float32Array(vertexCount * 2) : undefined;
  const uvs1 = parts.some((p) => p.uvs1) ? new Float32Array(vertexCount * 2) : undefined;
  const tangents = parts.some((p) => p.tangents) ? new Float32Array(vertexCount * 4) : undefined;
  const indices = new Uint32Array(indexCount);
  const materialIds = new Uint32Array(indexCount / 3);
  let v = 0, i = 0;
  for (const p of parts) {
    const n = p.positions.length / 3;
    positions.set(p.positions, v * 3);
    if (normals && p.normals) normals.set(p.normals, v * 3);
    if (uvs && p.uvs) uvs.set(p.uvs, v * 2);
    if (uvs1 && p.uvs1) uvs1.set(p.uvs1, v * 2);
    if (tangents) {
      if (p.tangents) tangents.set(p.tangents, v * 4);
      else for (let k = 0; k < n; k++) tangents.set([1, 0, 0, 1], (v + k) * 4);
    }
    for (let k = 0; k < p.indices.length; k++) indices[i + k] = p.indices[k]! + v;
    materialIds.fill(p.materialId, i / 3, (i + p.indices.length) / 3);
    v += n;
    i += p.indices.length;
  }
  return {
    name,
    positions,
    indices,
    materialIds,
    ...(normals ? { normals } : {}),
    ...(uvs ? { uvs } : {}),
    ...(uvs1 ? { uvs1 } : {}),
    ...(tangents ? { tangents } : {}),
  };
}
