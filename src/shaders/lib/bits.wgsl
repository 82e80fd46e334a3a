// Bit operations that GLSL ES 3.00 lacks (bitfieldReverse, findLSB and bitCount are ES 3.10), behind
// functions of their own: here WGSL's built-ins, which the compute kernels use; lib/bits-es300, the
// same results by shifts and masks, is linked in their place for the fragment tracer that WebGL2 runs
// (gpu/fragment-tracer-wgsl.ts; naga writes the built-ins as they are). Expects nothing.

fn bits_reverse(x: u32) -> u32 {
  return reverseBits(x);
}

// The index of the lowest set bit; 0xffffffff for 0.
fn bits_first_trailing(x: u32) -> u32 {
  return firstTrailingBit(x);
}

fn bits_count_ones(x: u32) -> u32 {
  return countOneBits(x);
}
