// Spectral mode's colour science: hero-wavelength sampling (Wilkie et al. 2014, one wavelength and three
// stratified companions per path over 360–830 nm, density ∝ sech² around 538 nm as in pbrt-v4), the
// linear RGB → spectrum lift (three smooth basis spectra summing to 1; white lifts to the constant 1),
// and CIE 1931 2° matching (Wyman, Sloan & Shirley 2013's multi-lobe fit) to the renderer's linear sRGB
// with equal-energy white shown as (1, 1, 1). Expects nothing. math/spectrum.ts is the TypeScript twin
// (its test holds these constants to it); docs/spectral.md explains the method.

// Whether paths carry four wavelengths instead of RGB (a pipeline constant: RGB mode compiles none of
// this in; passes/path-trace-pass.ts sets it from the `spectral` setting).
override SPECTRAL: bool = false;

const SPECTRUM_LAMBDA_MIN: f32 = 360.0;
const SPECTRUM_LAMBDA_MAX: f32 = 830.0;
// Sampling density a / ((t1 − t0) cosh²(a (λ − c))), CDF (tanh(a (λ − c)) − t0)/(t1 − t0).
const SPECTRUM_SAMPLING_SHARPNESS: f32 = 0.0072;
const SPECTRUM_SAMPLING_CENTER: f32 = 538.0;
const SPECTRUM_SAMPLING_T0: f32 = -0.856910625469828;
const SPECTRUM_SAMPLING_T1: f32 = 0.9705913469402698;
// ∫ ȳ dλ of the fit over 360–830 nm: the constant 1 spectrum has Y = 1.
const SPECTRUM_Y_INTEGRAL: f32 = 106.92207450618348;
// Basis logits: quartics in x = (λ − 595)/235, lowest power first; green's is 0.
const SPECTRUM_BASIS_X_CENTER: f32 = 595.0;
const SPECTRUM_BASIS_X_SCALE: f32 = 235.0;
const SPECTRUM_BASIS_RED_0: f32 = 0.013499;
const SPECTRUM_BASIS_RED_1: f32 = 33.986458;
const SPECTRUM_BASIS_RED_2: f32 = 44.810607;
const SPECTRUM_BASIS_RED_3: f32 = -22.729739;
const SPECTRUM_BASIS_RED_4: f32 = 4.812086;
const SPECTRUM_BASIS_BLUE_0: f32 = -3.274621;
const SPECTRUM_BASIS_BLUE_1: f32 = 5.22163;
const SPECTRUM_BASIS_BLUE_2: f32 = 13.560576;
const SPECTRUM_BASIS_BLUE_3: f32 = -18.94767;
const SPECTRUM_BASIS_BLUE_4: f32 = 20.45454;
// Linear sRGB from XYZ with a Bradford adaptation from E to D65 (math/spectrum.ts RGB_FROM_XYZ), rows.
const SPECTRUM_RGB_FROM_XYZ_0: vec3f = vec3f(3.147809464648221, -1.6628464107655163, -0.4805744047850218);
const SPECTRUM_RGB_FROM_XYZ_1: vec3f = vec3f(-0.9947474012741635, 1.9535709510572248, 0.03974022085562107);
const SPECTRUM_RGB_FROM_XYZ_2: vec3f = vec3f(0.06351552208192116, -0.2145108995419668, 1.1515951576064052);

// The wavelengths one path carries (x: the hero) and their sampling densities; set by
// spectrum_begin_path. A path crossing a dispersive interface keeps only the hero (spectrum_terminate_secondary).
struct Wavelengths {
  lambda: vec4f, // nm
  pdf: vec4f,    // per nm
}
var<private> path_wavelengths: Wavelengths;
var<private> path_secondary_alive: bool;
// The lift of the path's wavelengths: column k is basis spectrum k (r, g, b) at the four wavelengths.
var<private> path_lift: mat3x4f;

fn spectrum_sample_wavelength(u: f32) -> f32 {
  let t = SPECTRUM_SAMPLING_T0 + u * (SPECTRUM_SAMPLING_T1 - SPECTRUM_SAMPLING_T0);
  return SPECTRUM_SAMPLING_CENTER + atanh(clamp(t, -0.999999, 0.999999)) / SPECTRUM_SAMPLING_SHARPNESS;
}

fn spectrum_wavelength_pdf(lambda: vec4f) -> vec4f {
  let c = cosh(SPECTRUM_SAMPLING_SHARPNESS * (lambda - SPECTRUM_SAMPLING_CENTER));
  return SPECTRUM_SAMPLING_SHARPNESS / ((SPECTRUM_SAMPLING_T1 - SPECTRUM_SAMPLING_T0) * c * c);
}

