/**
 * The neutral scene model every loader produces and the renderer consumes. Renderer-agnostic: no GPU
 * types, no DOM, no file access. Units are whatever the source uses (millimetres for the Cornell box,
 * map units for Doom); the renderer never assumes a scale.
 */
import type { Vec3 } from '../math/vec3.ts';

/**
 * A diffuse (Lambertian) surface that may also emit.
 * - Reflection happens on both sides of a triangle.
 * - Emission is one-sided: a triangle emits only on the side its geometric normal
 *   (v1 - v0) x (v2 - v0) faces, i.e. the side from which the vertices appear counter-clockwise.
 */
export interface Material {
  readonly name: string;
  /** Diffuse reflectance per linear RGB channel, each in [0, 1]. */
  readonly albedo: Vec3;
  /** Emitted radiance per linear RGB channel (W·sr⁻¹·m⁻² in scene units), each ≥ 0. */
  readonly emission: Vec3;
}

/** An indexed triangle mesh in world space. */
export interface Mesh {
  readonly name: string;
  /** xyz per vertex, world space. */
  readonly positions: Float32Array;
  /** Three vertex indices per triangle. */
  readonly indices: Uint32Array;
  /** Optional unit shading normal per vertex (xyz). Absent: the geometric normal is used. */
  readonly normals?: Float32Array;
  /** Optional texture coordinate per vertex (uv). */
  readonly uvs?: Float32Array;
  /** One index into `Scene.materials` per triangle. */
  readonly materialIds: Uint32Array;
}

/** A pinhole camera. `forward` and `up` need not be unit length nor exactly orthogonal. */
export interface Camera {
  readonly position: Vec3;
  readonly forward: Vec3;
  readonly up: Vec3;
  /** Vertical field of view in degrees, in (0, 180). */
  readonly vfovDegrees: number;
}

export interface Scene {
  readonly name: string;
  readonly meshes: readonly Mesh[];
  readonly materials: readonly Material[];
  readonly camera: Camera;
}
