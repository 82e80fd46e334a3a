// Colour: luminance, tone-mapping curves and the sRGB transfer function. Expects nothing.
// ACES: Stephen Hill's fit of the ACES RRT+ODT with its sRGB→ACES input and output matrices
// (the "ACESFitted" of BakingLab, 2016). Reinhard: L/(1+L) on luminance (Reinhard et al. 2002, eq. 3),
// which keeps hue where per-channel Reinhard would desaturate.

// The closed set of tone-mapping operators; the host's names live in renderer/settings.ts.
const TONEMAP_LINEAR: u32 = 0u;
const TONEMAP_REINHARD: u32 = 1u;
const TONEMAP_ACES: u32 = 2u;

// Rec. 709 / sRGB luminance; the TypeScript twin is math/vec3.ts `luminance`.
fn luminance(c: vec3f) -> f32 {
  return dot(c, vec3f(0.2126, 0.7152, 0.0722));
}

fn tonemap_reinhard(c: vec3f) -> vec3f {
  let l = luminance(c);
  return c / (1.0 + l);
}

fn tonemap_aces(c: vec3f) -> vec3f {
  // Column-major constructors: these are the transposes of the row-major matrices usually printed.
  let aces_input = mat3x3f(
    vec3f(0.59719, 0.07600, 0.02840),
    vec3f(0.35458, 0.90834, 0.13383),
    vec3f(0.04823, 0.01566, 0.83777),
  );
  let aces_output = mat3x3f(
    vec3f(1.60475, -0.10208, -0.00327),
    vec3f(-0.53108, 1.10813, -0.07276),
    vec3f(-0.07367, -0.00605, 1.07602),
  );
  let v = aces_input * c;
  let a = v * (v + 0.0245786) - 0.000090537;
  let b = v * (0.983729 * v + 0.4329510) + 0.238081;
  return aces_output * (a / b);
}

fn tonemap(c: vec3f, tone_mapper: u32) -> vec3f {
  switch tone_mapper {
    case TONEMAP_REINHARD: { return tonemap_reinhard(c); }
    case TONEMAP_ACES: { return tonemap_aces(c); }
    default: { return c; }
  }
}

// The sRGB opto-electronic transfer function (IEC 61966-2-1), per channel, for linear values in [0, 1].
fn linear_to_srgb(c: vec3f) -> vec3f {
  let lo = c * 12.92;
  let hi = 1.055 * pow(c, vec3f(1.0 / 2.4)) - 0.055;
  return select(hi, lo, c <= vec3f(0.0031308));
}

// True when every component is a finite number. Tested on the bits, since WGSL compilers may assume
// floats are never inf or NaN and fold `x != x` away.
fn is_finite_vec3(v: vec3f) -> bool {
  let exponent = bitcast<vec3u>(v) & vec3u(0x7f800000u);
  return all(exponent != vec3u(0x7f800000u));
}

// YCoCg (Malvar and Sullivan 2003): luma and two chroma axes, a cheap decorrelation in which a
// neighbourhood's colour box hugs the samples more tightly than in RGB (Karis 2014, "High quality
// temporal supersampling"). Exactly invertible.
fn rgb_to_ycocg(c: vec3f) -> vec3f {
  return vec3f(0.25 * c.r + 0.5 * c.g + 0.25 * c.b, 0.5 * c.r - 0.5 * c.b, -0.25 * c.r + 0.5 * c.g - 0.25 * c.b);
}

fn ycocg_to_rgb(c: vec3f) -> vec3f {
  return vec3f(c.x + c.y - c.z, c.x + c.z, c.x - c.y - c.z);
}
