/**
 * Whether a model gets the default sky: decided by how much light its own emitters deliver, not by
 * whether it has any. An emissive texture that is black but for a few glowing details (DamagedHelmet's
 * visor) makes every triangle an emitter, yet lights nothing; a Cornell box's ceiling panel lights
 * the whole box. docs/environment.md ("The default sky") states the rule for users.
 *
 * Both sides are compared as mean irradiance on the scene's surfaces, as each would be shown (after
 * the exposure it comes with):
 *
 * - Own light: E_own = 2^stops · ((Σ Φ_emitter + Σ Φ_punctual) / A + Σ E_directional / 4). A Lambertian
 *   emitter of radiance L and area a sends Φ = π L a (both faces when two-sided); L is the luminance of
 *   its emission times the emission texture's mean over the primitive's uv footprint. A is the area of
 *   every surface that reflects light (world space). If all the power landed on the scene, Φ / A would
 *   be its mean first-bounce irradiance: nearly so in an enclosure lit by a panel; on an open object
 *   whose emitters face outward the light leaves and Φ / A is π times the surfaces' mean emitted
 *   radiance, how bright the emitters look. Either way it is the brightness scale of the image the
 *   emitters alone make. A directional light gives a surface facing it E, and a convex surface E / 4
 *   on average (its shadow is a quarter of its area); a point light's 4πI is power like an emitter's.
 *   `stops` is the camera's exposure compensation, which stays when no sky is added.
 * - The default sky: E_sky = 2^DAYLIGHT_EXPOSURE_STOPS · ¼ ∫ L_sky(ω) dω, sun included: a sphere of
 *   radius r intercepts πr² of each direction's radiance and has 4πr² of area, so this is the mean
 *   irradiance on a sphere under the sky, at the daylight exposure the sky brings (scene/sky.ts).
 *
 * The sky is added when E_own < OWN_LIGHT_SHARE · E_sky. Pure: loaders call withDefaultLight, the
 * CLI and the page show its note.
 */
import { determinant3 } from '../math/mat4.ts';
import { luminance } from '../math/vec3.ts';
import type { Environment } from './environment.ts';
import { withEnvironment } from './environment-override.ts';
import { punctualPower } from './punctual-power.ts';
import { DAYLIGHT_EXPOSURE_STOPS, SkyModel } from './sky.ts';
import type { Instance, Material, Mesh, Scene, Texture, TextureRef } from './types.ts';

/** What lights a model whose emitters cannot: a clear afternoon sky. */
export const DEFAULT_SKY: Extract<Environment, { kind: 'sky' }> = Object.freeze({ kind: 'sky', sunElevationDeg: 40, sunAzimuthDeg: 30, turbidity: 3, groundAlbedo: 0.3, intensity: 1 });

/**
 * Below this share of the default sky's light (as exposed), the emitters do not light the model and
 * the sky is added: 1/16, four stops. Four stops under a well-exposed image, mid-grey reads about
 * 0.1 in sRGB, where the image stops being lit; a Cornell box's ceiling light of the original
 * measurements (radiance ~12 in luminance) gives about a third of the sky's light, DamagedHelmet's
 * glowing details about half a per cent.
 */
export const OWN_LIGHT_SHARE = 1 / 16;

export interface LightingDecision {
  /** Whether the default sky lights the scene. */
  readonly sky: boolean;
  /** E_own / E_sky (see the module comment); 0 without emitters or lights. */
  readonly share: number;
  /** Whether the scene has any emitter or punctual light at all. */
  readonly hasLights: boolean;
  /** What was decided and why, for the user: information, not a warning. */
  readonly note: string;
}

/** The scene with the default sky added where its own light is too little (the decision's note in `lightingNote`). */
export function withDefaultLight(scene: Scene): Scene {
  const decision = decideDefaultLight(scene);
  const lit = decision.sky ? withEnvironment(scene, DEFAULT_SKY) : scene;
  return { ...lit, lightingNote: decision.note };
}

