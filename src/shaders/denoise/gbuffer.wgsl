// The real-time frame's per-pixel records, packed (docs/denoise.md, "Memory"): what the path tracer
// writes and what the temporal pass keeps from one frame to the next. Shared by
// passes/path-trace-frame, wavefront/frame, temporal, denoise-atrous and denoise-output; the host
// sizes buffers from these structs by reflection (renderer/recipes/real-time.ts).
//
//   SurfaceTexel (12 B, two: current and previous frame) the surface through the pixel centre
//   FrameTexel (8 B)        the current frame's albedo and first-hit emission, read at remodulation
//   MomentsTexel (8 B, two) luminance moments and history length (reprojected like the colour)
//   illumination history (8 B) f16 rgb + f16 σ: written by the first à-trous iteration (SVGF feedback)
//   frame scratch (16 B)    four words per pixel reused through the frame (FRAME_* below), and at the
//                           end the linear output (vec4f) that the tone mapper reads
//
// Colours are f16 pairs (pack2x16float into u32 storage: shader-f16 is not guaranteed) or rgb9e5
// (shared exponent); normals are octahedral 2 × 16 bits; only depth stays f32.

// linear_depth of a pixel whose camera ray hit nothing (the sky or the void).
const MISS_DEPTH: f32 = -1.0;
// id of a pixel whose camera ray hit nothing.
const NO_ID: u32 = 0xffffffffu;
// previous position (f32 pixels) of a point that was behind the previous camera (the hybrid recipe's motion).
const OFF_SCREEN: f32 = -1e9;
// Motion (f16 pixels) of a point that was behind the previous camera: far outside any image.
const OFF_SCREEN_MOTION: f32 = -32768.0;
// Largest magnitude an f16 holds (pack2x16float of a larger value is not defined).
const F16_MAX: f32 = 65504.0;

// The surface through the pixel centre (stable while the camera is still, whatever the samples'
// jitter): the à-trous guide and, one frame later, the reference of the temporal test.
struct SurfaceTexel {
  // Distance along the camera's forward axis, scene units; MISS_DEPTH for a miss.
  linear_depth: f32,
  // Unit world-space shading normal turned toward the camera (a miss: minus the ray direction),
  // octahedral, pack2x16snorm.
  normal: u32,
  // Material index of the first hit, NO_ID for a miss.
  id: u32,
}

// The current frame's remodulation record.
struct FrameTexel {
  // The remodulation albedo, rgb9e5: the centre's albedo where the pixel's samples are divided by it
  // (a material without texture, or the sky: path-trace-frame's pixel_demodulation), else the mean
  // first-hit albedo of the frame's samples (1 for a miss).
  albedo: u32,
  // Mean first-hit emission of the samples, rgb9e5: added back after filtering, never filtered.
  // frame_gbuffer leaves here the emission at the pixel-centre hit, filtered over the pixel.
  emission: u32,
}

// The temporal pass's per-pixel statistics, reprojected like the colour history.
struct MomentsTexel {
  // f16 pair: mean and variance of the frames' illumination luminance over the history (the
  // luminance clamped to MOMENT_LUMINANCE_MAX, so that its square fits an f16; passes/temporal).
  moments: u32,
  // Frames in the history (0: none).
  length: f32,
}

// The frame scratch, four u32 words per pixel (index 4 · pixel + word). After the path tracer:
const FRAME_RADIANCE: u32 = 0u;       // rgb9e5: the frame's mean demodulated radiance
const FRAME_MOTION: u32 = 1u;         // f16 pair: previous image position − pixel centre (OFF_SCREEN_MOTION)
const FRAME_PREVIOUS_DEPTH: u32 = 2u; // f16 (low half): linear depth seen from the previous camera
// After the temporal pass, words 2 and 3 hold its output (an illumination pair: f16 rgb, f16 σ);
// the à-trous iterations then use words 0–1 and 2–3 as two ping-pong pairs.
const FRAME_TEMPORAL: u32 = 2u;
const FRAME_WORDS: u32 = 4u;

// Luminance above this is clamped in the moments, which only estimate the variance (255² < F16_MAX).
const MOMENT_LUMINANCE_MAX: f32 = 255.0;

// The scratch words are named, not a struct: each pass touches only some of a pixel's words while
// neighbours read others, so nothing loads or stores a whole record of four.

fn is_miss_depth(depth: f32) -> bool {
  return depth < 0.0;
}

// The demodulation factor: albedo with a floor, so that black texels do not divide by zero. The same
// function demodulates (path tracer) and remodulates (denoise-atrous, denoise-output), so a pixel round-trips.
fn demodulation(albedo: vec3f) -> vec3f {
  return max(albedo, vec3f(1e-3));
}

