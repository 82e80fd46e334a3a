// The real-time frame's records and how a sample enters them, shared by the megakernel
// (passes/path-trace-frame) and the wavefront (wavefront/frame): the frame parameters and the
// per-pixel records (frame scratch, pixel-centre surface, frame record; denoise/gbuffer has their
// layouts), the split of each sample into demodulated illumination and kept first-hit emission,
// and the demodulation albedo. Group 2, bindings 3–6 (integrator/dispatch has 0–2). Expects the
// scene (group 0) and view (group 1).

#import integrator/dispatch
#import denoise/gbuffer

struct FrameParams {
  // The camera of the previous frame (equal to view.camera for a still camera).
  previous_camera: Camera,
  // 1: the first bounce takes its direct light from the pixel's final reservoir, lent in the frame
  // scratch (ReSTIR DI, restir/restir's restir_lend).
  restir: u32,
  // frame_gbuffer's pass: 0, the pixel-centre records; 1, the pixel emission (pixel_emission), once
  // the records of the pixel's neighbours are written.
  emission_pass: u32,
  // The centres pass traces a ring of pixels around its tile for the emission pass; it counts the
  // rays of the tile's own pixels only, [core_min, core_max), each pixel's once in a frame of bands.
  core_min: vec2u,
  core_max: vec2u,
}

@group(2) @binding(3) var<uniform> frame: FrameParams;
// Four words per pixel (denoise/gbuffer FRAME_*): the frame's mean demodulated radiance, the motion
// and the depth seen from the previous camera. The denoiser reuses them after the temporal pass.
@group(2) @binding(4) var<storage, read_write> frame_scratch: array<u32>;
// The pixel-centre surface: the à-trous filter's edge-stopping guide and the next frame's reference.
@group(2) @binding(5) var<storage, read_write> surface_records: array<SurfaceTexel>;
// Mean albedo and emission of the samples (the centre's filtered emission in between, see below).
@group(2) @binding(6) var<storage, read_write> frame_records: array<FrameTexel>;

// One sample split into the demodulated illumination the filters see and the first-hit emission
// added back after them (SVGF §4 keeps emission apart so that the filter does not blur lamps):
// - through a pinhole, on and around emitters the pixel's emission is pixel_emission's (what emits
//   over the part of the pixel that sees it), the same for every sample, so lamps and their edges are
//   steady from the first frame: a sample that met a surface leaves its own emission out there (and
//   where it met the centre's material, whose emission the grid counts);
// - elsewhere a sample that saw another surface than the centre's (a silhouette: the sky behind a
//   wall, a lamp too thin for the grid to be traced) puts its whole radiance in the illumination where
//   the pixel stands still (`still`: its surface has not moved on the screen), which the temporal
//   accumulation averages over frames like any other noise; where the pixel moves, the emission it
//   saw stays apart: reprojected, a history holding emitted light is resampled bilinearly into the
//   neighbours of the same surface and carries the light off the emitter's edge;
// - where both it and the centre see the environment, or a thin lens spreads the samples, its own
//   emission stays apart (the sky is not blurred; defocus is the samples' truth).
// `factor` is the albedo the sample is divided by (pixel_demodulation).
struct SampleSplit {
  illumination: vec3f,
  emission: vec3f,
}

fn split_sample(p: PrimaryHit, radiance: vec3f, emitted: vec3f, centre_id: u32, grid: GridEmission, still: bool, factor: vec3f) -> SampleSplit {
  let grid_emission = grid.emission;
  let apart = SampleSplit(max(radiance - emitted, vec3f(0.0)) / demodulation(factor), emitted);
  if (view.camera.aperture_radius != 0.0 || (p.id == NO_PRIMARY_ID && centre_id == NO_ID)) {
    return apart;
  }
  if (p.id != NO_PRIMARY_ID && (p.id == centre_id || grid.traced)) {
    return SampleSplit(apart.illumination, grid_emission);
  }
  if (!still) {
    return SampleSplit(apart.illumination, grid_emission + emitted);
  }
  return SampleSplit(radiance / demodulation(factor), grid_emission);
}

// pixel_emission as the G-buffer's emission pass leaves it in the frame record: `traced` where the
// points were traced (the pixel is on or beside an emitter), whatever they met. Which samples leave
// their own emission out depends on this alone, not on what the points happened to meet: deciding by
// the measured emission (> 0) counted a lamp's light twice in a frame whose points missed a sliver
// of it, once through the samples that met it.
struct GridEmission {
  traced: bool,
  emission: vec3f,
}

// The frame record's emission word of a traced pixel whose points met nothing that emits: rgb9e5
// with zero mantissas and the largest exponent, which unpacks to 0 like the word 0 of an untraced one.
const GRID_TRACED_NOTHING: u32 = 0xf8000000u;

fn pack_grid_emission(traced: bool, emission: vec3f) -> u32 {
  let word = pack_rgb9e5(emission);
  return select(word, select(word, GRID_TRACED_NOTHING, word == 0u), traced);
}

fn unpack_grid_emission(word: u32) -> GridEmission {
  return GridEmission(word != 0u, unpack_rgb9e5(word));
}

// Whether the pixel's centre surface stands still on the screen since the previous frame (its motion
// under a hundredth of a pixel): a still camera and no moving instance there.
fn pixel_still(pixel_index: u32) -> bool {
  let motion = unpack_motion(frame_scratch[FRAME_WORDS * pixel_index + FRAME_MOTION]);
  return !is_off_screen_motion(motion) && all(abs(motion) < vec2f(STILL_MOTION));
}

// Motion (pixels) below which a pixel counts as still (pixel_still).
const STILL_MOTION: f32 = 0.01;

// What a pixel's samples are divided by and its filtered illumination multiplied by again
// (demodulation, SVGF §4). The output is remodulation × mean(radiance / demodulation), the mean
// radiance exactly when both factors are one number for the pixel; only then is the history an honest
// average over frames. Each sample's own first-hit albedo (fixed false; the remodulation the frame's
// mean of them) keeps texture detail finer than the filters out of the illumination, but biases the
// accumulated image wherever a pixel's samples see surfaces of different albedo: a silhouette (the
// Cornell box's wall edges against the void read 0.22 for 0.02, whatever the sample count). So
// where the centre's albedo is one number for its whole material (no texture) or the centre sees
// nothing (albedo 1), every sample is divided by it and the output multiplied by it: the material's
// base colour, read from the material table (no texture, so nothing to evaluate at the hit), rounded
// as the frame record stores it so that the two factors are the same number. A textured centre keeps
// the samples' own albedo: one texel does not stand for the pixel, and the spatial filter, which
// mixes the pixel's illumination with its neighbours', then brightened a bright texel's pixel among
// dark ones ×20 (E1M1, docs/denoise.md).
struct Demodulation {
  fixed: bool,
  albedo: vec3f,
}

fn pixel_demodulation(pixel_index: u32) -> Demodulation {
  let id = surface_records[pixel_index].id;
  if (id == NO_ID) {
    return Demodulation(true, vec3f(1.0));
  }
  let material = scene_material(id);
  return Demodulation(material.base_color_texture == NO_TEXTURE, unpack_rgb9e5(pack_rgb9e5(material.base_color)));
}

// The factor for one sample, and the frame record's remodulation albedo from the samples' mean.
fn sample_factor(d: Demodulation, p: PrimaryHit) -> vec3f {
  return select(p.albedo, d.albedo, d.fixed);
}

fn remodulation_albedo(d: Demodulation, samples_mean: vec3f) -> vec3f {
  return select(samples_mean, d.albedo, d.fixed);
}