export function decideDefaultLight(scene: Pick<Scene, 'meshes' | 'instances' | 'materials' | 'textures' | 'lights' | 'camera'>): LightingDecision {
  const own = ownIrradiance(scene);
  const share = own.irradiance / defaultSkyIrradiance();
  const sky = share < OWN_LIGHT_SHARE;
  const note = !own.hasLights
    ? 'the model has no light of its own; a default sky lights it'
    : sky
      ? `its emitters give ${describeShare(share)}; a default sky lights it`
      : `its own lights light it (${describeShare(share)}); no sky is added`;
  return { sky, share, hasLights: own.hasLights, note };
}

/** "0.31 % of the light of a default sky", "3.1 times …": two figures, as the estimate deserves no more. */
export function describeShare(share: number): string {
  const sky = 'the light of a default sky';
  if (!(share > 0)) return `none of ${sky}`;
  if (share === Infinity) return `more than ${sky} (nothing in the scene reflects)`;
  if (share >= 2) return `${Number(share.toPrecision(2))} times ${sky}`;
  const percent = share * 100;
  return percent < 0.001 ? `less than 0.001 % of ${sky}` : `${Number(percent.toPrecision(2))} % of ${sky}`;
}

/**
 * E_own of the module comment, in the scene's radiance units as shown at the camera's exposure, and
 * whether there is any emitter or light at all.
 */
export function ownIrradiance(scene: Pick<Scene, 'meshes' | 'instances' | 'materials' | 'textures' | 'lights' | 'camera'>): { irradiance: number; hasLights: boolean } {
  const means = new EmissionMeans(scene.textures ?? []);
  // Meshes are summed once per material override and scaled per instance: EXT_mesh_gpu_instancing
  // can place one mesh many thousand times.
  const perMesh = new Map<string, MeshLight>();
  let area = 0, power = 0, hasLights = false;
  for (const instance of scene.instances) {
    const mesh = scene.meshes[instance.mesh];
    if (!mesh) continue;
    const key = `${instance.mesh}:${instance.material ?? ''}`;
    let sums = perMesh.get(key);
    if (!sums) perMesh.set(key, (sums = meshLight(mesh, instance, scene.materials, means)));
    // Areas scale by |det|^(2/3) under a similarity; for a shear or non-uniform scale that is the
    // mean over orientations, close enough for an estimate.
    const areaScale = Math.abs(determinant3(instance.worldFromObject)) ** (2 / 3);
    if (!Number.isFinite(areaScale)) continue;
    area += sums.area * areaScale;
    power += sums.power * areaScale;
    hasLights ||= sums.emits;
  }
  let directional = 0;
  for (const light of scene.lights ?? []) {
    // A directional light's irradiance E, not its power: see the E / 4 above.
    const p = light.kind === 'directional' ? light.irradiance * luminance(light.color) : punctualPower(light, 0);
    if (!(p > 0)) continue;
    hasLights = true;
    if (light.kind === 'directional') directional += p / 4;
    else power += p;
  }
  // A scene of emitters only has nothing for a sky to light: its own light is all there is to see.
  const fromPower = power > 0 ? (area > 0 ? power / area : Infinity) : 0;
  return { irradiance: 2 ** (scene.camera.exposureStops ?? 0) * (fromPower + directional), hasLights };
}

interface MeshLight {
  /** Object-space area of the surfaces that reflect light. */
  readonly area: number;
  /** Object-space luminous power of the emitters, π L a each. */
  readonly power: number;
  /** Whether any primitive has an emitting material (however dark its texture). */
  readonly emits: boolean;
}

