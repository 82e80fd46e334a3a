// lib/bits without the built-ins GLSL ES 3.00 lacks: the same results, bit for bit, by shifts, masks
// and a multiply (tests/gpu/fragment-tracer.test.ts compares the two over many words). Linked in place
// of lib/bits by the fragment tracer (gpu/fragment-tracer-wgsl.ts). Expects nothing.

fn bits_reverse(x: u32) -> u32 {
  var v = x;
  v = ((v >> 1u) & 0x55555555u) | ((v & 0x55555555u) << 1u);
  v = ((v >> 2u) & 0x33333333u) | ((v & 0x33333333u) << 2u);
  v = ((v >> 4u) & 0x0f0f0f0fu) | ((v & 0x0f0f0f0fu) << 4u);
  v = ((v >> 8u) & 0x00ff00ffu) | ((v & 0x00ff00ffu) << 8u);
  return (v >> 16u) | (v << 16u);
}

fn bits_count_ones(x: u32) -> u32 {
  var v = x - ((x >> 1u) & 0x55555555u);
  v = (v & 0x33333333u) + ((v >> 2u) & 0x33333333u);
  return (((v + (v >> 4u)) & 0x0f0f0f0fu) * 0x01010101u) >> 24u;
}

// The index of the lowest set bit (the ones below it counted); 0xffffffff for 0.
fn bits_first_trailing(x: u32) -> u32 {
  return select(bits_count_ones((x & (0u - x)) - 1u), 0xffffffffu, x == 0u);
}
