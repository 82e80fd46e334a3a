// Random numbers: a PCG32 generator (32-bit LCG state, RXS-M-XS output permutation; O'Neill 2014,
// "PCG: A Family of Simple Fast Space-Efficient Statistically Good Algorithms for Random Number
// Generation"), seeded per pixel and sample by the PCG hash (Jarzynski & Olano 2020, "Hash Functions
// for GPU Rendering", JCGT 9(3)). Expects nothing.

struct Rng {
  state: u32,
}

fn pcg_hash(v: u32) -> u32 {
  let state = v * 747796405u + 2891336453u;
  let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// A stream for one pixel and one batch of samples. Hashing the inputs in sequence (rather than
// adding them) keeps neighbouring pixels and consecutive batches decorrelated.
fn rng_seed(pixel_index: u32, sample_index: u32, seed: u32) -> Rng {
  return Rng(pcg_hash(pixel_index ^ pcg_hash(sample_index ^ pcg_hash(seed))));
}

fn rng_next_u32(rng: ptr<function, Rng>) -> u32 {
  let old = (*rng).state;
  (*rng).state = old * 747796405u + 2891336453u;
  let word = ((old >> ((old >> 28u) + 4u)) ^ old) * 277803737u;
  return (word >> 22u) ^ word;
}

// Uniform in [0, 1): the top 24 bits, so every value is exactly representable and 1.0 never occurs.
fn rng_next_f32(rng: ptr<function, Rng>) -> f32 {
  return f32(rng_next_u32(rng) >> 8u) * (1.0 / 16777216.0);
}

fn rng_next_2d(rng: ptr<function, Rng>) -> vec2f {
  let x = rng_next_f32(rng);
  return vec2f(x, rng_next_f32(rng));
}
