/**
 * The Hosek–Wilkie analytic clear sky (L. Hosek, A. Wilkie, "An Analytic Model for Full Spectral
 * Sky-Dome Radiance", ACM TOG 31(4), SIGGRAPH 2012), RGB version, evaluated on the CPU, plus a sun disk
 * whose radiance follows the same turbidity. Pure TypeScript; gpu/pack bakes it into a lat-long map.
 *
 * The sky model. For a view direction at zenith angle θ, at angle γ from the sun,
 *
 *   L(θ, γ) = L_M · (1 + A e^{B / (cos θ + 0.01)}) · (C + D e^{E γ} + F cos²γ + G χ(H, γ) + I √cos θ),
 *   χ(g, α) = (1 + cos²α) / (1 + g² − 2 g cos α)^{3/2}                  (an anisotropic Mie lobe)
 *
 * per colour channel. The nine parameters A–I and the overall radiance L_M come from the published
 * dataset (sky-data.ts): for each integer turbidity 1..10 and ground albedo 0 and 1, six control points
 * of a quintic Bézier curve in x = (solar elevation / (π/2))^{1/3}; between them we interpolate
 * linearly in turbidity and in albedo, as the paper does. The dataset holds nine parameters in the
 * order A, B, C, D, E, F, G, I, H. Output is linear sRGB radiance in W m⁻² sr⁻¹ (Y × 683 = cd/m²).
 *
 * Below the horizon the model is undefined; we show a Lambertian ground of the given albedo lit by
 * the whole sky and the sun: L_ground = albedo · E_horizontal / π.
 */
import { luminance, normalize, type Vec3 } from '../math/vec3.ts';
import { directionFromElevationAzimuth } from './environment.ts';
import { HOSEK_RGB_CONFIG, HOSEK_RGB_RADIANCE } from './sky-data.ts';

/**
 * Angular radius of the sun's disk seen from the earth, in degrees: half of the mean angular
 * diameter 0.5334° (solar radius 6.957e5 km at 1 AU = 1.496e8 km: asin(6.957e5 / 1.496e8) = 0.2665°;
 * the reference implementation uses the same 0.2667°).
 */
export const SUN_ANGULAR_RADIUS_DEG = 0.2667;

/**
 * Illuminance of the sun at the mean earth–sun distance outside the atmosphere, in lux: the solar
 * illuminance constant 133.8 klx (S. Darula, R. Kittler, C. Gueymard, "Reference luminous solar
 * constant and solar luminance for illuminance calculations", Solar Energy 79, 2005).
 */
export const SOLAR_ILLUMINANCE_CONSTANT_LUX = 133_800;

/**
 * The exposure that daylight wants, in stops: the "sunny 16" rule's EV100 = 15, i.e. luminance
 * (cd/m²) scaled by 1 / (1.2 · 2^15) (ISO 2720's saturation-based calibration). The sky's radiance is
 * radiometric (W m⁻² sr⁻¹, ×683 gives cd/m²), so the scale on radiance is 683 / (1.2 · 2^15): a white
 * Lambertian surface in sunlight (~80 klx, 25,000 cd/m², L ≈ 37) then shows about 0.6. Scenes lit by
 * the sky carry this as their camera's exposure compensation.
 */
export const DAYLIGHT_EXPOSURE_STOPS = Math.log2(683 / 1.2) - 15;

/** Luminous efficacy that converts the model's W m⁻² sr⁻¹ (its Y channel) to cd/m². */
export const LUMENS_PER_WATT = 683;

/**
 * Effective wavelengths of the linear sRGB channels for the sun's transmittance, in micrometres: the
 * dominant wavelengths of the Rec. 709 primaries (red 611 nm, green 549 nm, blue 464 nm).
 */
const CHANNEL_WAVELENGTH_UM: Vec3 = [0.611, 0.549, 0.464];

/** Ångström wavelength exponent of the aerosols (Preetham et al. 1999, Appendix A.2: α = 1.3). */
const ANGSTROM_ALPHA = 1.3;

export interface SkyParameters {
  /** Degrees above the horizon; the sky model is fitted for [0, 90]. */
  readonly sunElevationDeg: number;
  /** Degrees about +y from +z toward +x. */
  readonly sunAzimuthDeg: number;
  /** Atmospheric turbidity in [1, 10] (1: very clear, 10: hazy). */
  readonly turbidity: number;
  /** Ground albedo in [0, 1]. */
  readonly groundAlbedo: number;
}

const CONTROL_POINTS = 6;
const PARAMETERS = 9;
const TURBIDITIES = 10;
/** Binomial weights of the quintic Bézier: C(5, k). */
const BEZIER_WEIGHTS = [1, 5, 10, 10, 5, 1] as const;

