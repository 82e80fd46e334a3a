/**
 * Spectral rendering's colour science, pure: the CIE 1931 2° colour-matching functions (the analytic
 * multi-lobe Gaussian fit of Wyman, Sloan & Shirley 2013, "Simple Analytic Approximations to the CIE
 * XYZ Color Matching Functions", JCGT 2(2), §2.1), the wavelength sampling density, the output
 * matrix from XYZ to the renderer's linear sRGB, and the smooth linear RGB → spectrum lift.
 *
 * Shaders/lib/spectrum.wgsl is the GPU twin; spectrum.test.ts holds its constants to the ones here.
 * docs/spectral.md explains the choices.
 *
 * The lift is a spectral primary decomposition (in the manner of Mallett & Yuksel 2019, "Spectral
 * Primary Decomposition for Rendering with sRGB Reflectance", EGSR): three smooth basis spectra
 * b_r, b_g, b_b ≥ 0 that sum to 1 at every wavelength, fitted so that each one's colour is exactly its
 * primary. A colour c lifts to s(λ) = c_r b_r(λ) + c_g b_g(λ) + c_b b_b(λ): linear (so it lifts
 * unbounded emission and radiance as well as reflectance, and commutes with the affine colour maths of
 * the BSDFs), white (1, 1, 1) lifts to the constant 1 (the furnace stays exact), a reflectance in
 * [0, 1]³ stays in [0, 1] at every wavelength, and c → s → XYZ → RGB is the identity. Here the basis
 * is a softmax of two quartic logits (b_g's logit is 0), fitted once by Levenberg–Marquardt on the
 * six round-trip equations (with a small penalty on the coefficients and on red below 480 nm and blue
 * above 620 nm, so each basis keeps to its own band); docs/spectral.md gives the fit and its error.
 *
 * White: emitters' white (1, 1, 1) is the equal-energy spectrum E; XYZ is taken to linear sRGB (D65)
 * through a Bradford adaptation from E to D65, so E shows as (1, 1, 1), as white does in RGB mode.
 */

/** Wavelengths the spectral mode covers, in nm (the CIE tables' span, as in the issue). */
export const LAMBDA_MIN = 360;
export const LAMBDA_MAX = 830;

/** A two-sided Gaussian: σ₁ below the mean, σ₂ above (Wyman et al. 2013, eq. 1). */
function lobe(lambda: number, mean: number, sigmaBelow: number, sigmaAbove: number): number {
  const t = (lambda - mean) / (lambda < mean ? sigmaBelow : sigmaAbove);
  return Math.exp(-0.5 * t * t);
}

/** CIE 1931 2° colour-matching functions x̄, ȳ, z̄ at `lambda` nm (Wyman et al. 2013, the multi-lobe fit). */
export function cieXyz(lambda: number): [number, number, number] {
  const x = 1.056 * lobe(lambda, 599.8, 37.9, 31.0) + 0.362 * lobe(lambda, 442.0, 16.0, 26.7) - 0.065 * lobe(lambda, 501.1, 20.4, 26.2);
  const y = 0.821 * lobe(lambda, 568.8, 46.9, 40.5) + 0.286 * lobe(lambda, 530.9, 16.3, 31.1);
  const z = 1.217 * lobe(lambda, 437.0, 11.8, 36.0) + 0.681 * lobe(lambda, 459.0, 26.0, 13.8);
  return [x, y, z];
}

/** ∫ f(λ) dλ over [LAMBDA_MIN, LAMBDA_MAX] by the midpoint rule at 1/`perNm` nm. */
export function integrateSpectrum(f: (lambda: number) => number, perNm = 4): number {
  const n = (LAMBDA_MAX - LAMBDA_MIN) * perNm;
  const h = 1 / perNm;
  let sum = 0;
  for (let i = 0; i < n; i++) sum += f(LAMBDA_MIN + (i + 0.5) * h);
  return sum * h;
}