function meshLight(mesh: Mesh, instance: Instance, materials: readonly Material[], means: EmissionMeans): MeshLight {
  let area = 0, power = 0, emits = false;
  const materialOf = (own: number) => materials[instance.material ?? own];
  /** Adds a primitive's area; returns the power it emits before its emission texture (π L a; 0: none). */
  const surface = (material: Material | undefined, a: number): number => {
    // A degenerate or non-finite primitive (validation refuses the latter later) adds nothing.
    if (!material || !(a > 0 && a < Infinity)) return 0;
    if (material.kind !== 'emissive') area += a;
    const y = luminance(material.emission);
    if (!(y > 0)) return 0;
    emits = true;
    return Math.PI * y * a * (material.twoSidedEmission ? 2 : 1);
  };
  /** The whole emission texture's mean (1 without one): a panorama-mapped emitter's, an analytic shape's (its uv covers the texture). */
  const wholeMean = (material: Material) => (material.emissionTexture ? means.whole(material.emissionTexture.texture) : 1);

  const p = mesh.positions, idx = mesh.indices;
  for (let t = 0; t < idx.length / 3; t++) {
    const v0 = idx[3 * t]!, v1 = idx[3 * t + 1]!, v2 = idx[3 * t + 2]!;
    const ax = p[3 * v1]! - p[3 * v0]!, ay = p[3 * v1 + 1]! - p[3 * v0 + 1]!, az = p[3 * v1 + 2]! - p[3 * v0 + 2]!;
    const bx = p[3 * v2]! - p[3 * v0]!, by = p[3 * v2 + 1]! - p[3 * v0 + 1]!, bz = p[3 * v2 + 2]! - p[3 * v0 + 2]!;
    const cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
    const material = materialOf(mesh.materialIds[t]!);
    const emitted = surface(material, 0.5 * Math.sqrt(cx * cx + cy * cy + cz * cz));
    if (emitted === 0) continue;
    const texture = material!.emissionTexture;
    power += emitted * (texture && material!.emissionMapping?.kind !== 'panorama' ? means.overTriangle(texture, mesh, v0, v1, v2) : wholeMean(material!));
  }
  const spheres = mesh.spheres;
  for (let s = 0; s < (spheres?.radii.length ?? 0); s++) {
    const r = spheres!.radii[s]!, material = materialOf(spheres!.materialIds[s]!);
    const emitted = surface(material, 4 * Math.PI * r * r);
    if (emitted > 0) power += emitted * wholeMean(material!);
  }
  const capsules = mesh.capsules;
  for (let c = 0; c < (capsules?.radii.length ?? 0); c++) {
    const r = capsules!.radii[c]!, e = capsules!.endpoints, material = materialOf(capsules!.materialIds[c]!);
    const h = Math.hypot(e[6 * c + 3]! - e[6 * c]!, e[6 * c + 4]! - e[6 * c + 1]!, e[6 * c + 5]! - e[6 * c + 2]!);
    const emitted = surface(material, 2 * Math.PI * r * h + 4 * Math.PI * r * r);
    if (emitted > 0) power += emitted * wholeMean(material!);
  }
  return { area, power, emits };
}

/** The sRGB electro-optical transfer function (IEC 61966-2-1) for each 8-bit code. */
const SRGB_TO_LINEAR = Float64Array.from({ length: 256 }, (_, c) => {
  const v = c / 255;
  return v <= 0.04045 ? v / 12.92 : ((v + 0.055) / 1.055) ** 2.4;
});

/** 8-bit codes of linear data. */
const LINEAR = Float64Array.from({ length: 256 }, (_, c) => c / 255);

/**
 * At most this many cells a side in a texture's table of sums: a larger texture is averaged down
 * first (an 8K texture's table would take half a gigabyte; a power estimate needs no more detail).
 */
const MAX_TABLE_SIDE = 1024;

/**
 * Means of emission textures (linear luminance) over uv rectangles, from a summed-area table per
 * texture (F. Crow, "Summed-area tables for texture mapping", SIGGRAPH 1984), built when first asked.
 * Lookups repeat, as the renderer's do.
 */
class EmissionMeans {
  private readonly tables = new Map<number, SumTable>();

  constructor(private readonly textures: readonly Texture[]) {}

