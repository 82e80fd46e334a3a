/**
 * The neutral scene model every loader produces and the renderer consumes. Renderer-agnostic: no GPU
 * types, no DOM, no file access. Units are whatever the source uses (millimetres for the Cornell box,
 * map units for Doom); the renderer never assumes a scale.
 */
import type { Vec3 } from '../math/vec3.ts';
import type { WalkMap } from './walk-map.ts';

/**
 * An image for materials: 8-bit RGBA, row-major, top row first. Colour channels are sRGB-encoded
 * (as in PNG and glTF base colour textures); alpha is linear coverage (0 = a hole). Sampled with
 * wrapping (repeat) and nearest filtering; (u, v) = (0, 0) is the top-left corner of the image and
 * one unit covers the whole image.
 */
export interface Texture {
  readonly name: string;
  readonly width: number;
  readonly height: number;
  readonly rgba: Uint8Array;
}

/**
 * How an emission texture is looked up: by the surface's uv, or by the direction of the ray that
 * sees the surface, as a cylindrical panorama around the vertical (+y) axis (Doom's sky: the sky
 * texture drawn behind F_SKY1 surfaces, wherever they are).
 */
export type EmissionMapping =
  | { readonly kind: 'uv' }
  | {
      readonly kind: 'panorama';
      /** How many times the texture repeats around the horizon (Doom: 4). */
      readonly repeats: number;
      /** Texture v (0 top, 1 bottom) seen at the horizon. */
      readonly horizonV: number;
      /** Texture v per radian of elevation (positive: upward moves toward the top, v = 0). */
      readonly vPerRadian: number;
    };

/**
 * A diffuse (Lambertian) surface that may also emit.
 * - Reflection happens on both sides of a triangle.
 * - Emission is one-sided: a triangle emits only on the side its geometric normal
 *   (v1 - v0) x (v2 - v0) faces, i.e. the side from which the vertices appear counter-clockwise.
 * - Textures multiply the constant colours (after decoding sRGB to linear).
 */
export interface Material {
  readonly name: string;
  /** Diffuse reflectance per linear RGB channel, each in [0, 1]. */
  readonly albedo: Vec3;
  /** Emitted radiance per linear RGB channel (W·sr⁻¹·m⁻² in scene units), each ≥ 0. */
  readonly emission: Vec3;
  /** Index into Scene.textures multiplying albedo (and giving alpha for 'mask'). */
  readonly albedoTexture?: number;
  /** Index into Scene.textures multiplying emission. */
  readonly emissionTexture?: number;
  /** Default uv. */
  readonly emissionMapping?: EmissionMapping;
  /**
   * 'mask': where the albedo texture's alpha is below 0.5 the surface is not there: every ray,
   * shadow rays included, passes through (Doom's masked middle textures). Default 'opaque'.
   */
  readonly alphaMode?: 'opaque' | 'mask';
}

/**
 * A small spherical light the viewer carries at the camera (a torch). Sampled by next-event
 * estimation only: it is not geometry, so it never blocks or appears in view.
 */
export interface Torch {
  /** Linear RGB colour, each channel in [0, 1]. */
  readonly color: Vec3;
  /** Radiant intensity in W/sr (scene units) before the range window. */
  readonly intensity: number;
  /** Distance at which the light has faded to zero (a smooth window, see shaders/scene/torch.wgsl). */
  readonly range: number;
  /** Radius of the sphere, for soft shadows. */
  readonly radius: number;
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
  /**
   * The camera's exposure compensation in stops (default 0): radiance is scaled by 2^stops before
   * tone mapping. A user's exposure setting adds to it.
   */
  readonly exposureStops?: number;
}

export interface Scene {
  readonly name: string;
  readonly meshes: readonly Mesh[];
  readonly materials: readonly Material[];
  readonly textures?: readonly Texture[];
  readonly camera: Camera;
  /** A light the viewer carries, on by default where the scene has one (Doom maps). */
  readonly torch?: Torch;
  /** Size of one scene unit in metres, when known (Cornell box: 0.001; Doom: 1/32). */
  readonly metersPerUnit?: number;
  /** The floor plan a viewer can walk on (Doom maps), with the walker's dimensions. */
  readonly walkMap?: WalkMap;
}
