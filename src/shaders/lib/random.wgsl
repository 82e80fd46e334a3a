// Random numbers behind one stream type, Rng, drawn by rng_next_f32 / rng_next_2d:
//  - a PCG32 generator (32-bit LCG state, RXS-M-XS output permutation; O'Neill 2014, "PCG: A Family
//    of Simple Fast Space-Efficient Statistically Good Algorithms for Random Number Generation"),
//    seeded by the PCG hash (Jarzynski & Olano 2020, "Hash Functions for GPU Rendering", JCGT 9(3)):
//    white noise. rng_seed always gives this stream (tests, the debug views' primary rays);
//  - the path tracers' sampler (sampler_seed, settings.sampler): that stream, or (SAMPLER_SOBOL) an
//    Owen-scrambled Sobol sequence per pixel spread over the screen as blue noise, below.
// Expects nothing (lib/bits: its bit reversal).
//
// The Sobol sampler. Every rng_next_2d draws one 2D dimension pair d (camera jitter d = 0, lens
// d = 1, then the path's draws in trace_path's order; rng_next_f32 draws a whole pair and keeps x, so
// that the pairs stay aligned across samples; a path that ends early just stops drawing). Pair d of
// sample s of pixel p is the point
//     owen_d( sobol( shuffle_d(s) ^ shuffle'_d(rank(p)) ) )
// where sobol(i) is the first two dimensions of the Sobol sequence (a (0,2)-sequence in base 2),
// owen_d a hash-based nested uniform (Owen) scramble of each coordinate and shuffle_d a nested uniform
// scramble of the index bits (Burley 2020, "Practical Hash-based Owen Scrambling", JCGT 9(4): the
// per-pair index shuffle is its padding, which decorrelates the pairs), and rank(p) the pixel's place
// in a randomly scrambled Morton order of the screen (Ahmed & Wonka 2020, "Screen-Space Blue-Noise
// Diffusion of Monte Carlo Sampling Error via Hierarchical Ordering of Pixels": the four children of
// every quadtree node are taken in a random order). Why this shape:
//  - the Sobol points are linear over GF(2), sobol(a ^ b) = sobol(a) ^ sobol(b), so the rank term is a
//    digital shift of the pixel's own sequence, and digital shifts, Owen scrambles and the index
//    shuffle (bit j of an index flips as a function of the bits above j only) all map aligned blocks
//    of 2^k indices to aligned blocks and nets to nets. Hence both:
//      · per pixel, samples [m·2^k, (m+1)·2^k) form a (0,k,2)-net in every pair: each pixel converges
//        as a low-discrepancy sequence, also across the frames of the real-time chain, whose
//        params.sample_index advances every frame (frames decorrelated, their union stratified);
//      · per sample, the pixels of an aligned 2^a × 2^a screen tile hold one aligned block of 4^a
//        indices, a (0,2a,2)-net: neighbours take stratified points, so a 1-spp frame's error is
//        pushed to high spatial frequencies (blue), which the à-trous filter and TAA remove best;
//  - no tables (the second Sobol dimension's direction numbers follow v ^= v >> 1), unlike the rank
//    and scrambling tables of Heitz et al. 2019 (kilobytes per dimension, 128 × 128 tiles);
//  - unlike Ahmed & Wonka's single global sequence (index = rank·spp + s), it needs no sample count
//    known in advance, which progressive and real-time rendering do not have.
// The cost: pixels of a tile share their index block across samples, so a 2 × 2 tile's first two
// frames hold its four points twice (each pixel's own sequence stays a net).

#import lib/bits

const SAMPLER_RANDOM: u32 = 0u;
const SAMPLER_SOBOL: u32 = 1u;
// Not a sampler but the default of SAMPLER below: each stream says at run time which it is.
const PER_STREAM_SAMPLER: u32 = 2u;