/** XYZ of a spectrum (radiance or reflectance under E), scaled so the constant 1 has Y = 1. */
export function spectrumToXyz(f: (lambda: number) => number, perNm = 4): [number, number, number] {
  const n = (LAMBDA_MAX - LAMBDA_MIN) * perNm;
  const h = 1 / perNm;
  let x = 0, y = 0, z = 0;
  for (let i = 0; i < n; i++) {
    const l = LAMBDA_MIN + (i + 0.5) * h;
    const v = f(l);
    const c = cieXyz(l);
    x += v * c[0];
    y += v * c[1];
    z += v * c[2];
  }
  return [x * h / Y_INTEGRAL, y * h / Y_INTEGRAL, z * h / Y_INTEGRAL];
}

/** ∫ ȳ(λ) dλ of the fit over the span (nm): the normalization that gives the constant 1 spectrum Y = 1. */
export const Y_INTEGRAL = integrateSpectrum((l) => cieXyz(l)[1], 16);

// ---- wavelength sampling ----

/**
 * Wavelengths are drawn with density ∝ sech²(a (λ − 538 nm)), a = 0.0072/nm, on [360, 830] nm: close to
 * the visible part of ȳ, so wavelengths the eye barely sees are rarely traced (the density pbrt-v4
 * uses, Pharr et al. 2023 §4.6.5). Its CDF is (tanh(a (λ − 538)) − t₀)/(t₁ − t₀), inverted exactly.
 */
export const WAVELENGTH_SHARPNESS = 0.0072;
export const WAVELENGTH_CENTER = 538;
const T0 = Math.tanh(WAVELENGTH_SHARPNESS * (LAMBDA_MIN - WAVELENGTH_CENTER));
const T1 = Math.tanh(WAVELENGTH_SHARPNESS * (LAMBDA_MAX - WAVELENGTH_CENTER));

export function sampleWavelength(u: number): number {
  return WAVELENGTH_CENTER + Math.atanh(T0 + u * (T1 - T0)) / WAVELENGTH_SHARPNESS;
}

export function wavelengthPdf(lambda: number): number {
  if (lambda < LAMBDA_MIN || lambda > LAMBDA_MAX) return 0;
  const c = Math.cosh(WAVELENGTH_SHARPNESS * (lambda - WAVELENGTH_CENTER));
  return WAVELENGTH_SHARPNESS / ((T1 - T0) * c * c);
}

/**
 * The hero wavelength and its three companions (Wilkie et al. 2014, "Hero Wavelength Spectral
 * Sampling", EGSR): one uniform number u gives u, u + ¼, u + ½, u + ¾ (mod 1), each mapped through the
 * sampling density's inverse CDF: stratified, and each alone distributed with wavelengthPdf.
 */
export function heroWavelengths(u: number): [number, number, number, number] {
  const at = (k: number) => sampleWavelength((u + k / 4) % 1);
  return [at(0), at(1), at(2), at(3)];
}

// ---- output: XYZ → linear sRGB ----

type Mat3 = readonly [readonly [number, number, number], readonly [number, number, number], readonly [number, number, number]];

function mul(a: Mat3, b: Mat3): Mat3 {
  const r = (i: number) => [0, 1, 2].map((j) => a[i]![0] * b[0]![j]! + a[i]![1] * b[1]![j]! + a[i]![2] * b[2]![j]!) as [number, number, number];
  return [r(0), r(1), r(2)];
}

export function mulVec(m: Mat3, v: readonly [number, number, number]): [number, number, number] {
  return [0, 1, 2].map((i) => m[i]![0] * v[0] + m[i]![1] * v[1] + m[i]![2] * v[2]) as [number, number, number];
}

