/**
 * Environment → the resources of group 0, bindings 8–11 (shaders/scene/bindings.wgsl), pure CPU.
 *
 * Every kind but 'none' becomes a lat-long radiance image (environment_map, top row = +y; f32 RGB
 * here, expanded to RGBA as it is uploaded bit for bit into an rgba32uint texture,
 * ENVIRONMENT_MAP_FORMAT, see bindings.wgsl):
 * constant → 1×1, gradient → 1×GRADIENT_ROWS, sky → SKY_WIDTH×SKY_HEIGHT (the sun's disk left out:
 * it is a light of its own), map → the image itself (rotation and intensity are applied at lookup).
 *
 * Importance sampling (pbrt-v4's PiecewiseConstant2D, Pharr et al. 4th ed. §A.5, over solid angle):
 * texel (i, j) gets probability ∝ w_ij · Ω_j, where Ω_j is the solid angle of a texel of row j and
 * w_ij the largest luminance in its 3×3 neighbourhood. Taking the neighbourhood's maximum makes the
 * density nonzero wherever the bilinear lookup (which blends the four surrounding texel centres) can
 * be nonzero, so no radiance is left unsampled. The shader picks a row from the marginal CDF, a
 * column from that row's conditional CDF, then a point uniform in solid angle inside the texel, so
 * pdf(ω) = w_ij / Σ w Ω — exactly 1/4π for a constant environment.
 */
import { LanternError } from '../../errors.ts';
import { luminance as luminanceOf, normalize, type Vec3 } from '../../math/vec3.ts';
import type { Environment, EnvironmentKind } from '../../scene/environment.ts';
import { SUN_ANGULAR_RADIUS_DEG, SkyModel } from '../../scene/sky.ts';
import { reflectModule, structLayout } from '../wgsl/reflect.ts';
import { StructArray } from './struct-array.ts';

/** Position = ENVIRONMENT_KIND_* in shaders/scene/environment-types.wgsl. */
export const ENVIRONMENT_KINDS: readonly EnvironmentKind[] = ['none', 'constant', 'gradient', 'sky', 'map'];
/** Flag bits of EnvironmentInfo.flags (environment-types.wgsl). */
export const ENVIRONMENT_HAS_MAP = 1;
export const ENVIRONMENT_HAS_SUN = 2;

/** Rows of a baked gradient: 0.7° each, smooth to the eye after bilinear filtering. */
export const GRADIENT_ROWS = 256;
/** The baked sky: 0.7° texels, fine enough for the sun's aureole. */
export const SKY_WIDTH = 512;
export const SKY_HEIGHT = 256;
/**
 * The texture format of environment_map: f32 texels uploaded as their bits (bytesPerRow = width × 16);
 * the shader bitcasts. rgba32float would be unfilterable, which a reflected texture_2d<f32> layout
 * cannot express.
 */
export const ENVIRONMENT_MAP_FORMAT: GPUTextureFormat = 'rgba32uint';
/** Floats per texel of the baked image. */
const RGB = 3;

/**
 * The lat-long image to upload as environment_map. RGB, not the texture's RGBA: an 8K map's image
 * is then its decoded pixels themselves (384 MB) rather than a copy with alpha (512 MB more); the
 * upload adds the alpha a band at a time (gpu/scene-resources.ts).
 */
export interface EnvironmentTexture {
  readonly width: number;
  readonly height: number;
  /** width × height × 3 floats, top row first, every one finite and ≥ 0. */
  readonly rgb: Float32Array;
}

/**
 * Both sampling CDFs in one ENVIRONMENT_CDF_FORMAT texture (see shaders/scene/bindings.wgsl), each
 * without its first entry, which is always 0: row j < map height holds entries 1..w of row j's
 * conditional CDF, row `map height` entries 1..h of the marginal CDF. So the texture is
 * max(w, h) × (h + 1): an 8192 × 4096 map fits a device's 8192 (with the zeros stored it needed 8193).
 */
export interface CdfTexture {
  readonly width: number;
  readonly height: number;
  /** Upload these bytes to a width × height texture (bytesPerRow = width × 4). */
  readonly data: Float32Array;
}

/** Entry i of CDF `row` of the texture (row = map height: the marginal CDF), as the shader reads it. */
export function cdfEntry(cdf: CdfTexture, row: number, i: number): number {
  return i === 0 ? 0 : cdf.data[row * cdf.width + i - 1]!;
}

