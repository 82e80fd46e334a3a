// The real-time frame's per-pixel records: the G-buffer the path tracer writes (first hit of the
// first sample) and the temporal history. Shared by passes/path-trace-frame, temporal, atrous and
// denoise-output; the host sizes buffers from these structs by reflection.

// linear_depth of a pixel whose camera ray hit nothing (the sky or the void).
const MISS_DEPTH: f32 = -1.0;
// id of a pixel whose camera ray hit nothing.
const NO_ID: u32 = 0xffffffffu;
// previous_position of a point that was behind the previous camera.
const OFF_SCREEN: f32 = -1e9;

// Describes the surface through the pixel centre (stable while the camera is still, whatever the
// samples' jitter), except albedo and emission, which are the means over the frame's jittered samples
// (so remodulation inverts their demodulation).
struct GBufferTexel {
  // Unit world-space shading normal turned toward the camera (for a miss: minus the ray direction).
  normal: vec3f,
  // Distance along the camera's forward axis, scene units; MISS_DEPTH for a miss.
  linear_depth: f32,
  // Mean first-hit albedo of the frame's samples (1 for a miss): the demodulation factor.
  albedo: vec3f,
  // Material index of the first hit, NO_ID for a miss.
  id: u32,
  // Mean radiance emitted by the samples' first hits: added back after filtering, never filtered.
  emission: vec3f,
  // Linear depth of the first hit seen from the previous camera (MISS_DEPTH for a miss).
  previous_depth: f32,
  // Where the first hit was in the previous frame: image point in pixels (motion = this − pixel centre).
  previous_position: vec2f,
}

struct HistoryTexel {
  // Temporally accumulated demodulated radiance (illumination).
  illumination: vec3f,
  // Frames in the history (0: none).
  length: f32,
  // Accumulated first and second moments of each frame's illumination luminance (SVGF's variance source).
  moments: vec2f,
  // Accumulated first-hit emission (G-buffer emission), blended like the illumination but never filtered.
  emission: vec3f,
}

fn is_miss(g: GBufferTexel) -> bool {
  return g.linear_depth < 0.0;
}

// The demodulation factor: albedo with a floor, so that black texels do not divide by zero. The same
// function demodulates (path tracer) and remodulates (denoise-output), so a pixel round-trips exactly.
fn demodulation(albedo: vec3f) -> vec3f {
  return max(albedo, vec3f(1e-3));
}