/** Quintic Bézier of the control points data[offset + k·stride], k = 0..5, at x ∈ [0, 1]. */
function bezier(data: readonly number[], offset: number, stride: number, x: number): number {
  let sum = 0;
  for (let k = 0; k < CONTROL_POINTS; k++) {
    sum += BEZIER_WEIGHTS[k]! * (1 - x) ** (CONTROL_POINTS - 1 - k) * x ** k * data[offset + k * stride]!;
  }
  return sum;
}

/**
 * One parameter (or L_M when `count` is 1) at a fractional turbidity and albedo: the Bézier in
 * elevation at the bracketing integer turbidities and both albedos, blended linearly.
 */
function cook(data: readonly number[], count: number, param: number, turbidity: number, albedo: number, x: number): number {
  const t0 = Math.min(TURBIDITIES - 1, Math.floor(turbidity)); // 1..9: lower integer turbidity
  const ft = turbidity - t0; // in [0, 1]
  const perTurbidity = CONTROL_POINTS * count;
  const perAlbedo = TURBIDITIES * perTurbidity;
  const at = (a: number, t: number): number => bezier(data, a * perAlbedo + (t - 1) * perTurbidity + param, count, x);
  const low = (1 - albedo) * at(0, t0) + albedo * at(1, t0);
  const high = (1 - albedo) * at(0, t0 + 1) + albedo * at(1, t0 + 1);
  return (1 - ft) * low + ft * high;
}

/** Transmittance of the atmosphere at one wavelength along the sun's path (Preetham et al. 1999, A.2). */
function sunTransmittance(lambdaUm: number, turbidity: number, zenithRad: number): number {
  // Relative optical air mass (Kasten 1966, as in Preetham): finite at the horizon.
  const zenithDeg = (zenithRad * 180) / Math.PI;
  const airMass = 1 / (Math.cos(zenithRad) + 0.15 * (93.885 - zenithDeg) ** -1.253);
  // Rayleigh optical depth per air mass: 0.008735 λ^-4.08 (λ in µm).
  const rayleigh = 0.008735 * lambdaUm ** -4.08;
  // Aerosol optical depth: Ångström's β λ^-α with β from turbidity (Preetham: β = 0.04608 T − 0.04586).
  const beta = Math.max(0, 0.04608 * turbidity - 0.04586);
  const aerosol = beta * lambdaUm ** -ANGSTROM_ALPHA;
  return Math.exp(-airMass * (rayleigh + aerosol));
}

/** The sky (without the sun's disk) and the sun, for one set of parameters. */
export class SkyModel {
  /** Unit direction toward the sun's centre. */
  readonly sunDirection: Vec3;
  /** Radiance of the sun's disk (uniform across it), linear sRGB, W m⁻² sr⁻¹; zero when the sun is hidden. */
  readonly sunRadiance: Vec3;
  /** Whether the sun's centre is above the horizon. */
  readonly sunVisible: boolean;
  /** Cosine of the sun's angular radius. */
  readonly sunCosMax: number;
  /** A–I of each channel, channel-major (9 per channel). */
  private readonly config = new Float64Array(3 * PARAMETERS);
  private readonly radianceScale = new Float64Array(3);
  private groundRadiance: Vec3 = [0, 0, 0];

  constructor(readonly parameters: SkyParameters) {
    const turbidity = Math.min(10, Math.max(1, parameters.turbidity));
    const albedo = Math.min(1, Math.max(0, parameters.groundAlbedo));
    const elevationDeg = Math.min(90, Math.max(-90, parameters.sunElevationDeg));
    // The model is fitted for elevations in [0, π/2]; below, the sky of a sun at the horizon.
    const elevation = (Math.max(0, elevationDeg) * Math.PI) / 180;
    const x = Math.cbrt(elevation / (Math.PI / 2));
    for (let c = 0; c < 3; c++) {
      for (let p = 0; p < PARAMETERS; p++) this.config[c * PARAMETERS + p] = cook(HOSEK_RGB_CONFIG[c]!, PARAMETERS, p, turbidity, albedo, x);
      this.radianceScale[c] = cook(HOSEK_RGB_RADIANCE[c]!, 1, 0, turbidity, albedo, x);
    }
    this.sunDirection = normalize(directionFromElevationAzimuth(elevationDeg, parameters.sunAzimuthDeg));
    this.sunVisible = elevationDeg > 0;
    const radius = (SUN_ANGULAR_RADIUS_DEG * Math.PI) / 180;
    this.sunCosMax = Math.cos(radius);
    if (this.sunVisible) {
      // Outside the atmosphere: the luminous solar constant spread over the disk's solid angle
      // Ω = 2π(1 − cos r), with the chromaticity of the extraterrestrial sun taken as the sRGB white
      // (its CIE xy ≈ (0.322, 0.331) is within 0.01 of D65), so R = G = B = Y. Then attenuated per
      // channel by Rayleigh and aerosol extinction at this turbidity.
      const solidAngle = 2 * Math.PI * (1 - this.sunCosMax);
      const y = SOLAR_ILLUMINANCE_CONSTANT_LUX / LUMENS_PER_WATT / solidAngle;
      const zenith = Math.PI / 2 - (elevationDeg * Math.PI) / 180;
      this.sunRadiance = CHANNEL_WAVELENGTH_UM.map((l) => y * sunTransmittance(l, turbidity, zenith)) as unknown as Vec3;
    } else {
      this.sunRadiance = [0, 0, 0];
    }
    this.groundRadiance = this.computeGround(albedo);
  }