/** Group-0 environment resources, keyed by their WGSL variable names, plus the texture's texels. */
export interface PackedEnvironment {
  readonly environment_info: ArrayBuffer;
  readonly environment_cdf: CdfTexture;
  /** Mean luminance of the map over the sphere (0 without one). */
  readonly meanLuminance: number;
  /** Luminance irradiance of the sun on a surface facing it (0 without one). */
  readonly sunIrradiance: number;
  readonly environment_map: EnvironmentTexture;
  readonly hasMap: boolean;
  readonly hasSun: boolean;
  /** Entries of the CDFs (with their first zeros, which are not stored): height + 1 and height × (width + 1). */
  readonly counts: { readonly marginal: number; readonly conditional: number };
  /** Σ w Ω over texels: the normalisation of the sampling density (for tests and tools). */
  readonly samplingTotal: number;
}

export function environmentLayouts() {
  const { defs } = reflectModule('scene/bindings');
  return { info: structLayout(defs, 'EnvironmentInfo') };
}

function checkFinite(what: string, values: readonly number[]): void {
  if (!values.every(Number.isFinite)) throw new LanternError(`environment: ${what} must be finite numbers (got ${values.join(', ')})`);
}

function checkRange(what: string, v: number, lo: number, hi: number): void {
  if (!(v >= lo && v <= hi)) throw new LanternError(`environment: ${what} ${v} is outside [${lo}, ${hi}]`);
}

/**
 * Texels of every kind but 'none', with negative and non-finite values replaced by 0. A map with
 * none of those is used as it is, not copied.
 */
export function bakeEnvironment(env: Exclude<Environment, { kind: 'none' }>): EnvironmentTexture {
  switch (env.kind) {
    case 'constant': {
      checkFinite('constant radiance', env.radiance);
      return { width: 1, height: 1, rgb: new Float32Array(env.radiance.map(clean)) };
    }
    case 'gradient': {
      checkFinite('gradient colours', [...env.zenith, ...env.horizon, ...env.ground]);
      const rgb = new Float32Array(GRADIENT_ROWS * RGB);
      for (let j = 0; j < GRADIENT_ROWS; j++) {
        // y = cos θ at the row's centre; linear from the horizon toward the zenith or the ground.
        const y = Math.cos(((j + 0.5) / GRADIENT_ROWS) * Math.PI);
        const far = y >= 0 ? env.zenith : env.ground;
        const t = Math.abs(y);
        for (let c = 0; c < 3; c++) rgb[j * RGB + c] = clean(env.horizon[c]! + t * (far[c]! - env.horizon[c]!));
      }
      return { width: 1, height: GRADIENT_ROWS, rgb };
    }
    case 'sky': {
      const sky = new SkyModel(env);
      const rgb = new Float32Array(SKY_WIDTH * SKY_HEIGHT * RGB);
      const [sx, sy, sz] = sky.sunDirection;
      const sinPhi = new Float64Array(SKY_WIDTH), cosPhi = new Float64Array(SKY_WIDTH);
      for (let i = 0; i < SKY_WIDTH; i++) {
        const phi = 2 * Math.PI * ((i + 0.5) / SKY_WIDTH - 0.5);
        sinPhi[i] = Math.sin(phi);
        cosPhi[i] = Math.cos(phi);
      }
      for (let j = 0; j < SKY_HEIGHT; j++) {
        // Texel centres, as directionFromLatLong: d = (sin θ sin φ, cos θ, −sin θ cos φ).
        const theta = ((j + 0.5) / SKY_HEIGHT) * Math.PI;
        const y = Math.cos(theta), r = Math.sin(theta);
        for (let i = 0; i < SKY_WIDTH; i++) {
          const o = (j * SKY_WIDTH + i) * RGB;
          if (y < 0) {
            const ground = sky.radiance([0, y, 0]);
            rgb[o] = ground[0];
            rgb[o + 1] = ground[1];
            rgb[o + 2] = ground[2];
          } else {
            const x = r * sinPhi[i]!, z = -r * cosPhi[i]!;
            sky.skyRadianceInto(y, x * sx + y * sy + z * sz, rgb, o);
          }
        }
      }
      return { width: SKY_WIDTH, height: SKY_HEIGHT, rgb };
    }
    case 'map': {
      const { width, height, rgb, name } = env.image;
      if (!(Number.isInteger(width) && Number.isInteger(height) && width > 0 && height > 0) || rgb.length !== width * height * 3) {
        throw new LanternError(`environment map ${name}: ${rgb.length} floats for ${width}×${height} RGB pixels`);
      }
      // clean(), inlined: NaN fails every comparison and becomes 0 (and -0 becomes 0: the texels go
      // to the GPU bit for bit).
      const isClean = (v: number) => (v > 0 && v < Infinity) || (v === 0 && 1 / v > 0);
      let n = 0;
      while (n < rgb.length && isClean(rgb[n]!)) n++;
      if (n === rgb.length) return { width, height, rgb };
      const cleaned = rgb.slice();
      for (let p = n; p < cleaned.length; p++) {
        const v = cleaned[p]!;
        cleaned[p] = v > 0 && v < Infinity ? v : 0;
      }
      return { width, height, rgb: cleaned };
    }
  }
}

