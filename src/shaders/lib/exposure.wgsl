// The automatic exposure's state, written by passes/exposure and read by passes/tonemap, and the
// constants of its average. Mirrors renderer/exposure.ts (MIDDLE_GREY, the luminance clamp).

// The luminance the log-average is mapped to: Reinhard's key of a normal scene.
const MIDDLE_GREY: f32 = 0.18;
// Luminances are clamped to [2^-20, 2^20] before the log: an unlit pixel (exactly 0) would
// otherwise pull the average to −∞, and one firefly should not decide the exposure.
const MIN_EXPOSURE_LUMINANCE: f32 = 9.5367431640625e-7;
const MAX_EXPOSURE_LUMINANCE: f32 = 1048576.0;

struct ExposureState {
  // log2 of the image's log-average luminance (linear radiance, before exposure).
  log2_average: f32,
  // The exposure in use, in stops, and 2^stops: what the tone map multiplies radiance by.
  stops: f32,
  scale: f32,
}
