/**
 * Tessellated shapes for built-in scenes, in object space: a UV sphere with exact unit normals (so
 * shading is smooth however coarse the tessellation) and a square. Triangles are wound so that
 * (v1 − v0) × (v2 − v0) points outward.
 */
import type { Mesh } from './types.ts';

/** A sphere of `radius` at the origin: `segments` around the y axis, `rings` from pole to pole. uv: u around, v from the top. */
export function uvSphere(name: string, radius: number, segments = 64, rings = 32, material = 0): Mesh {
  const positions: number[] = [], normals: number[] = [], uvs: number[] = [], indices: number[] = [];
  for (let r = 0; r <= rings; r++) {
    const theta = (r / rings) * Math.PI;
    for (let s = 0; s <= segments; s++) {
      const phi = (s / segments) * 2 * Math.PI;
      const n = [Math.sin(theta) * Math.sin(phi), Math.cos(theta), Math.sin(theta) * Math.cos(phi)] as const;
      positions.push(n[0] * radius, n[1] * radius, n[2] * radius);
      normals.push(...n);
      uvs.push(s / segments, r / rings);
    }
  }
  const row = segments + 1;
  for (let r = 0; r < rings; r++) {
    for (let s = 0; s < segments; s++) {
      const a = r * row + s, b = a + row, c = b + 1, d = a + 1;
      // Skip the degenerate triangles at the poles.
      if (r > 0) indices.push(a, b, d);
      if (r < rings - 1) indices.push(d, b, c);
    }
  }
  return {
    name,
    positions: new Float32Array(positions),
    normals: new Float32Array(normals),
    uvs: new Float32Array(uvs),
    indices: new Uint32Array(indices),
    materialIds: new Uint32Array(indices.length / 3).fill(material),
  };
}

/** A square of side 2·half in the y = 0 plane facing +y, with uvs repeating `tiles` times across. */
export function floorSquare(name: string, half: number, tiles: number, material = 0): Mesh {
  return {
    name,
    positions: new Float32Array([-half, 0, -half, -half, 0, half, half, 0, half, half, 0, -half]),
    normals: new Float32Array([0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0]),
    uvs: new Float32Array([0, 0, 0, tiles, tiles, tiles, tiles, 0]),
    indices: new Uint32Array([0, 1, 2, 0, 2, 3]),
    materialIds: new Uint32Array([material, material]),
  };
}