/** Negative, NaN and infinite radiance would poison the sampling tables and every estimate. */
function clean(v: number): number {
  return v > 0 && v < Infinity ? v : 0;
}

/**
 * The sampling CDFs of a baked texture (see the file header), written straight into their texture
 * (CdfTexture). Besides the texture, one float a texel is held while they are built (the luminance,
 * then in place its maximum along the row): an 8192 × 4096 map takes 256 MB here, where the
 * luminance, its row maximum, the tables and the texture holding them again took 640 MB.
 */
export function buildSamplingTables(texture: EnvironmentTexture): { cdf: CdfTexture; total: number } {
  const { width: w, height: h, rgb } = texture;
  // Luminance, then its 3×3 maximum, separably: along rows (wrapping), then along columns (clamped).
  const rowMax = new Float32Array(w * h);
  // Rec. 709 luminance, as math/vec3.ts luminance(), inlined: this loop runs over every texel.
  for (let p = 0; p < w * h; p++) rowMax[p] = 0.2126 * rgb[p * 3]! + 0.7152 * rgb[p * 3 + 1]! + 0.0722 * rgb[p * 3 + 2]!;
  for (let j = 0; j < h; j++) {
    const o = j * w;
    // In place: the luminance of the texel before, and of the first (for the last, wrapping), kept aside.
    const first = rowMax[o]!;
    let left = rowMax[o + w - 1]!;
    for (let i = 0; i < w; i++) {
      const here = rowMax[o + i]!, right = i === w - 1 ? first : rowMax[o + i + 1]!;
      const m = left > here ? left : here;
      rowMax[o + i] = m > right ? m : right;
      left = here;
    }
  }
  const cdf: CdfTexture = { width: Math.max(w, h), height: h + 1, data: new Float32Array(Math.max(w, h) * (h + 1)) };
  const data = cdf.data;
  const rowWeights = new Float64Array(h);
  const dtheta = Math.PI / h;
  for (let j = 0; j < h; j++) {
    const up = Math.max(0, j - 1) * w, here = j * w, down = Math.min(h - 1, j + 1) * w;
    const o = j * cdf.width;
    let sum = 0;
    for (let i = 0; i < w; i++) {
      const a = rowMax[up + i]!, b = rowMax[here + i]!, c = rowMax[down + i]!;
      const m = a > b ? a : b;
      sum += m > c ? m : c;
      data[o + i] = sum; // provisional: the running sum through texel i (entry i + 1)
    }
    // Ω of one texel of row j = (2π / w) · 2 sin θ_mid sin(Δθ / 2), as environment.wgsl computes it.
    const texelSolidAngle = ((2 * Math.PI) / w) * 2 * Math.sin((j + 0.5) * dtheta) * Math.sin(0.5 * dtheta);
    rowWeights[j] = sum * texelSolidAngle;
    if (sum > 0) {
      const inverse = 1 / sum;
      for (let i = 0; i < w - 1; i++) data[o + i] = data[o + i]! * inverse;
    } else {
      // A black row is never chosen; a uniform CDF keeps the table well formed.
      for (let i = 0; i < w - 1; i++) data[o + i] = (i + 1) / w;
    }
    data[o + w - 1] = 1;
  }
  let total = 0;
  for (let j = 0; j < h; j++) total += rowWeights[j]!;
  const marginal = h * cdf.width;
  let acc = 0;
  for (let j = 0; j < h - 1; j++) {
    acc += rowWeights[j]!;
    data[marginal + j] = total > 0 ? acc / total : (j + 1) / h;
  }
  data[marginal + h - 1] = 1;
  return { cdf, total };
}