export function invert3(m: Mat3): Mat3 {
  const [[a, b, c], [d, e, f], [g, h, i]] = m;
  const A = e * i - f * h, B = -(d * i - f * g), C = d * h - e * g;
  const det = a * A + b * B + c * C;
  return [
    [A / det, -(b * i - c * h) / det, (b * f - c * e) / det],
    [B / det, (a * i - c * g) / det, -(a * f - c * d) / det],
    [C / det, -(a * h - b * g) / det, (a * e - b * d) / det],
  ];
}

/** IEC 61966-2-1: linear sRGB from CIE XYZ (D65 white). */
export const SRGB_FROM_XYZ: Mat3 = [
  [3.2404542, -1.5371385, -0.4985314],
  [-0.969266, 1.8760108, 0.041556],
  [0.0556434, -0.2040259, 1.0572252],
];
/** The Bradford cone response matrix (Lam 1985). */
const BRADFORD: Mat3 = [
  [0.8951, 0.2664, -0.1614],
  [-0.7502, 1.7135, 0.0367],
  [0.0389, -0.0685, 1.0296],
];

/** XYZ of the constant 1 spectrum (E) through the fitted CMFs: Y = 1, X ≈ Z ≈ 1. */
export const E_WHITE_XYZ = spectrumToXyz(() => 1, 16);

/**
 * Linear sRGB from the XYZ of a spectrum lit by E: Bradford adaptation E → D65, then SRGB_FROM_XYZ.
 * D65's XYZ is taken as the one SRGB_FROM_XYZ maps to (1, 1, 1), so E maps to white exactly.
 */
export const RGB_FROM_XYZ: Mat3 = (() => {
  const d65 = mulVec(invert3(SRGB_FROM_XYZ), [1, 1, 1]);
  const src = mulVec(BRADFORD, E_WHITE_XYZ);
  const dst = mulVec(BRADFORD, d65);
  const scale: Mat3 = [
    [dst[0] / src[0], 0, 0],
    [0, dst[1] / src[1], 0],
    [0, 0, dst[2] / src[2]],
  ];
  return mul(SRGB_FROM_XYZ, mul(invert3(BRADFORD), mul(scale, BRADFORD)));
})();

/** The colour a spectrum shows in the renderer's linear sRGB (E-white balanced). */
export function spectrumToRgb(f: (lambda: number) => number, perNm = 4): [number, number, number] {
  return mulVec(RGB_FROM_XYZ, spectrumToXyz(f, perNm));
}

// ---- the lift: RGB → spectrum ----

/**
 * Logits of the red and blue basis spectra, quartics in x = (λ − 595 nm)/235 nm (x ∈ [−1, 1] over the
 * span), lowest power first; green's logit is 0. b_k = e^{z_k} / (e^{z_r} + 1 + e^{z_b}).
 */
export const SPECTRAL_BASIS_X_CENTER = 595;
export const SPECTRAL_BASIS_X_SCALE = 235;
export const SPECTRAL_BASIS_LOGITS: { readonly red: readonly number[]; readonly blue: readonly number[] } = {
  red: [0.013499, 33.986458, 44.810607, -22.729739, 4.812086],
  blue: [-3.274621, 5.22163, 13.560576, -18.94767, 20.45454],
};

/** The three basis spectra at `lambda`: non-negative, summing to 1. */
export function spectralBasis(lambda: number, logits = SPECTRAL_BASIS_LOGITS): [number, number, number] {
  const x = (lambda - SPECTRAL_BASIS_X_CENTER) / SPECTRAL_BASIS_X_SCALE;
  const poly = (c: readonly number[]) => c.reduceRight((acc, k) => acc * x + k, 0);
  const er = Math.exp(poly(logits.red)), eb = Math.exp(poly(logits.blue));
  const sum = er + 1 + eb;
  return [er / sum, 1 / sum, eb / sum];
}

/** The spectrum an RGB colour lifts to, at `lambda` nm. */
export function liftRgb(rgb: readonly [number, number, number], lambda: number): number {
  const b = spectralBasis(lambda);
  return rgb[0] * b[0] + rgb[1] * b[1] + rgb[2] * b[2];
}