  /** The mean over the whole texture (0 for a texture index that names none). */
  whole(texture: number): number {
    const t = this.table(texture);
    return t ? t.total / (t.width * t.height) : 0;
  }

  /**
   * The mean over the uv bounding box of a triangle's texture coordinates (after the reference's
   * transform), at least one cell wide: a box holds its triangle, and over a mesh's many triangles
   * the excess averages out. Without the uv set, every vertex reads (0, 0), as on the GPU.
   */
  overTriangle(ref: TextureRef, mesh: Mesh, i0: number, i1: number, i2: number): number {
    const t = this.table(ref.texture);
    if (!t) return 0;
    const uvs = ref.texCoord === 1 ? mesh.uvs1 : mesh.uvs;
    let u0 = Infinity, u1 = -Infinity, v0 = Infinity, v1 = -Infinity;
    const tr = ref.transform;
    const c = Math.cos(tr?.rotation ?? 0), s = Math.sin(tr?.rotation ?? 0);
    const sx = tr?.scale[0] ?? 1, sy = tr?.scale[1] ?? 1, ox = tr?.offset[0] ?? 0, oy = tr?.offset[1] ?? 0;
    for (let k = 0; k < 3; k++) {
      const i = k === 0 ? i0 : k === 1 ? i1 : i2;
      const u = uvs?.[2 * i] ?? 0, v = uvs?.[2 * i + 1] ?? 0;
      // KHR_texture_transform, as the packer writes it (gpu/pack/material-pack.ts transformWriter).
      const tu = c * sx * u + s * sy * v + ox, tv = -s * sx * u + c * sy * v + oy;
      u0 = Math.min(u0, tu);
      u1 = Math.max(u1, tu);
      v0 = Math.min(v0, tv);
      v1 = Math.max(v1, tv);
    }
    // Coordinates that are not numbers (validation refuses them later): the texture's mean.
    if (!Number.isFinite(u0 + u1 + v0 + v1)) return t.total / (t.width * t.height);
    // Moved by whole repeats into the first one, so that far-off coordinates keep their precision.
    const du = Math.floor(u0), dv = Math.floor(v0);
    return t.meanOver((u0 - du) * t.width, (u1 - du) * t.width, (v0 - dv) * t.height, (v1 - dv) * t.height);
  }

  private table(index: number): SumTable | undefined {
    let t = this.tables.get(index);
    if (!t) {
      const texture = this.textures[index];
      if (!texture || texture.width < 1 || texture.height < 1) return undefined;
      this.tables.set(index, (t = new SumTable(texture)));
    }
    return t;
  }
}

/** A summed-area table of a texture's linear luminance, over a grid of at most MAX_TABLE_SIDE cells a side. */
class SumTable {
  readonly width: number;
  readonly height: number;
  readonly total: number;
  /** (width + 1) × (height + 1): sums[y][x] = Σ of the cells left of x and above y. */
  private readonly sums: Float64Array;

  constructor(texture: Texture) {
    const w = texture.width, h = texture.height;
    this.width = Math.min(w, MAX_TABLE_SIDE);
    this.height = Math.min(h, MAX_TABLE_SIDE);
    const cw = this.width, ch = this.height;
    // Each texel's luminance into the cell that holds it; cells hold the mean of their texels.
    const cells = new Float64Array(cw * ch), counts = new Float64Array(cw * ch);
    const decode = texture.encoding === 'linear' ? LINEAR : SRGB_TO_LINEAR;
    const column = Int32Array.from({ length: w }, (_, x) => Math.floor((x * cw) / w));
    const rgba = texture.rgba;
    for (let y = 0, o = 0; y < h; y++) {
      const row = Math.floor((y * ch) / h) * cw;
      for (let x = 0; x < w; x++, o += 4) {
        const cell = row + column[x]!;
        cells[cell]! += 0.2126 * decode[rgba[o]!]! + 0.7152 * decode[rgba[o + 1]!]! + 0.0722 * decode[rgba[o + 2]!]!;
        counts[cell]! += 1;
      }
    }
    const stride = cw + 1;
    this.sums = new Float64Array(stride * (ch + 1));
    for (let y = 0; y < ch; y++) {
      let row = 0;
      for (let x = 0; x < cw; x++) {
        row += cells[y * cw + x]! / counts[y * cw + x]!;
        this.sums[(y + 1) * stride + x + 1] = this.sums[y * stride + x + 1]! + row;
      }
    }
    this.total = this.sums[ch * stride + cw]!;
  }