// --- packing -------------------------------------------------------------------------------------

fn pack_f16_pair(a: f32, b: f32) -> u32 {
  return pack2x16float(clamp(vec2f(a, b), vec2f(-F16_MAX), vec2f(F16_MAX)));
}

// Octahedral map of a unit vector onto [−1, 1]² (Cigolle et al. 2014, "A Survey of Efficient
// Representations for Independent Unit Vectors"), 16 bits a coordinate.
fn pack_normal(n: vec3f) -> u32 {
  let p = n.xy / max(abs(n.x) + abs(n.y) + abs(n.z), 1e-30);
  let sign_p = select(vec2f(-1.0), vec2f(1.0), p >= vec2f(0.0));
  let folded = select(p, (1.0 - abs(p.yx)) * sign_p, n.z < 0.0);
  return pack2x16snorm(folded);
}

fn unpack_normal(packed: u32) -> vec3f {
  let e = unpack2x16snorm(packed);
  var n = vec3f(e, 1.0 - abs(e.x) - abs(e.y));
  let t = max(-n.z, 0.0);
  n.x += select(t, -t, n.x >= 0.0);
  n.y += select(t, -t, n.y >= 0.0);
  return normalize(n);
}

// rgb9e5: three 9-bit mantissas and a shared 5-bit exponent (the format of
// EXT_texture_shared_exponent), non-negative values up to 65408, rounded to nearest.
const RGB9E5_MAX: f32 = 65408.0;

fn pack_rgb9e5(c: vec3f) -> u32 {
  let v = clamp(c, vec3f(0.0), vec3f(RGB9E5_MAX));
  let m = max(max(v.r, v.g), v.b);
  var e = clamp(i32(floor(log2(max(m, 1e-30)))) + 16, 0, 31);
  var scale = exp2(f32(e - 24));
  if (floor(m / scale + 0.5) >= 512.0 && e < 31) {
    e += 1;
    scale *= 2.0;
  }
  let q = min(vec3u(floor(v / scale + 0.5)), vec3u(511u));
  return q.r | (q.g << 9u) | (q.b << 18u) | (u32(e) << 27u);
}

fn unpack_rgb9e5(p: u32) -> vec3f {
  let scale = exp2(f32(p >> 27u) - 24.0);
  return vec3f(f32(p & 511u), f32((p >> 9u) & 511u), f32((p >> 18u) & 511u)) * scale;
}

// An illumination pair (two words): f16 rgb and the f16 standard deviation of its luminance (the
// variance itself would underflow f16 in converged regions).
fn pack_illumination(c: vec3f, variance: f32) -> vec2u {
  return vec2u(pack_f16_pair(c.r, c.g), pack_f16_pair(c.b, sqrt(max(variance, 0.0))));
}

// rgb: the illumination; a: its variance.
fn unpack_illumination(p: vec2u) -> vec4f {
  let rg = unpack2x16float(p.x);
  let b_sigma = unpack2x16float(p.y);
  return vec4f(rg, b_sigma.x, b_sigma.y * b_sigma.y);
}

// --- accessors -----------------------------------------------------------------------------------

// The pixel-centre surface, unpacked.
struct PixelSurface {
  normal: vec3f,
  linear_depth: f32,
  id: u32,
}

fn pack_surface(normal: vec3f, linear_depth: f32, id: u32) -> SurfaceTexel {
  return SurfaceTexel(linear_depth, pack_normal(normal), id);
}

fn unpack_surface(t: SurfaceTexel) -> PixelSurface {
  return PixelSurface(unpack_normal(t.normal), t.linear_depth, t.id);
}

fn frame_albedo(t: FrameTexel) -> vec3f {
  return unpack_rgb9e5(t.albedo);
}

fn frame_emission(t: FrameTexel) -> vec3f {
  return unpack_rgb9e5(t.emission);
}

// Motion in pixels (previous image position − pixel centre) from its scratch word.
fn unpack_motion(word: u32) -> vec2f {
  return unpack2x16float(word);
}

fn is_off_screen_motion(motion: vec2f) -> bool {
  return motion.x <= OFF_SCREEN_MOTION;
}

fn pack_motion(motion: vec2f, on_screen: bool) -> u32 {
  return select(pack_f16_pair(OFF_SCREEN_MOTION, OFF_SCREEN_MOTION), pack_f16_pair(clamp(motion.x, -30000.0, 30000.0), motion.y), on_screen);
}