// The sampler compiled into a kernel, a pipeline constant (SAMPLER_*): the path tracers' kernels are
// compiled for the sampler their chain uses (passes/path-trace-pass.ts TracingKernels), so that a PCG
// kernel carries none of the Sobol code. With both in the kernel and the choice made per stream at run
// time, PCG paths ran 2–16 % slower on an H200 (Cornell, rtiow, E1M1; docs/perf.md, 2026-12-01) for
// the Sobol code they carried (registers, most likely: nothing else differs). PER_STREAM_SAMPLER (the
// default) keeps that run-time choice: tests and kernels that draw PCG streams only.
override SAMPLER: u32 = PER_STREAM_SAMPLER;

// Rng.dimension of a PCG stream (a Sobol stream counts its pairs there).
const RNG_WHITE: u32 = 0xffffffffu;

struct Rng {
  // PCG: the generator's state. Sobol: the stream's scrambling key (from the seed).
  state: u32,
  // Sobol: the next dimension pair to draw. RNG_WHITE: a PCG stream.
  dimension: u32,
  // Sobol: the sample's index in its pixel's sequence, its bits reversed (see sobol_next_2d_bits).
  sample_bits: u32,
  // Sobol: the pixel's place in the screen's scrambled Morton order, its bits reversed.
  rank_bits: u32,
}

