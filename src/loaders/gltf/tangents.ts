/**
 * Tangents for normal-mapped primitives that have none. glTF 2.0 §3.7.2.1: "When tangents are not
 * specified, client implementations SHOULD calculate tangents using default MikkTSpace algorithms
 * with the specified vertex positions, normals, and texture coordinates associated with the normal
 * texture." meshoptimizer's generateTangents with the 'Compatible' flag is that construction (its
 * default uses a different weighting); its WASM is embedded as text, so Node and a Web Worker load
 * it the same way.
 *
 * MikkTSpace works per triangle corner; two corners of one vertex can disagree (UV seams, mirrored
 * halves), and such vertices are split here so every corner keeps its own tangent.
 */
import { MeshoptTangents } from 'meshoptimizer/tangents';

export interface TangentInput {
  positions: Float32Array;
  normals: Float32Array;
  uvs: Float32Array;
  /** Other per-vertex attributes that must follow a split vertex, with their component counts. */
  extra: { data: Float32Array; size: number }[];
  indices: Uint32Array;
}

export interface TangentOutput {
  positions: Float32Array;
  normals: Float32Array;
  uvs: Float32Array;
  extra: Float32Array[];
  tangents: Float32Array;
  indices: Uint32Array;
}

/** Two corner tangents closer than this (per component) are the same tangent. */
const SAME = 1e-4;

export async function generateTangents(input: TangentInput): Promise<TangentOutput> {
  await MeshoptTangents.ready;
  const corners = MeshoptTangents.generateTangents(input.indices, input.positions, 3, input.normals, 3, input.uvs, 2, ['Compatible']);
  const vertexCount = input.positions.length / 3;
  // Per vertex: the first copy made of it, and copies chained through `next` (most vertices have one).
  const firstCopy = new Int32Array(vertexCount).fill(-1);
  const sourceOf: number[] = [];
  const next: number[] = [];
  const tangents: number[] = [];
  const indices = new Uint32Array(input.indices.length);
  for (let c = 0; c < input.indices.length; c++) {
    const v = input.indices[c]!;
    // MikkTSpace's bitangent follows increasing v; glTF's normal-map green points toward decreasing
    // v (uv (0, 0) is the image's top-left), hence the sign is negated, as three.js does for glTF.
    const t = [corners[c * 4]!, corners[c * 4 + 1]!, corners[c * 4 + 2]!, -corners[c * 4 + 3]!];
    let copy = firstCopy[v]!;
    let last = -1;
    while (copy >= 0 && !sameTangent(tangents, copy, t)) {
      last = copy;
      copy = next[copy]!;
    }
    if (copy < 0) {
      copy = sourceOf.length;
      sourceOf.push(v);
      next.push(-1);
      tangents.push(...t);
      if (last >= 0) next[last] = copy;
      else firstCopy[v] = copy;
    }
    indices[c] = copy;
  }
  const gather = (data: Float32Array, size: number): Float32Array => {
    const out = new Float32Array(sourceOf.length * size);
    sourceOf.forEach((v, i) => out.set(data.subarray(v * size, v * size + size), i * size));
    return out;
  };
  return {
    positions: gather(input.positions, 3),
    normals: gather(input.normals, 3),
    uvs: gather(input.uvs, 2),
    extra: input.extra.map((e) => gather(e.data, e.size)),
    tangents: new Float32Array(tangents),
    indices,
  };
}

function sameTangent(tangents: readonly number[], copy: number, t: readonly number[]): boolean {
  for (let k = 0; k < 4; k++) if (Math.abs(tangents[copy * 4 + k]! - t[k]!) > SAME) return false;
  return true;
}
