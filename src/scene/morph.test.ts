import { describe, expect, it } from 'vitest';
import { morphMesh, morphTargetProblem } from './morph.ts';
import type { Mesh } from './types.ts';

const quad: Mesh = {
  name: 'door',
  positions: new Float32Array([0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0]),
  indices: new Uint32Array([0, 1, 2, 0, 2, 3]),
  uvs: new Float32Array([0, 1, 1, 1, 1, 0, 0, 0]),
  materialIds: new Uint32Array([0, 0]),
  // Target 0 raises the top edge (and its v); target 1 moves everything along z.
  morphTargets: [
    { positions: new Float32Array([0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 1, 0]), uvs: new Float32Array([0, 0, 0, 0, 0, -1, 0, -1]) },
    { positions: new Float32Array([0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1]) },
  ],
};

describe('morphMesh', () => {
  it('is base + Σ weight · target, for positions and uvs, leaving the base alone', () => {
    const m = morphMesh(quad, [2, 0.5]);
    expect([...m.positions]).toEqual([0, 0, 0.5, 1, 0, 0.5, 1, 3, 0.5, 0, 3, 0.5]);
    expect([...m.uvs!]).toEqual([0, 1, 1, 1, 1, -2, 0, -2]);
    expect(quad.positions[7]).toBe(1);
    expect([...morphMesh(quad, []).positions]).toEqual([...quad.positions]);
  });

  it('rejects more weights than targets, and targets of the wrong size', () => {
    expect(() => morphMesh(quad, [1, 1, 1])).toThrow(/2 morph targets, not 3/);
    expect(morphTargetProblem(quad)).toBeUndefined();
    expect(morphTargetProblem({ ...quad, morphTargets: [{ positions: new Float32Array(3) }] })).toMatch(/1 vertex displacements for 4 vertices/);
  });
});
