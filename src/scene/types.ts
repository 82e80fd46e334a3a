/**
 * The neutral scene model every loader produces and the renderer consumes. Renderer-agnostic: no GPU
 * types, no DOM, no file access. Units are whatever the source uses (millimetres for the Cornell box,
 * map units for Doom, metres for glTF); the renderer never assumes a scale.
 *
 * Geometry is meshes in object space placed by instances (a world-from-object transform each), so a
 * mesh used twice is stored once and an object can move without touching its vertices. The flat
 * world-space triangle list the BVH is built over is a build product (scene/triangles.ts), not the
 * model. Materials are a closed union keyed by `kind`; the WGSL twin of each kind is one case of
 * shaders/scene/bsdf.wgsl.
 */
import type { Mat4 } from '../math/mat4.ts';
import type { Vec3 } from '../math/vec3.ts';
import type { Dispersion } from './dispersion.ts';
import type { SceneDynamics } from './dynamics-types.ts';
import type { Environment } from './environment.ts';
import type { WalkMap } from './walk-map.ts';

export type { Environment, EnvironmentImage } from './environment.ts';
export type { Dispersion } from './dispersion.ts';

/**
 * How a texture's colour channels are stored: 'srgb' for colour (base colour, emission: decoded to
 * linear when sampled), 'linear' for data (normals, metallic-roughness, transmission).
 */
export type TextureEncoding = 'srgb' | 'linear';

/**
 * An image for materials: 8-bit RGBA, row-major, top row first. Alpha is linear coverage (0 = a
 * hole). (u, v) = (0, 0) is the top-left corner of the image and one unit covers the whole image;
 * lookups wrap (repeat).
 */
export interface Texture {
  readonly name: string;
  readonly width: number;
  readonly height: number;
  readonly rgba: Uint8Array;
  /** Default 'srgb'. */
  readonly encoding?: TextureEncoding;
  /** Magnification filter: 'bilinear' (default) or 'nearest' (Doom's texels, seen as pixels). */
  readonly filter?: 'nearest' | 'bilinear';
}

/** KHR_texture_transform: uv' = T(offset) · R(rotation) · S(scale) · uv. */
export interface UvTransform {
  readonly offset: readonly [number, number];
  /** Radians, counter-clockwise in uv space. */
  readonly rotation: number;
  readonly scale: readonly [number, number];
}

/** A material's use of a texture: which one, which uv set, and an optional transform. */
export interface TextureRef {
  /** Index into Scene.textures. */
  readonly texture: number;
  /** Which uv set of the mesh (0 = Mesh.uvs, 1 = Mesh.uvs1). Default 0. */
  readonly texCoord?: 0 | 1;
  readonly transform?: UvTransform;
}

