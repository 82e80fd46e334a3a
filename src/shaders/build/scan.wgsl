// Exclusive prefix sums in place over scan_data[0 .. scan_length), in three dispatches: scan_reduce
// (one sum per block of SCAN_BLOCK entries), scan_block_sums (one workgroup scans those sums, a chunk
// at a time), scan_apply (each block scans itself and adds its block's offset). Plain workgroup
// memory and barriers: WebGPU guarantees no subgroup operations.
// Expects scan_length to be read from GPU memory (the PLOC loop's cluster count changes on the GPU).

#import build/scan-sizes

@group(0) @binding(0) var<storage, read_write> scan_data: array<u32>;
@group(0) @binding(1) var<storage, read_write> scan_block_sums: array<u32>;
@group(0) @binding(2) var<storage, read> scan_length: u32;

var<workgroup> scan_shared: array<u32, SCAN_THREADS>;
var<workgroup> scan_length_shared: u32;

// Exclusive scan of one value per thread across the workgroup (Hillis–Steele in shared memory);
// returns (exclusive prefix, workgroup total). Call from uniform control flow.
fn workgroup_exclusive_scan(lid: u32, value: u32) -> vec2u {
  scan_shared[lid] = value;
  workgroupBarrier();
  for (var offset = 1u; offset < SCAN_THREADS; offset <<= 1u) {
    var add = 0u;
    if (lid >= offset) {
      add = scan_shared[lid - offset];
    }
    workgroupBarrier();
    scan_shared[lid] += add;
    workgroupBarrier();
  }
  let inclusive = scan_shared[lid];
  let total = scan_shared[SCAN_THREADS - 1u];
  workgroupBarrier();
  return vec2u(inclusive - value, total);
}

fn load_scan_length() -> u32 {
  scan_length_shared = scan_length;
  return workgroupUniformLoad(&scan_length_shared);
}

@compute @workgroup_size(SCAN_THREADS)
fn scan_reduce(@builtin(local_invocation_index) lid: u32, @builtin(workgroup_id) wid: vec3u) {
  let n = load_scan_length();
  let base = wid.x * SCAN_BLOCK + lid * SCAN_ITEMS;
  var sum = 0u;
  for (var k = 0u; k < SCAN_ITEMS; k++) {
    if (base + k < n) {
      sum += scan_data[base + k];
    }
  }
  let scanned = workgroup_exclusive_scan(lid, sum);
  if (lid == 0u) {
    scan_block_sums[wid.x] = scanned.y;
  }
}

@compute @workgroup_size(SCAN_THREADS)
fn scan_block_sums_in_place(@builtin(local_invocation_index) lid: u32) {
  let blocks = (load_scan_length() + SCAN_BLOCK - 1u) / SCAN_BLOCK;
  var carry = 0u;
  for (var chunk = 0u; chunk < blocks; chunk += SCAN_BLOCK) {
    let base = chunk + lid * SCAN_ITEMS;
    var items: array<u32, SCAN_ITEMS>;
    var sum = 0u;
    for (var k = 0u; k < SCAN_ITEMS; k++) {
      items[k] = select(0u, scan_block_sums[base + k], base + k < blocks);
      sum += items[k];
    }
    let scanned = workgroup_exclusive_scan(lid, sum);
    var running = carry + scanned.x;
    for (var k = 0u; k < SCAN_ITEMS; k++) {
      if (base + k < blocks) {
        scan_block_sums[base + k] = running;
      }
      running += items[k];
    }
    carry += scanned.y;
  }
}

@compute @workgroup_size(SCAN_THREADS)
fn scan_apply(@builtin(local_invocation_index) lid: u32, @builtin(workgroup_id) wid: vec3u) {
  let n = load_scan_length();
  let base = wid.x * SCAN_BLOCK + lid * SCAN_ITEMS;
  var items: array<u32, SCAN_ITEMS>;
  var sum = 0u;
  for (var k = 0u; k < SCAN_ITEMS; k++) {
    items[k] = select(0u, scan_data[base + k], base + k < n);
    sum += items[k];
  }
  let scanned = workgroup_exclusive_scan(lid, sum);
  var running = scan_block_sums[wid.x] + scanned.x;
  for (var k = 0u; k < SCAN_ITEMS; k++) {
    if (base + k < n) {
      scan_data[base + k] = running;
    }
    running += items[k];
  }
}