fn pcg_hash(v: u32) -> u32 {
  let state = v * 747796405u + 2891336453u;
  let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// A PCG stream for one pixel and one batch of samples. Hashing the inputs in sequence (rather than
// adding them) keeps neighbouring pixels and consecutive batches decorrelated.
fn rng_seed(pixel_index: u32, sample_index: u32, seed: u32) -> Rng {
  return Rng(pcg_hash(pixel_index ^ pcg_hash(sample_index ^ pcg_hash(seed))), RNG_WHITE, 0u, 0u);
}

// The stream of one sample of one pixel of an image of image_size pixels from the chosen sampler
// (SAMPLER_*): the PCG stream of rng_seed, or the Sobol sampler's sample `sample_index` of the pixel.
// A kernel compiled for one sampler (SAMPLER) uses it whatever `sampler` says.
fn sampler_seed(sampler: u32, pixel: vec2u, image_size: vec2u, sample_index: u32, seed: u32) -> Rng {
  return sampler_next_sample(sampler_pixel(sampler, pixel, image_size, seed), pixel, image_size, sample_index, seed);
}

// What every sample of a pixel shares, worked out once for a loop over its samples (the Sobol
// sampler's pixel rank walks the screen's quadtree): give it to sampler_next_sample for each sample.
fn sampler_pixel(sampler: u32, pixel: vec2u, image_size: vec2u, seed: u32) -> Rng {
  let chosen = select(sampler, SAMPLER, SAMPLER != PER_STREAM_SAMPLER);
  if (chosen != SAMPLER_SOBOL) {
    return Rng(0u, RNG_WHITE, 0u, 0u);
  }
  let key = pcg_hash(seed ^ 0x2545f491u);
  return Rng(key, 0u, 0u, bits_reverse(morton_rank(pixel, image_size, pcg_hash(key))));
}

// The stream of sample `sample_index` of the pixel `pixel_stream` (sampler_pixel) was made for.
fn sampler_next_sample(pixel_stream: Rng, pixel: vec2u, image_size: vec2u, sample_index: u32, seed: u32) -> Rng {
  if (rng_is_white(pixel_stream)) {
    return rng_seed(pixel.y * image_size.x + pixel.x, sample_index, seed);
  }
  var rng = pixel_stream;
  rng.sample_bits = bits_reverse(sample_index);
  return rng;
}

// Whether a stream is PCG's: known when the kernel is compiled for PCG, else the stream says.
fn rng_is_white(rng: Rng) -> bool {
  return SAMPLER == SAMPLER_RANDOM || rng.dimension == RNG_WHITE;
}

// What a stream must keep to go on later (the wavefront's path state keeps one word): the PCG state,
// or the Sobol stream's next pair; rng_resume(the same sampler_seed, word) goes on from there.
fn rng_word(rng: Rng) -> u32 {
  return select(rng.dimension, rng.state, rng_is_white(rng));
}

fn rng_resume(seeded: Rng, word: u32) -> Rng {
  var rng = seeded;
  if (rng_is_white(rng)) {
    rng.state = word;
  } else {
    rng.dimension = word;
  }
  return rng;
}

fn pcg_next_u32(rng: ptr<function, Rng>) -> u32 {
  let old = (*rng).state;
  (*rng).state = old * 747796405u + 2891336453u;
  let word = ((old >> ((old >> 28u) + 4u)) ^ old) * 277803737u;
  return (word >> 22u) ^ word;
}

// 32 random bits (white noise): a PCG stream's next word, or a Sobol stream's next pair hashed.
fn rng_next_u32(rng: ptr<function, Rng>) -> u32 {
  if (rng_is_white(*rng)) {
    return pcg_next_u32(rng);
  }
  let p = sobol_next_2d_bits(rng);
  return pcg_hash(p.x ^ pcg_hash(p.y));
}

// Uniform in [0, 1): the top 24 bits, so every value is exactly representable and 1.0 never occurs.
fn rng_next_f32(rng: ptr<function, Rng>) -> f32 {
  if (rng_is_white(*rng)) {
    return f32(pcg_next_u32(rng) >> 8u) * (1.0 / 16777216.0);
  }
  return unit_f32(sobol_next_2d_bits(rng).x);
}

fn rng_next_2d(rng: ptr<function, Rng>) -> vec2f {
  if (rng_is_white(*rng)) {
    let x = f32(pcg_next_u32(rng) >> 8u) * (1.0 / 16777216.0);
    return vec2f(x, f32(pcg_next_u32(rng) >> 8u) * (1.0 / 16777216.0));
  }
  let p = sobol_next_2d_bits(rng);
  return vec2f(unit_f32(p.x), unit_f32(p.y));
}

fn unit_f32(bits: u32) -> f32 {
  return f32(bits >> 8u) * (1.0 / 16777216.0);
}

// The Sobol stream's next dimension pair as 32-bit fixed-point fractions:
//     index = owen(sample_index, key) ^ owen(pixel_rank, key')
//     point = (owen(sobol_x(index), key_x), owen(sobol_y(index), key_y))
// with owen(x, k) = reverseBits(lk(reverseBits(x), k)) and sobol_x(i) = reverseBits(i), written so that
// the reversals cancel: the stream keeps its sample index and rank reversed, one reversal makes the
// index, and each coordinate needs one (three a pair instead of ten; the same points bit for bit).
fn sobol_next_2d_bits(rng: ptr<function, Rng>) -> vec2u {
  let d = (*rng).dimension;
  (*rng).dimension = d + 1u;
  let key = pcg_hash((*rng).state ^ pcg_hash(d));
  let index = bits_reverse(laine_karras_permutation((*rng).sample_bits, key) ^ laine_karras_permutation((*rng).rank_bits, pcg_hash(key ^ 0x68e31da4u)));
  let x = bits_reverse(laine_karras_permutation(index, pcg_hash(key ^ 0xb5297a4du)));
  let y = bits_reverse(laine_karras_permutation(sobol_2d_y_reversed(index), pcg_hash(key ^ 0x1b56c4e9u)));
  return vec2u(x, y);
}

// Point i of the first two Sobol dimensions as 32-bit fractions: the van der Corput sequence (the
// index's bits reversed) and the dimension of primitive polynomial x + 1, whose direction numbers are
// v_0 = 1/2, v_j = v_{j-1} ^ (v_{j-1} >> 1): v_j's bit 31 − k is C(j, k) mod 2, which by Lucas's
// theorem is 1 exactly when k's bits are a subset of j's. So bit 31 − k of the point is the XOR of
// the index bits i_j over every j ⊇ k: a superset transform over the 5-bit positions, five
// shift-mask-XOR steps (one per position bit) instead of a loop over the index's 32 bits (equal for
// every index: tests/gpu/sampler.test.ts compares it with the loop).
fn sobol_2d(i: u32) -> vec2u {
  return vec2u(bits_reverse(i), bits_reverse(sobol_2d_y_reversed(i)));
}

// The second coordinate of sobol_2d(i) with its bits reversed (bit k of the result is bit 31 − k of
// the point): the superset transform itself.
fn sobol_2d_y_reversed(i: u32) -> u32 {
  var z = i;
  z ^= (z >> 1u) & 0x55555555u;
  z ^= (z >> 2u) & 0x33333333u;
  z ^= (z >> 4u) & 0x0f0f0f0fu;
  z ^= (z >> 8u) & 0x00ff00ffu;
  z ^= (z >> 16u) & 0x0000ffffu;
  return z;
}

// A permutation of 32-bit words in which each bit depends only on itself and the bits below it
// (additions and multiplications carry upwards only): a Laine–Karras style hash, with the constants of
// Vegdahl 2021 ("Building a Better LK Hash"), better mixed than Burley's original four.
fn laine_karras_permutation(x: u32, seed: u32) -> u32 {
  var v = x ^ (x * 0x3d20adeau);
  v += seed;
  v *= (seed >> 16u) | 1u;
  v ^= v * 0x05526c56u;
  v ^= v * 0x53a22864u;
  return v;
}

// A nested uniform (Owen) scramble of x read as a binary fraction: bit j (from the top) flips as a
// random function of the bits above it, so dyadic intervals map to dyadic intervals of the same size.
// Applied to an index it is Burley's shuffle: aligned blocks of 2^k indices map to aligned blocks.
fn owen_scramble(x: u32, seed: u32) -> u32 {
  return bits_reverse(laine_karras_permutation(bits_reverse(x), seed));
}

// Permutation p (0 ≤ p < 24) of the four quadtree children, applied to child `digit`: Fisher–Yates on
// (0 1 2 3) with p's factorial-base digits as the choices, tabulated (PERMUTATIONS_4: each
// permutation's four entries two bits each, four permutations a word; tests/gpu/sampler.test.ts holds
// the table to the shuffle), since every pixel walks a dozen levels for every sample.
const PERMUTATIONS_4_LOW = vec3u(0xc98d4b39u, 0xd293721eu, 0xe1b1632du);
const PERMUTATIONS_4_HIGH = vec3u(0xc6874e36u, 0xd89c781bu, 0xe4b46c27u);

fn permute4(digit: u32, p: u32) -> u32 {
  let w = p >> 2u;
  let word = select(PERMUTATIONS_4_HIGH[w - 3u], PERMUTATIONS_4_LOW[w], w < 3u);
  return (word >> ((p & 3u) * 8u + 2u * digit)) & 3u;
}

// The pixel's place in a scrambled Morton (Z) order of the screen (Ahmed & Wonka 2020): two bits per
// quadtree level, top level first, each level's child permuted at random by a hash of the node (its
// path from the root). Only the levels the image needs are walked; above them every pixel shares the
// same path, which would only add the same constant to every rank.
fn morton_rank(pixel: vec2u, image_size: vec2u, key: u32) -> u32 {
  let extent = max(max(image_size.x, image_size.y), 2u) - 1u;
  let levels = min(32u - countLeadingZeros(extent), 16u);
  var rank = 0u;
  var node = key;
  for (var level = levels; level > 0u; level--) {
    let digit = ((pixel.x >> (level - 1u)) & 1u) | (((pixel.y >> (level - 1u)) & 1u) << 1u);
    let h = pcg_hash(node);
    rank = (rank << 2u) | permute4(digit, h % 24u);
    node = h ^ ((digit + 1u) * 0x9e3779b9u);
  }
  return rank;
}