// b_r, b_g, b_b at four wavelengths: a softmax of the logits (non-negative, summing to 1).
fn spectrum_basis(lambda: vec4f) -> mat3x4f {
  let x = (lambda - SPECTRUM_BASIS_X_CENTER) / SPECTRUM_BASIS_X_SCALE;
  let zr = SPECTRUM_BASIS_RED_0 + x * (SPECTRUM_BASIS_RED_1 + x * (SPECTRUM_BASIS_RED_2 + x * (SPECTRUM_BASIS_RED_3 + x * SPECTRUM_BASIS_RED_4)));
  let zb = SPECTRUM_BASIS_BLUE_0 + x * (SPECTRUM_BASIS_BLUE_1 + x * (SPECTRUM_BASIS_BLUE_2 + x * (SPECTRUM_BASIS_BLUE_3 + x * SPECTRUM_BASIS_BLUE_4)));
  let er = exp(zr);
  let eb = exp(zb);
  let inv = 1.0 / (er + 1.0 + eb);
  return mat3x4f(er * inv, inv, eb * inv);
}

// Draws the path's hero wavelength from u and its three companions at u + k/4 (mod 1).
fn spectrum_begin_path(u: f32) {
  let us = fract(vec4f(u, u + 0.25, u + 0.5, u + 0.75));
  let lambda = vec4f(spectrum_sample_wavelength(us.x), spectrum_sample_wavelength(us.y), spectrum_sample_wavelength(us.z), spectrum_sample_wavelength(us.w));
  path_wavelengths = Wavelengths(lambda, spectrum_wavelength_pdf(lambda));
  path_lift = spectrum_basis(lambda);
  path_secondary_alive = true;
}

// An RGB quantity (reflectance, radiance, a BSDF weight) in the path's channels: the spectrum it lifts
// to at the four wavelengths in spectral mode, (r, g, b, 0) in RGB mode.
fn lift(c: vec3f) -> vec4f {
  if (SPECTRAL) {
    return path_lift * c;
  }
  return vec4f(c, 0.0);
}

// The path met a wavelength-dependent direction (dispersion): from here on only the hero goes on. Its
// throughput counts four times, since the companions' share of the average is now 0 (Wilkie et al.
// 2014 §4; pbrt-v4's TerminateSecondary). Radiance the companions gathered before stays theirs (each
// wavelength's estimate of the path so far is unbiased on its own), so their densities are kept.
fn spectrum_terminate_secondary(throughput: vec4f) -> vec4f {
  if (!path_secondary_alive) {
    return throughput;
  }
  path_secondary_alive = false;
  return vec4f(4.0 * throughput.x, 0.0, 0.0, 0.0);
}

fn spectrum_lobe(lambda: vec4f, mean: f32, sigma_below: f32, sigma_above: f32) -> vec4f {
  let t = (lambda - mean) / select(vec4f(sigma_above), vec4f(sigma_below), lambda < vec4f(mean));
  return exp(-0.5 * t * t);
}

// CIE 1931 2° x̄, ȳ, z̄ at four wavelengths (Wyman et al. 2013, multi-lobe fit), as three vec4s.
fn spectrum_cie_x(l: vec4f) -> vec4f {
  return 1.056 * spectrum_lobe(l, 599.8, 37.9, 31.0) + 0.362 * spectrum_lobe(l, 442.0, 16.0, 26.7) - 0.065 * spectrum_lobe(l, 501.1, 20.4, 26.2);
}
fn spectrum_cie_y(l: vec4f) -> vec4f {
  return 0.821 * spectrum_lobe(l, 568.8, 46.9, 40.5) + 0.286 * spectrum_lobe(l, 530.9, 16.3, 31.1);
}
fn spectrum_cie_z(l: vec4f) -> vec4f {
  return 1.217 * spectrum_lobe(l, 437.0, 11.8, 36.0) + 0.681 * spectrum_lobe(l, 459.0, 26.0, 13.8);
}

// The path's channels as linear sRGB: in spectral mode the Monte Carlo estimate of XYZ over the four
// wavelengths (¼ Σ L(λ) cmf(λ) / pdf(λ)), then RGB; in RGB mode the channels.
fn channels_to_rgb(c: vec4f) -> vec3f {
  if (!SPECTRAL) {
    return c.xyz;
  }
  let l = path_wavelengths.lambda;
  let pdf = path_wavelengths.pdf;
  let w = c / max(pdf, vec4f(1e-20)) * (0.25 / SPECTRUM_Y_INTEGRAL);
  let xyz = vec3f(dot(w, spectrum_cie_x(l)), dot(w, spectrum_cie_y(l)), dot(w, spectrum_cie_z(l)));
  return vec3f(dot(SPECTRUM_RGB_FROM_XYZ_0, xyz), dot(SPECTRUM_RGB_FROM_XYZ_1, xyz), dot(SPECTRUM_RGB_FROM_XYZ_2, xyz));
}
