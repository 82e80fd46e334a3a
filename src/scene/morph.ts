/**
 * Morph targets (Mesh.morphTargets): a mesh's vertices and uvs as base + Σ weightᵢ · targetᵢ. Pure.
 */
import { LanternError } from '../errors.ts';
import type { Mesh } from './types.ts';

/** `base` with its morph targets applied at `weights` (one per target; missing weights are 0). */
export function morphMesh(base: Mesh, weights: ArrayLike<number>): Mesh {
  const targets = base.morphTargets ?? [];
  if (weights.length > targets.length) throw new LanternError(`mesh '${base.name}' has ${targets.length} morph targets, not ${weights.length}`);
  const positions = new Float32Array(base.positions);
  let uvs = base.uvs ? new Float32Array(base.uvs) : undefined;
  for (let k = 0; k < weights.length; k++) {
    const w = weights[k]!;
    if (w === 0) continue;
    const target = targets[k]!;
    const d = target.positions;
    for (let i = 0; i < positions.length; i++) positions[i] = positions[i]! + w * d[i]!;
    if (target.uvs && uvs) {
      const du = target.uvs;
      for (let i = 0; i < uvs.length; i++) uvs[i] = uvs[i]! + w * du[i]!;
    }
  }
  return { ...base, positions, ...(uvs ? { uvs } : {}) };
}

/** What is wrong with a mesh's morph targets, or undefined (validate.ts reports it). */
export function morphTargetProblem(mesh: Mesh): string | undefined {
  for (const [k, t] of (mesh.morphTargets ?? []).entries()) {
    if (t.positions.length !== mesh.positions.length) return `morph target ${k} has ${t.positions.length / 3} vertex displacements for ${mesh.positions.length / 3} vertices`;
    if (t.uvs && (!mesh.uvs || t.uvs.length !== mesh.uvs.length)) return `morph target ${k} moves uvs the mesh does not have in that number`;
    for (const v of t.positions) if (!Number.isFinite(v)) return `morph target ${k} has a non-finite displacement`;
  }
  if (mesh.morphTargets?.length && (mesh.spheres || mesh.capsules)) return 'morph targets move triangles only, and this mesh has spheres or capsules';
  return undefined;
}