/** The format of environment_cdf: f32 values as their bits, one per texel. */
export const ENVIRONMENT_CDF_FORMAT: GPUTextureFormat = 'r32uint';

/** Packs an environment; throws a LanternError for parameters outside their documented ranges. */
export function packEnvironment(env: Environment): PackedEnvironment {
  const layouts = environmentLayouts();
  const info = new StructArray(layouts.info, 1);
  const kind = ENVIRONMENT_KINDS.indexOf(env.kind);
  info.u32Field('kind')(0, kind);

  let texture: EnvironmentTexture = { width: 1, height: 1, rgb: new Float32Array(RGB) };
  let intensity = 1;
  let rotationDeg = 0;
  let sun: { direction: Vec3; radiance: Vec3; oneMinusCosMax: number } | undefined;
  if (env.kind === 'sky') {
    checkFinite('sky parameters', [env.sunElevationDeg, env.sunAzimuthDeg, env.turbidity, env.groundAlbedo, env.intensity]);
    checkRange('sun elevation (degrees)', env.sunElevationDeg, -90, 90);
    checkRange('turbidity', env.turbidity, 1, 10);
    checkRange('ground albedo', env.groundAlbedo, 0, 1);
    checkRange('sky intensity', env.intensity, 0, Infinity);
    intensity = env.intensity;
    const model = new SkyModel(env);
    if (model.sunVisible && env.intensity > 0) {
      const radius = (SUN_ANGULAR_RADIUS_DEG * Math.PI) / 180;
      sun = {
        direction: normalize(model.sunDirection),
        radiance: model.sunRadiance.map((v) => v * env.intensity) as unknown as Vec3,
        // 1 − cos r = 2 sin²(r/2), in double precision.
        oneMinusCosMax: 2 * Math.sin(radius / 2) ** 2,
      };
    }
  } else if (env.kind === 'map') {
    checkFinite('map rotation and intensity', [env.rotationDeg, env.intensity]);
    checkRange('map intensity', env.intensity, 0, Infinity);
    intensity = env.intensity;
    rotationDeg = env.rotationDeg;
  }
  if (env.kind !== 'none') texture = bakeEnvironment(env);

  const tables = buildSamplingTables(texture);
  const hasMap = env.kind !== 'none' && tables.total > 0 && intensity > 0;
  const hasSun = sun !== undefined;

  info.u32Field('flags')(0, (hasMap ? ENVIRONMENT_HAS_MAP : 0) | (hasSun ? ENVIRONMENT_HAS_SUN : 0));
  info.vec2u('map_size')(0, texture.width, texture.height);
  const rho = (rotationDeg * Math.PI) / 180;
  info.vec2('rotation_cos_sin')(0, Math.cos(rho), Math.sin(rho));
  info.f32Field('intensity')(0, intensity);
  if (sun) {
    info.vec3('sun_direction')(0, ...sun.direction);
    info.vec3('sun_radiance')(0, ...sun.radiance);
    info.f32Field('sun_one_minus_cos_max')(0, sun.oneMinusCosMax);
    info.f32Field('sun_pdf')(0, 1 / (2 * Math.PI * sun.oneMinusCosMax));
  } else {
    info.vec3('sun_direction')(0, 0, 1, 0);
  }

  return {
    environment_info: info.bytes,
    environment_cdf: tables.cdf,
    environment_map: texture,
    hasMap,
    hasSun,
    counts: { marginal: texture.height + 1, conditional: texture.height * (texture.width + 1) },
    samplingTotal: tables.total,
    // For light selection: the map's mean luminance over the sphere (its sampling weights bound the
    // luminance from above, which is fine for a selection weight) and the sun's irradiance.
    meanLuminance: hasMap ? (intensity * tables.total) / (4 * Math.PI) : 0,
    sunIrradiance: sun ? luminanceOf(sun.radiance) * 2 * Math.PI * sun.oneMinusCosMax : 0,
  };
}
