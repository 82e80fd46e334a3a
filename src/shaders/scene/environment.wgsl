// INTERIM (replaced by the environment branch): the environment interface, black.
struct EnvironmentSample {
  direction: vec3f,
  radiance: vec3f,
  pdf: f32,
}
fn environment_radiance(direction: vec3f) -> vec3f { return vec3f(0.0); }
fn sample_environment(u: vec2f) -> EnvironmentSample { return EnvironmentSample(vec3f(0.0, 1.0, 0.0), vec3f(0.0), 0.0); }
fn environment_pdf(direction: vec3f) -> f32 { return 0.0; }
fn sun_radiance(direction: vec3f) -> vec3f { return vec3f(0.0); }
fn sample_sun(u: vec2f) -> EnvironmentSample { return EnvironmentSample(vec3f(0.0, 1.0, 0.0), vec3f(0.0), 0.0); }
fn sun_pdf(direction: vec3f) -> f32 { return 0.0; }
fn environment_has_map() -> bool { return false; }
fn environment_has_sun() -> bool { return false; }
