// One pass of a least-significant-digit radix sort of (key, value) pairs by RADIX_BITS bits at
// sort_params.shift: radix_histogram counts each block's digits into sort_counts (digit-major, so an
// exclusive scan of it, build/scan, gives every (digit, block) its first output index), then
// radix_scatter moves each pair there, stably (a block ranks its keys by digit and thread order).
// Expects the host to run the passes over shifts 0, 4, ... ping-ponging the key and value buffers.

const RADIX_BITS: u32 = 4u;
const RADIX: u32 = 16u;
const SORT_THREADS: u32 = 128u;
const SORT_ITEMS: u32 = 8u;
// Keys per block: one workgroup's share.
const SORT_BLOCK: u32 = 1024u; // SORT_THREADS × SORT_ITEMS (literal: wgsl_reflect cannot evaluate the product)

struct SortParams {
  // The lowest bit of this pass's digit.
  shift: u32,
  key_count: u32,
  // ceil(key_count / SORT_BLOCK).
  block_count: u32,
}

@group(0) @binding(0) var<uniform> sort_params: SortParams;
@group(0) @binding(1) var<storage, read> keys_in: array<u32>;
@group(0) @binding(2) var<storage, read> values_in: array<u32>;
@group(0) @binding(3) var<storage, read_write> keys_out: array<u32>;
@group(0) @binding(4) var<storage, read_write> values_out: array<u32>;
// RADIX × block_count counts (histogram), then their exclusive scan (scatter).
@group(0) @binding(5) var<storage, read_write> sort_counts: array<u32>;

var<workgroup> digit_counts: array<atomic<u32>, RADIX>;
// Scatter: per (digit, thread) counts, digit-major; then their exclusive scan within the block.
var<workgroup> thread_digit_counts: array<u32, RADIX * SORT_THREADS>;
var<workgroup> thread_sums: array<u32, SORT_THREADS>;

fn digit_of(key: u32) -> u32 {
  return (key >> sort_params.shift) & (RADIX - 1u);
}

@compute @workgroup_size(SORT_THREADS)
fn radix_histogram(@builtin(local_invocation_index) lid: u32, @builtin(workgroup_id) wid: vec3u) {
  if (lid < RADIX) {
    atomicStore(&digit_counts[lid], 0u);
  }
  workgroupBarrier();
  // Strided by thread so neighbouring threads read neighbouring keys.
  for (var k = 0u; k < SORT_ITEMS; k++) {
    let i = wid.x * SORT_BLOCK + k * SORT_THREADS + lid;
    if (i < sort_params.key_count) {
      atomicAdd(&digit_counts[digit_of(keys_in[i])], 1u);
    }
  }
  workgroupBarrier();
  if (lid < RADIX) {
    sort_counts[lid * sort_params.block_count + wid.x] = atomicLoad(&digit_counts[lid]);
  }
}

@compute @workgroup_size(SORT_THREADS)
fn radix_scatter(@builtin(local_invocation_index) lid: u32, @builtin(workgroup_id) wid: vec3u) {
  // Thread `lid` owns keys base .. base + SORT_ITEMS (consecutive, so thread order is key order).
  let base = wid.x * SORT_BLOCK + lid * SORT_ITEMS;
  var keys: array<u32, SORT_ITEMS>;
  var digits: array<u32, SORT_ITEMS>;
  for (var d = 0u; d < RADIX; d++) {
    thread_digit_counts[d * SORT_THREADS + lid] = 0u;
  }
  for (var k = 0u; k < SORT_ITEMS; k++) {
    digits[k] = RADIX;
    if (base + k < sort_params.key_count) {
      keys[k] = keys_in[base + k];
      digits[k] = digit_of(keys[k]);
      thread_digit_counts[digits[k] * SORT_THREADS + lid] += 1u;
    }
  }
  workgroupBarrier();
  // Exclusive scan of thread_digit_counts in its digit-major order: thread t takes entries
  // t·RADIX .. t·RADIX + RADIX, sums them, the sums are scanned, and each entry gets its prefix.
  // Entry (d, t) then holds how many of the block's keys precede thread t's keys of digit d.
  var sum = 0u;
  for (var e = 0u; e < RADIX; e++) {
    sum += thread_digit_counts[lid * RADIX + e];
  }
  thread_sums[lid] = sum;
  workgroupBarrier();
  for (var offset = 1u; offset < SORT_THREADS; offset <<= 1u) {
    var add = 0u;
    if (lid >= offset) {
      add = thread_sums[lid - offset];
    }
    workgroupBarrier();
    thread_sums[lid] += add;
    workgroupBarrier();
  }
  var running = thread_sums[lid] - sum;
  for (var e = 0u; e < RADIX; e++) {
    let c = thread_digit_counts[lid * RADIX + e];
    thread_digit_counts[lid * RADIX + e] = running;
    running += c;
  }
  workgroupBarrier();
  for (var k = 0u; k < SORT_ITEMS; k++) {
    let d = digits[k];
    if (d < RADIX) {
      // Keys of digit d earlier in this thread keep their order.
      var before = 0u;
      for (var m = 0u; m < k; m++) {
        before += select(0u, 1u, digits[m] == d);
      }
      let in_block = thread_digit_counts[d * SORT_THREADS + lid] - thread_digit_counts[d * SORT_THREADS];
      let to = sort_counts[d * sort_params.block_count + wid.x] + in_block + before;
      keys_out[to] = keys[k];
      values_out[to] = values_in[base + k];
    }
  }
}