  /** The mean over [x0, x1] × [y0, y1] in cells (any reals: the texture repeats), widened to one cell at least. */
  meanOver(x0: number, x1: number, y0: number, y1: number): number {
    if (x1 - x0 < 1) [x0, x1] = [(x0 + x1 - 1) / 2, (x0 + x1 + 1) / 2];
    if (y1 - y0 < 1) [y0, y1] = [(y0 + y1 - 1) / 2, (y0 + y1 + 1) / 2];
    const integral = this.repeated(x1, y1) - this.repeated(x0, y1) - this.repeated(x1, y0) + this.repeated(x0, y0);
    return Math.max(0, integral / ((x1 - x0) * (y1 - y0)));
  }

  /** ∫₀ˣ∫₀ʸ of the repeated texture, cells as unit squares. */
  private repeated(x: number, y: number): number {
    const qx = Math.floor(x / this.width), qy = Math.floor(y / this.height);
    const rx = x - qx * this.width, ry = y - qy * this.height;
    return qx * qy * this.total + qx * this.within(this.width, ry) + qy * this.within(rx, this.height) + this.within(rx, ry);
  }

  /** ∫₀ˣ∫₀ʸ for 0 ≤ x ≤ width, 0 ≤ y ≤ height: the table's corners interpolated bilinearly, which is exact for cells of constant value. */
  private within(x: number, y: number): number {
    const i = Math.min(Math.floor(x), this.width - 1), j = Math.min(Math.floor(y), this.height - 1);
    const a = x - i, b = y - j, stride = this.width + 1, s = this.sums;
    const s00 = s[j * stride + i]!, s01 = s[j * stride + i + 1]!, s10 = s[(j + 1) * stride + i]!, s11 = s[(j + 1) * stride + i + 1]!;
    return s00 + a * (s01 - s00) + b * (s10 - s00) + a * b * (s11 - s01 - s10 + s00);
  }
}

let skyIrradiance: number | undefined;

/**
 * E_sky of the module comment, luminance: ¼ ∫ L dω over the sphere of directions (the upper
 * hemisphere by the midpoint rule in (cos θ, φ), the uniform ground below, the sun's disk), at the
 * daylight exposure. Computed once.
 */
export function defaultSkyIrradiance(): number {
  if (skyIrradiance !== undefined) return skyIrradiance;
  const model = new SkyModel(DEFAULT_SKY);
  const rows = 64, columns = 128;
  const s = model.sunDirection;
  let upper = 0;
  for (let j = 0; j < rows; j++) {
    const ct = (j + 0.5) / rows, st = Math.sqrt(1 - ct * ct);
    for (let k = 0; k < columns; k++) {
      const phi = ((k + 0.5) / columns) * 2 * Math.PI;
      const dx = st * Math.sin(phi), dz = st * Math.cos(phi);
      upper += luminance(model.skyRadiance(ct, dx * s[0] + ct * s[1] + dz * s[2]));
    }
  }
  const cell = (1 / rows) * ((2 * Math.PI) / columns);
  const ground = 2 * Math.PI * luminance(model.radiance([0, -1, 0]));
  const sun = 2 * Math.PI * (1 - model.sunCosMax) * luminance(model.sunRadiance);
  skyIrradiance = (DEFAULT_SKY.intensity * 2 ** DAYLIGHT_EXPOSURE_STOPS * (upper * cell + ground + sun)) / 4;
  return skyIrradiance;
}
