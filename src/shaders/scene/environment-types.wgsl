// The environment's GPU layout (EnvironmentInfo, EnvironmentSample) and its kind and flag constants;
// gpu/pack/environment-pack.ts fills EnvironmentInfo by reflection. Expects nothing.
// Conventions (lat-long orientation, azimuth, units) are those of scene/environment.ts and docs/environment.md.

// Closed set of environment kinds, mirrored by position in gpu/pack/environment-pack.ts.
const ENVIRONMENT_KIND_NONE: u32 = 0u;
const ENVIRONMENT_KIND_CONSTANT: u32 = 1u;
const ENVIRONMENT_KIND_GRADIENT: u32 = 2u;
const ENVIRONMENT_KIND_SKY: u32 = 3u;
const ENVIRONMENT_KIND_MAP: u32 = 4u;

// environment_map holds radiance worth sampling (some texel is nonzero).
const ENVIRONMENT_HAS_MAP: u32 = 1u;
// The sun's disk is above the horizon and bright.
const ENVIRONMENT_HAS_SUN: u32 = 2u;

struct EnvironmentInfo {
  // ENVIRONMENT_KIND_*; every kind but NONE is baked into environment_map.
  kind: u32,
  // ENVIRONMENT_HAS_* bits.
  flags: u32,
  // Width and height of environment_map in texels (lat-long, top row = +y).
  map_size: vec2u,
  // cos and sin of the map's rotation about +y (from +z toward +x): world_from_map.
  rotation_cos_sin: vec2f,
  // Multiplies the texels of environment_map (the map's or the sky's intensity; 1 otherwise).
  intensity: f32,
  // 1 − cos(angular radius of the sun), computed in double precision on the host: f32 cos of a
  // 0.27° angle keeps only ~3 digits of 1 − cos.
  sun_one_minus_cos_max: f32,
  // Unit world-space direction toward the sun's centre.
  sun_direction: vec3f,
  // 1 / solid angle of the sun's disk (sr⁻¹): the density of uniform cone sampling.
  sun_pdf: f32,
  // Radiance inside the sun's disk (intensity included), linear RGB.
  sun_radiance: vec3f,
}

// A direction toward the environment (or the sun), what is seen along it and the solid-angle density
// with which it was drawn (0: no sample).
struct EnvironmentSample {
  direction: vec3f,
  radiance: vec3f,
  pdf: f32,
}