  /** Sky radiance of the upper hemisphere at zenith cosine cosTheta ≥ 0 and sun angle gamma. */
  skyRadiance(cosTheta: number, cosGamma: number): Vec3 {
    const out: [number, number, number] = [0, 0, 0];
    this.skyRadianceInto(cosTheta, cosGamma, out, 0);
    return out;
  }

  /** skyRadiance written to out[offset..offset + 2], without allocating: baking calls it per texel. */
  skyRadianceInto(cosTheta: number, cosGamma: number, out: { [i: number]: number }, offset: number): void {
    const ct = cosTheta > 0 ? cosTheta : 0;
    const cg = Math.min(1, Math.max(-1, cosGamma));
    const gamma = Math.acos(cg);
    const cg2 = cg * cg;
    const sqrtCt = Math.sqrt(ct);
    const k = this.config;
    for (let c = 0; c < 3; c++) {
      const o = c * PARAMETERS;
      // Dataset order: A, B, C, D, E, F, G, I, H.
      const a = k[o]!, b = k[o + 1]!, cc = k[o + 2]!, d = k[o + 3]!, e = k[o + 4]!, f = k[o + 5]!, g = k[o + 6]!, i = k[o + 7]!, h = k[o + 8]!;
      const q = 1 + h * h - 2 * h * cg;
      const mie = (1 + cg2) / (q * Math.sqrt(q)); // q^{3/2}
      const value = (1 + a * Math.exp(b / (ct + 0.01))) * (cc + d * Math.exp(e * gamma) + f * cg2 + g * mie + i * sqrtCt);
      const l = value * this.radianceScale[c]!;
      out[offset + c] = l > 0 ? l : 0;
    }
  }

  /** What a ray in unit direction d sees, excluding the sun's disk: the sky above, the ground below. */
  radiance(d: Vec3): Vec3 {
    if (d[1] < 0) return this.groundRadiance;
    const s = this.sunDirection;
    return this.skyRadiance(d[1], d[0] * s[0] + d[1] * s[1] + d[2] * s[2]);
  }

  /** Radiance of the ground: albedo/π times the irradiance of sky and sun on a horizontal plane. */
  private computeGround(albedo: number): Vec3 {
    // E_sky = ∫ L cos θ dω over the upper hemisphere, midpoint rule in (cos θ, φ): dω = d(cos θ) dφ.
    const rows = 48, columns = 96;
    const e = [0, 0, 0];
    const s = this.sunDirection;
    for (let j = 0; j < rows; j++) {
      const ct = (j + 0.5) / rows;
      const st = Math.sqrt(1 - ct * ct);
      for (let k = 0; k < columns; k++) {
        const phi = ((k + 0.5) / columns) * 2 * Math.PI;
        const dx = st * Math.sin(phi), dz = st * Math.cos(phi);
        const l = this.skyRadiance(ct, dx * s[0] + ct * s[1] + dz * s[2]);
        for (let c = 0; c < 3; c++) e[c]! += l[c]! * ct;
      }
    }
    const cell = (1 / rows) * ((2 * Math.PI) / columns);
    // The sun's disk: E = L Ω sin(elevation) for a disk entirely above the horizon.
    const sunE = 2 * Math.PI * (1 - this.sunCosMax) * Math.max(0, s[1]);
    return [0, 1, 2].map((c) => (albedo / Math.PI) * (e[c]! * cell + this.sunRadiance[c]! * sunE)) as unknown as Vec3;
  }
}

/** Luminance (W m⁻² sr⁻¹, × 683 for cd/m²) of the sky in direction d. For tests and tools. */
export function skyLuminance(model: SkyModel, d: Vec3): number {
  return luminance(model.radiance(d));
}
