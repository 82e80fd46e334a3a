// Automatic exposure (eye adaptation): the image's log-average luminance (Reinhard et al. 2002,
// "Photographic Tone Reproduction for Digital Images", eq. 1) by a two-pass reduction, then the
// exposure moved toward the one that maps that average to middle grey by an exponential law in
// stops (renderer/exposure.ts is the CPU twin the tests hold this to).
// Expects the view (group 1) for the image size; its own inputs and outputs are group 2.

#import lib/color
#import lib/exposure
#import view/bindings

// exposure_reduce: a 16 × 16 workgroup sums a 64 × 64 tile, each thread 4 × 4 pixels strided by 16
// (neighbouring threads read neighbouring pixels).
const REDUCE_TILE: u32 = 64u;
const REDUCE_SIDE: u32 = 16u;
const REDUCE_THREADS: u32 = 256u;

struct ExposureParams {
  // 1 / samples accumulated per pixel (1 for a real-time frame).
  inv_sample_count: f32,
  // Workgroups of exposure_reduce along x, and in all (the partial sums' count).
  groups_x: u32,
  group_count: u32,
  // exp(−Δt / τ): the fraction of the old exposure's distance to the target kept. 0 snaps to the
  // target (a new scene, automatic exposure just turned on).
  keep: f32,
  // Stops added to the target exposure.
  compensation_stops: f32,
}

@group(2) @binding(0) var<uniform> params: ExposureParams;
@group(2) @binding(1) var<storage, read> radiance: array<vec4f>;
// Per reduce workgroup: (sum of log2 luminance, pixel count).
@group(2) @binding(2) var<storage, read_write> partials: array<vec2f>;
@group(2) @binding(3) var<storage, read_write> state: ExposureState;

var<workgroup> sums: array<vec2f, REDUCE_THREADS>;

fn reduce_sums(index: u32) {
  for (var stride = REDUCE_THREADS / 2u; stride > 0u; stride >>= 1u) {
    workgroupBarrier();
    if (index < stride) {
      sums[index] += sums[index + stride];
    }
  }
  workgroupBarrier();
}

@compute @workgroup_size(16, 16)
fn exposure_reduce(@builtin(workgroup_id) group: vec3u, @builtin(local_invocation_id) local: vec3u, @builtin(local_invocation_index) index: u32) {
  let size = view.image_size;
  var sum = vec2f(0.0);
  for (var y = 0u; y < REDUCE_TILE; y += REDUCE_SIDE) {
    for (var x = 0u; x < REDUCE_TILE; x += REDUCE_SIDE) {
      let p = group.xy * REDUCE_TILE + local.xy + vec2u(x, y);
      if (all(p < size)) {
        let c = radiance[p.y * size.x + p.x].rgb * params.inv_sample_count;
        // A non-finite pixel (a firefly gone wrong) counts as the brightest the range allows.
        let l = select(MAX_EXPOSURE_LUMINANCE, luminance(c), is_finite_vec3(c));
        sum += vec2f(log2(clamp(l, MIN_EXPOSURE_LUMINANCE, MAX_EXPOSURE_LUMINANCE)), 1.0);
      }
    }
  }
  sums[index] = sum;
  reduce_sums(index);
  if (index == 0u) {
    partials[group.y * params.groups_x + group.x] = sums[0];
  }
}

@compute @workgroup_size(256)
fn exposure_adapt(@builtin(local_invocation_index) index: u32) {
  var sum = vec2f(0.0);
  for (var i = index; i < params.group_count; i += REDUCE_THREADS) {
    sum += partials[i];
  }
  sums[index] = sum;
  reduce_sums(index);
  if (index == 0u) {
    let total = sums[0];
    // An empty image keeps middle grey at exposure 0.
    let log2_average = select(log2(MIDDLE_GREY), total.x / max(total.y, 1.0), total.y > 0.0);
    let target_stops = log2(MIDDLE_GREY) - log2_average + params.compensation_stops;
    let stops = select(target_stops, target_stops + (state.stops - target_stops) * params.keep, params.keep > 0.0);
    state = ExposureState(log2_average, stops, exp2(stops));
  }
}