/** A tangent-space normal map (glTF normalTexture): n = normalize((2·rgb − 1) · (scale, scale, 1)). */
export interface NormalTextureRef extends TextureRef {
  /** Default 1. */
  readonly scale?: number;
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
 * What every material kind has: emission and coverage.
 * - Emission is one-sided: a triangle emits only on the side its geometric normal
 *   (v1 - v0) x (v2 - v0) faces, i.e. the side from which the vertices appear counter-clockwise.
 * - Textures multiply the constant factors (after decoding sRGB to linear).
 */
interface MaterialBase {
  readonly name: string;
  /** Emitted radiance per linear RGB channel (W·sr⁻¹·m⁻² in scene units), each ≥ 0. */
  readonly emission: Vec3;
  /** Multiplies emission (sRGB). */
  readonly emissionTexture?: TextureRef;
  /** Default uv. */
  readonly emissionMapping?: EmissionMapping;
  /**
   * Both faces of a triangle emit `emission` (default false: only the front, see above). For thin
   * emitters seen from both sides: Doom's torches and lamps, which are sprites turned toward the viewer.
   */
  readonly twoSidedEmission?: boolean;
  /**
   * Coverage, from the alpha of the colour texture (albedo / base colour) times any constant opacity:
   * - 'opaque' (default): alpha is ignored;
   * - 'mask': where alpha is below `alphaCutoff` the surface is not there for any ray, shadow rays
   *   included (Doom's masked middle textures, glTF MASK);
   * - 'blend': the surface is there with probability alpha (stochastic transparency, glTF BLEND).
   */
  readonly alphaMode?: 'opaque' | 'mask' | 'blend';
  /** Default 0.5. */
  readonly alphaCutoff?: number;
  /**
   * glTF's doubleSided (default true), kept so exporters write it back. Light transport treats every
   * surface as two-sided (a closed model's back faces are never seen; culling the backs of an open
   * one would cost every glTF scene the traversal's hit filter), so rendering does not depend on it.
   */
  readonly doubleSided?: boolean;
  /** Tangent-space normal map (needs Mesh.tangents or derives them from uvs). */
  readonly normalTexture?: NormalTextureRef;
}

/** A Lambertian reflector, both sides. */
export interface DiffuseMaterial extends MaterialBase {
  readonly kind: 'diffuse';
  /** Diffuse reflectance per linear RGB channel, each in [0, 1]. */
  readonly albedo: Vec3;
  /** Multiplies albedo (sRGB; its alpha is the coverage for 'mask' and 'blend'). */
  readonly albedoTexture?: TextureRef;
  /**
   * A convergence aid for flat scenes (the prism): scatter only into directions perpendicular to this
   * world-space unit vector (the normal of the scene's plane), cosine-weighted on that half circle,
   * with albedo `albedo`. A delta lobe across the plane: lights are found by scattered rays alone.
   * Not a physical material; a screen lit through glass converges where a Lambertian one would not.
   */
  readonly scatterPlaneNormal?: Vec3;
}

/**
 * The glTF 2.0 metallic-roughness model (glTF 2.0 Appendix B) with KHR_materials_ior, _specular,
 * _transmission and _volume: a dielectric base (diffuse, or transmission) under a specular layer
 * with F0 from ior and specular, mixed with a metal of F0 = base colour by `metallic`.
 */
export interface MetallicRoughnessMaterial extends MaterialBase {
  readonly kind: 'metallic-roughness';
  /** Linear RGB in [0, 1]. */
  readonly baseColor: Vec3;
  /** baseColorFactor's alpha, in [0, 1]. */
  readonly opacity: number;
  /** Multiplies baseColor (sRGB) and opacity (alpha). */
  readonly baseColorTexture?: TextureRef;
  readonly metallic: number;
  /** Perceptual roughness in [0, 1]; GGX α = roughness². */
  readonly roughness: number;
  /** Linear; G multiplies roughness, B multiplies metallic. */
  readonly metallicRoughnessTexture?: TextureRef;
  /** Default 1.5. The index at 589.3 nm when `dispersion` is given. */
  readonly ior: number;
  /**
   * KHR_materials_dispersion: how the index varies with wavelength (scene/dispersion.ts), for volumetric
   * transmission (thickness > 0). Only spectral rendering sees it; RGB rendering uses `ior`.
   */
  readonly dispersion?: Dispersion;
  /** KHR_materials_specular: strength of the dielectric specular layer (default 1). */
  readonly specular: number;
  /** Linear; A multiplies specular. */
  readonly specularTexture?: TextureRef;
  /** KHR_materials_specular: tint of the dielectric F0 (default 1, 1, 1). */
  readonly specularColor: Vec3;
  /** sRGB; RGB multiplies specularColor. */
  readonly specularColorTexture?: TextureRef;
  /** KHR_materials_transmission (default 0). */
  readonly transmission: number;
  /** Linear; R multiplies transmission. */
  readonly transmissionTexture?: TextureRef;
  /**
   * KHR_materials_volume: 0 (default) is thin-walled (transmission does not bend rays); > 0 the mesh
   * bounds a volume whose interface refracts.
   */
  readonly thickness: number;
  /** Beer–Lambert: after this distance (scene units) light inside keeps `attenuationColor`. Infinity: clear. */
  readonly attenuationDistance: number;
  readonly attenuationColor: Vec3;
}

/** Glass: Fresnel reflection and refraction at a smooth (roughness 0) or rough interface. */
export interface DielectricMaterial extends MaterialBase {
  readonly kind: 'dielectric';
  /** Index of refraction (at 589.3 nm when `dispersion` is given). */
  readonly ior: number;
  /** How the index varies with wavelength (scene/dispersion.ts; GLASSES names catalogue glasses). Spectral rendering only. */
  readonly dispersion?: Dispersion;
  /** Perceptual roughness in [0, 1] (0: a perfect, delta interface). */
  readonly roughness: number;
  /** Transmission tint at the interface, linear RGB (1, 1, 1: clear). */
  readonly tint: Vec3;
  /** Beer–Lambert absorption inside, as in MetallicRoughnessMaterial. Infinity: none. */
  readonly attenuationDistance: number;
  readonly attenuationColor: Vec3;
}

/** A surface that only emits: black to every incoming ray (lamps, light panels, the sky behind Doom's F_SKY1). */
export interface EmissiveMaterial extends MaterialBase {
  readonly kind: 'emissive';
}

export type Material = DiffuseMaterial | MetallicRoughnessMaterial | DielectricMaterial | EmissiveMaterial;
export type MaterialKind = Material['kind'];

/**
 * The colour texture whose alpha gives coverage (albedo or base colour), and the constant opacity.
 * One place for the rule, used by packing, validation and the exporters.
 */
export function coverageOf(material: Material): { readonly texture?: TextureRef; readonly opacity: number } {
  switch (material.kind) {
    case 'diffuse':
      return { ...(material.albedoTexture ? { texture: material.albedoTexture } : {}), opacity: 1 };
    case 'metallic-roughness':
      return { ...(material.baseColorTexture ? { texture: material.baseColorTexture } : {}), opacity: material.opacity };
    case 'dielectric':
    case 'emissive':
      return { opacity: 1 };
  }
}

/** A material's diffuse-equivalent colour: what a debug 'albedo' view, the exporters and the denoiser show. */
export function baseColorOf(material: Material): Vec3 {
  switch (material.kind) {
    case 'diffuse':
      return material.albedo;
    case 'metallic-roughness':
      return material.baseColor;
    case 'dielectric':
      return material.tint;
    case 'emissive':
      return [0, 0, 0];
  }
}

/** A Lambertian material: the one kind the Doom loader, the studio and the built-in boxes use. */
export function diffuse(name: string, albedo: Vec3, emission: Vec3 = [0, 0, 0], extra: Partial<Omit<DiffuseMaterial, 'kind' | 'name' | 'albedo' | 'emission'>> = {}): DiffuseMaterial {
  return { kind: 'diffuse', name, albedo, emission, ...extra };
}

/** A glTF metallic-roughness material with the specification's defaults for everything not given (glTF 2.0 and its KHR_materials_* extensions). */
export function metallicRoughness(name: string, fields: Partial<Omit<MetallicRoughnessMaterial, 'kind' | 'name'>> = {}): MetallicRoughnessMaterial {
  return {
    kind: 'metallic-roughness',
    name,
    emission: [0, 0, 0],
    baseColor: [1, 1, 1],
    opacity: 1,
    metallic: 1,
    roughness: 1,
    ior: 1.5,
    specular: 1,
    specularColor: [1, 1, 1],
    transmission: 0,
    thickness: 0,
    attenuationDistance: Infinity,
    attenuationColor: [1, 1, 1],
    ...fields,
  };
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

/**
 * Punctual lights (KHR_lights_punctual), in world space. Not geometry: sampled by next-event
 * estimation only. Intensities are radiometric in scene units (glTF's candela and lux are taken as
 * W/sr and W/m² one to one).
 */
export type PunctualLight =
  | {
      readonly kind: 'point';
      readonly name: string;
      readonly position: Vec3;
      readonly color: Vec3;
      /** Radiant intensity, W/sr. */
      readonly intensity: number;
      /** Distance beyond which it is cut off (glTF range), or Infinity. */
      readonly range: number;
    }
  | {
      readonly kind: 'spot';
      readonly name: string;
      readonly position: Vec3;
      /** Unit direction the light shines in. */
      readonly direction: Vec3;
      readonly color: Vec3;
      readonly intensity: number;
      readonly range: number;
      /** Radians: full intensity inside the inner cone, smoothly zero at the outer one. */
      readonly innerConeAngle: number;
      readonly outerConeAngle: number;
    }
  | {
      readonly kind: 'directional';
      readonly name: string;
      /** Unit direction the light travels in (from the light toward the scene). */
      readonly direction: Vec3;
      readonly color: Vec3;
      /** Irradiance on a surface facing the light, W/m². */
      readonly irradiance: number;
    };

/** An indexed triangle mesh in object space. */
export interface Mesh {
  readonly name: string;
  /** xyz per vertex, object space. */
  readonly positions: Float32Array;
  /** Three vertex indices per triangle. */
  readonly indices: Uint32Array;
  /** Optional unit shading normal per vertex (xyz). Absent: the geometric normal is used. */
  readonly normals?: Float32Array;
  /** Optional texture coordinate per vertex (uv), set 0. */
  readonly uvs?: Float32Array;
  /** Optional second texture coordinate set. */
  readonly uvs1?: Float32Array;
  /** Optional tangent per vertex (xyz + w = bitangent sign), for normal maps (glTF TANGENT). */
  readonly tangents?: Float32Array;
  /** One index into `Scene.materials` per triangle. */
  readonly materialIds: Uint32Array;
  /**
   * Analytic spheres and capsules placed with the triangles. An instance of a mesh that has them must
   * be a similarity (rotation, uniform scale, translation; validate.ts checks), so a sphere stays a sphere.
   */
  readonly spheres?: SphereSet;
  readonly capsules?: CapsuleSet;
  /**
   * Morph targets (glTF 2.0 §3.7.2.2): per target, a displacement of every vertex (xyz), and of every
   * uv where given; the mesh's vertices are base + Σ weightᵢ · targetᵢ. Weights start at 0 (the
   * base mesh) and change through SceneUpdate.morphWeights (Doom's doors and lifts: a sector's floor
   * and ceiling as two targets). Triangles only. A morphed mesh's BVH is refitted, not rebuilt.
   */
  readonly morphTargets?: readonly MorphTarget[];
}

/** One morph target of a Mesh: displacements per vertex. */
export interface MorphTarget {
  /** xyz per vertex. */
  readonly positions: Float32Array;
  /** uv per vertex (set 0), or absent (uvs do not move). */
  readonly uvs?: Float32Array;
}

/**
 * Spheres: an analytic primitive, intersected exactly (no tessellation) in the same BVH as the
 * triangles. Both sides are surfaces (glass works from inside); emission leaves the outside.
 * uv: u = longitude / 2π around the object's +y axis from +z (as scene/shapes.ts uvSphere), v =
 * colatitude / π from +y (0 at the top).
 */
export interface SphereSet {
  /** xyz per sphere, object space. */
  readonly centers: Float32Array;
  /** One radius (> 0) per sphere, object space. */
  readonly radii: Float32Array;
  /** One index into `Scene.materials` per sphere. */
  readonly materialIds: Uint32Array;
}

/**
 * Capsules: every point within `radius` of the segment a–b (a cylinder closed by two hemispheres), an
 * analytic primitive like SphereSet. Molecules draw bonds with them. uv: u around the axis, v from a
 * (0) to b (1) along it.
 */
export interface CapsuleSet {
  /** Six floats per capsule: a xyz, b xyz (object space; a = b gives a sphere). */
  readonly endpoints: Float32Array;
  /** One radius (> 0) per capsule. */
  readonly radii: Float32Array;
  readonly materialIds: Uint32Array;
}

/** One placement of a mesh in the world. */
export interface Instance {
  /** Stable across scene updates (a moving object keeps its id), unique in the scene. */
  readonly id: number;
  readonly name?: string;
  /** Index into Scene.meshes. */
  readonly mesh: number;
  /** Column-major 4×4 affine transform, world from object (as glTF stores matrices). */
  readonly worldFromObject: Mat4;
  /** The instance may move between frames (doors, lifts, the phantom). Default false. */
  readonly moves?: boolean;
  /** Index into Scene.materials replacing every material of the mesh (one sphere mesh, many materials). */
  readonly material?: number;
}

/**
 * A thin lens (pbrt-v4 §5.2.3): rays start on a disk of `apertureRadius` around the camera position,
 * in the plane facing `forward`, and converge on the plane at `focusDistance` along forward, which
 * stays sharp. Scene units.
 */
export interface ThinLens {
  /**
   * Radius of the aperture disk (≥ 0; 0 renders as a pinhole but keeps its focus distance, as the
   * panel's slider at 0 does; a scene without depth of field simply has no lens). Ray Tracing in One
   * Weekend's `aperture` is the diameter. scene/lens.ts converts f-numbers.
   */
  readonly apertureRadius: number;
  /** Distance from the lens to the plane in focus, measured along forward (> 0). */
  readonly focusDistance: number;
}

/** A pinhole or thin-lens camera. `forward` and `up` need not be unit length nor exactly orthogonal. */
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
  /** Depth of field. Absent: a pinhole (everything sharp). */
  readonly lens?: ThinLens;
}

export interface Scene {
  readonly name: string;
  readonly meshes: readonly Mesh[];
  /** What is drawn: each mesh appears once per instance that names it (a mesh no instance names is not drawn). */
  readonly instances: readonly Instance[];
  readonly materials: readonly Material[];
  readonly textures?: readonly Texture[];
  readonly camera: Camera;
  /** What rays leaving the scene see. Absent: { kind: 'none' } (black). */
  readonly environment?: Environment;
  readonly lights?: readonly PunctualLight[];
  /**
   * A light the viewer carries, on by default where the scene has one (Doom and Wolfenstein maps, the
   * dungeon). Absent: the scene has no torch, and torch settings that do not give one do nothing.
   */
  readonly torch?: Torch;
  /**
   * True where the image's exposure should adapt to what is seen by default, as an eye walking from
   * a dark corridor into a lit room does (the game maps, whose rooms differ in brightness by many
   * stops). Absent: the camera's exposure is kept (reference scenes, whose brightness is the point).
   * The exposure setting overrides it (renderer/exposure.ts exposureChoice).
   */
  readonly autoExposure?: boolean;
  /** Size of one scene unit in metres, when known (Cornell box: 0.001; Doom: 1/32; glTF: 1). */
  readonly metersPerUnit?: number;
  /** The floor plan a viewer can walk on (Doom maps), with the walker's dimensions. */
  readonly walkMap?: WalkMap;
  /** What moves (scene/dynamics-types.ts; played by world/world.ts). Absent: a frozen scene. */
  readonly dynamics?: SceneDynamics;
  /**
   * A tile map's own grid, as a hint for the uniform-grid traversal (bvh/grid.ts, setting `accel`):
   * the corner of cell (0, 0, 0), one cell's size on each axis, and the cells on each axis (a
   * Wolfenstein map: 64 × 1 × 64 tiles). Absent: the grid's resolution is chosen from the primitives.
   */
  readonly tileGrid?: { readonly origin: Vec3; readonly cellSize: Vec3; readonly dims: readonly [number, number, number] };
  /** What the loader had to work around (a missing texture, an unsupported extension): shown once to the user. */
  readonly warnings?: readonly string[];
  /**
   * Whether the default sky was added or the scene's own lights light it, and why
   * (scene/default-light.ts): information for the user, not a warning. Dropped when another
   * environment replaces the scene's own (scene/environment-override.ts), as it then says nothing.
   */
  readonly lightingNote?: string;
}
