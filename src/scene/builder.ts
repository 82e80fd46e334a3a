/**
 * A small helper for loaders that produce scenes from polygons (built-in scenes, tile maps):
 * collects quads and triangles per material into one mesh. Quads `v0 v1 v2 v3` are split into
 * triangles (v0, v1, v2) and (v0, v2, v3), so the winding (and with it the emitting side) follows the
 * order the vertices are given in.
 */
import type { Vec3 } from '../math/vec3.ts';
import type { Material, Mesh } from './types.ts';

export class MeshBuilder {
  private readonly positions: number[] = [];
  private readonly indices: number[] = [];
  private readonly materialIds: number[] = [];
  readonly materials: Material[] = [];

  constructor(readonly name: string) {}

  /** Adds a material and returns its index. */
  material(material: Material): number {
    this.materials.push(material);
    return this.materials.length - 1;
  }

  triangle(material: number, a: Vec3, b: Vec3, c: Vec3): void {
    const base = this.positions.length / 3;
    this.positions.push(...a, ...b, ...c);
    this.indices.push(base, base + 1, base + 2);
    this.materialIds.push(material);
  }

  quad(material: number, v0: Vec3, v1: Vec3, v2: Vec3, v3: Vec3): void {
    const base = this.positions.length / 3;
    this.positions.push(...v0, ...v1, ...v2, ...v3);
    this.indices.push(base, base + 1, base + 2, base, base + 2, base + 3);
    this.materialIds.push(material, material);
  }

  build(): Mesh {
    return {
      name: this.name,
      positions: new Float32Array(this.positions),
      indices: new Uint32Array(this.indices),
      materialIds: new Uint32Array(this.materialIds),
    };
  }
}
