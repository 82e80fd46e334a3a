// The block sizes of build/scan, for the kernels that size its indirect dispatches (build/ploc).
// Expects nothing.

const SCAN_THREADS: u32 = 256u;
const SCAN_ITEMS: u32 = 4u;
// Entries per workgroup of scan_reduce and scan_apply.
const SCAN_BLOCK: u32 = 1024u; // SCAN_THREADS × SCAN_ITEMS (literal: wgsl_reflect cannot evaluate the product)
