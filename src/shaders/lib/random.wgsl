// Random numbers behind one stream type, Rng, drawn by rng_next_f32 / rng_next_2d:
//  - a PCG32 generator (32-bit LCG state, RXS-M-XS output permutation; O'Neill 2014, "PCG: A Family
//    of Simple Fast Space-Efficient Statistically Good Algorithms for Random Number Generation"),
//    seeded by the PCG hash (Jarzynski & Olano 2020, "Hash Functions for GPU Rendering", JCGT 9(3)):
//    white noise. rng_seed always gives this stream (tests, the debug views' primary rays);
//  - the path tracers' sampler (sampler_seed, settings.sampler): that stream, or (SAMPLER_SOBOL) an
//    Owen-scrambled Sobol sequence per pixel spread over the screen as blue noise, below.
// Expects nothing.
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

const SAMPLER_RANDOM: u32 = 0u;
const SAMPLER_SOBOL: u32 = 1u;

// Rng.dimension of a PCG stream (a Sobol stream counts its pairs there).
const RNG_WHITE: u32 = 0xffffffffu;

struct Rng {
  // PCG: the generator's state. Sobol: the stream's scrambling key (from the seed).
  state: u32,
  // Sobol: the next dimension pair to draw. RNG_WHITE: a PCG stream.
  dimension: u32,
  // Sobol: the sample's index in its pixel's sequence.
  sample_index: u32,
  // Sobol: the pixel's place in the screen's scrambled Morton order.
  pixel_rank: u32,
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
fn sampler_seed(sampler: u32, pixel: vec2u, image_size: vec2u, sample_index: u32, seed: u32) -> Rng {
  if (sampler != SAMPLER_SOBOL) {
    return rng_seed(pixel.y * image_size.x + pixel.x, sample_index, seed);
  }
  let key = pcg_hash(seed ^ 0x2545f491u);
  return Rng(key, 0u, sample_index, morton_rank(pixel, image_size, pcg_hash(key)));
}

// What a stream must keep to go on later (the wavefront's path state keeps one word): the PCG state,
// or the Sobol stream's next pair; rng_resume(the same sampler_seed, word) goes on from there.
fn rng_word(rng: Rng) -> u32 {
  return select(rng.dimension, rng.state, rng.dimension == RNG_WHITE);
}

fn rng_resume(seeded: Rng, word: u32) -> Rng {
  var rng = seeded;
  if (rng.dimension == RNG_WHITE) {
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
  if ((*rng).dimension == RNG_WHITE) {
    return pcg_next_u32(rng);
  }
  let p = sobol_next_2d_bits(rng);
  return pcg_hash(p.x ^ pcg_hash(p.y));
}

// Uniform in [0, 1): the top 24 bits, so every value is exactly representable and 1.0 never occurs.
fn rng_next_f32(rng: ptr<function, Rng>) -> f32 {
  if ((*rng).dimension == RNG_WHITE) {
    return f32(pcg_next_u32(rng) >> 8u) * (1.0 / 16777216.0);
  }
  return unit_f32(sobol_next_2d_bits(rng).x);
}

fn rng_next_2d(rng: ptr<function, Rng>) -> vec2f {
  if ((*rng).dimension == RNG_WHITE) {
    let x = f32(pcg_next_u32(rng) >> 8u) * (1.0 / 16777216.0);
    return vec2f(x, f32(pcg_next_u32(rng) >> 8u) * (1.0 / 16777216.0));
  }
  let p = sobol_next_2d_bits(rng);
  return vec2f(unit_f32(p.x), unit_f32(p.y));
}

fn unit_f32(bits: u32) -> f32 {
  return f32(bits >> 8u) * (1.0 / 16777216.0);
}

// The Sobol stream's next dimension pair as 32-bit fixed-point fractions.
fn sobol_next_2d_bits(rng: ptr<function, Rng>) -> vec2u {
  let d = (*rng).dimension;
  (*rng).dimension = d + 1u;
  let key = pcg_hash((*rng).state ^ pcg_hash(d));
  let index = owen_scramble((*rng).sample_index, key) ^ owen_scramble((*rng).pixel_rank, pcg_hash(key ^ 0x68e31da4u));
  let p = sobol_2d(index);
  return vec2u(owen_scramble(p.x, pcg_hash(key ^ 0xb5297a4du)), owen_scramble(p.y, pcg_hash(key ^ 0x1b56c4e9u)));
}

// Point i of the first two Sobol dimensions as 32-bit fractions: the van der Corput sequence (the
// index's bits reversed) and the dimension of primitive polynomial x + 1, whose direction numbers are
// v_0 = 1/2, v_j = v_{j-1} ^ (v_{j-1} >> 1): v_j's bit 31 − k is C(j, k) mod 2, which by Lucas's
// theorem is 1 exactly when k's bits are a subset of j's. So bit 31 − k of the point is the XOR of
// the index bits i_j over every j ⊇ k: a superset transform over the 5-bit positions, five
// shift-mask-XOR steps (one per position bit) instead of a loop over the index's 32 bits (equal for
// every index: tests/gpu/sampler.test.ts compares it with the loop).
fn sobol_2d(i: u32) -> vec2u {
  var z = i;
  z ^= (z >> 1u) & 0x55555555u;
  z ^= (z >> 2u) & 0x33333333u;
  z ^= (z >> 4u) & 0x0f0f0f0fu;
  z ^= (z >> 8u) & 0x00ff00ffu;
  z ^= (z >> 16u) & 0x0000ffffu;
  return vec2u(reverseBits(i), reverseBits(z));
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
  return reverseBits(laine_karras_permutation(reverseBits(x), seed));
}

// Permutation p (0 ≤ p < 24) of the four quadtree children, applied to child `digit`: Fisher–Yates on
// (0 1 2 3), packed two bits an entry, with p's factorial-base digits as the choices.
fn permute4(digit: u32, p: u32) -> u32 {
  var items = 0xe4u;
  var r = p;
  for (var i = 3u; i > 0u; i--) {
    let j = r % (i + 1u);
    r /= i + 1u;
    let a = (items >> (2u * i)) & 3u;
    let b = (items >> (2u * j)) & 3u;
    items = (items & ~((3u << (2u * i)) | (3u << (2u * j)))) | (a << (2u * j)) | (b << (2u * i));
  }
  return (items >> (2u * digit)) & 3u;
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
