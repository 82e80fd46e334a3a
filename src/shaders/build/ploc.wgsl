// PLOC's clustering loop (Meister & Bittner 2018): clusters start as the triangles in Morton order;
// each iteration finds every cluster's nearest neighbour within SEARCH_RADIUS places on either side
// (the smallest box around both; ties broken by the pair's indices, so the globally closest pair is
// always mutual and every iteration merges), merges mutual pairs into new nodes, and compacts the
// survivors in order (flags scanned by build/scan, then ploc_compact). ploc_finalize counts what is
// left and writes the next iteration's indirect dispatch sizes, which become zero at TAIL_CLUSTERS or
// fewer, so the host may encode more iterations than needed; ploc_tail then does the remaining
// iterations in one workgroup. Each node also gets the SAH cost of the best
// tree below it when subtrees of at most MAX_LEAF_SIZE triangles may become leaves (`leaf` marks a
// node cheaper as one leaf), for build/emit.
// Expects build/morton's boxes and the radix-sorted triangle indices.
#import build/common
#import build/ploc-types

// Equal to TAIL_CLUSTERS: ploc_tail gives each cluster a thread.
const PLOC_THREADS: u32 = 256u;
override SEARCH_RADIUS: u32 = 16u;
override MAX_LEAF_SIZE: u32 = 8u;
override TRAVERSAL_COST: f32 = 1.0;
override INTERSECTION_COST: f32 = 1.0;

@group(0) @binding(0) var<uniform> ploc_params: PlocParams;
@group(0) @binding(1) var<storage, read_write> state: BuildState;
@group(0) @binding(2) var<storage, read_write> dispatch_args: array<u32>;
@group(0) @binding(3) var<storage, read_write> cluster_nodes: array<u32>;
@group(0) @binding(4) var<storage, read_write> clusters: array<Cluster>;
@group(0) @binding(5) var<storage, read_write> merged_nodes: array<u32>;
@group(0) @binding(6) var<storage, read_write> merged: array<Cluster>;
@group(0) @binding(7) var<storage, read_write> nearest: array<u32>;
@group(0) @binding(8) var<storage, read_write> nodes: array<PlocNode>;
// Survivor flags, then their exclusive scan: each survivor's place in the compacted list.
@group(0) @binding(9) var<storage, read_write> keep: array<u32>;
@group(0) @binding(10) var<storage, read> prim_boxes: array<Aabb>;
@group(0) @binding(11) var<storage, read> sorted_prims: array<u32>;
@group(0) @binding(12) var<storage, read_write> level_end: array<u32>;
// Per interior node: (output slot, first entry of triIndices), or NONE until build/emit places it.
@group(0) @binding(13) var<storage, read_write> node_places: array<vec2u>;

fn write_args(at: u32, groups: u32) {
  dispatch_args[at] = groups;
  dispatch_args[at + 1u] = 1u;
  dispatch_args[at + 2u] = 1u;
}

// The next iteration's sizes: the multi-dispatch loop runs above TAIL_CLUSTERS clusters (ploc_tail,
// dispatched after each batch, takes over from there).
fn write_loop_args(count: u32) {
  let busy = count > TAIL_CLUSTERS;
  write_args(ARGS_CLUSTERS, select(0u, (count + PLOC_THREADS - 1u) / PLOC_THREADS, busy));
  write_args(ARGS_SCAN_BLOCKS, select(0u, (count + SCAN_BLOCK - 1u) / SCAN_BLOCK, busy));
  write_args(ARGS_SINGLE, select(0u, 1u, busy));
}

@compute @workgroup_size(PLOC_THREADS)
fn ploc_init(@builtin(global_invocation_id) gid: vec3u) {
  let i = gid.x;
  let n = ploc_params.prim_count;
  if (i < n) {
    let t = sorted_prims[i];
    let box = prim_boxes[t];
    cluster_nodes[i] = t;
    clusters[i] = Cluster(box.lo, 1u, box.hi, INTERSECTION_COST * half_area(box.lo, box.hi));
  }
  if (i + 1u < n) {
    node_places[i] = vec2u(NONE, 0u);
  }
  if (i == 0u) {
    state.cluster_count = n;
    atomicStore(&state.node_count, 0u);
    state.iteration_count = 0u;
    atomicStore(&state.pair_count, 0u);
    write_loop_args(n);
  }
}

var<workgroup> window_lo: array<vec3f, PLOC_THREADS + 2u * 32u>;
var<workgroup> window_hi: array<vec3f, PLOC_THREADS + 2u * 32u>;
var<workgroup> count_shared: u32;

// Whether pair {i, j} at distance dj comes before pair {i, k} at dk: by distance, then by the
// smaller index and the larger, a total order on pairs.
fn pair_before(i: u32, j: u32, dj: f32, k: u32, dk: f32) -> bool {
  if (dj != dk) {
    return dj < dk;
  }
  let pj = vec2u(min(i, j), max(i, j));
  let pk = vec2u(min(i, k), max(i, k));
  return pj.x < pk.x || (pj.x == pk.x && pj.y < pk.y);
}

@compute @workgroup_size(PLOC_THREADS)
fn ploc_nearest(@builtin(local_invocation_index) lid: u32, @builtin(workgroup_id) wid: vec3u) {
  count_shared = state.cluster_count;
  let count = workgroupUniformLoad(&count_shared);
  let radius = min(SEARCH_RADIUS, 32u);
  // The workgroup's clusters and `radius` more on each side, loaded once.
  let first = i32(wid.x * PLOC_THREADS) - i32(radius);
  let window = PLOC_THREADS + 2u * radius;
  for (var w = lid; w < window; w += PLOC_THREADS) {
    let c = first + i32(w);
    if (c >= 0 && u32(c) < count) {
      let cl = clusters[c];
      window_lo[w] = cl.lo;
      window_hi[w] = cl.hi;
    }
  }
  workgroupBarrier();
  let i = wid.x * PLOC_THREADS + lid;
  if (i >= count) {
    return;
  }
  let me = lid + radius;
  let lo = window_lo[me];
  let hi = window_hi[me];
  var best = NONE;
  var best_distance = 0.0;
  let j_first = max(i, radius) - radius;
  let j_end = min(i + radius + 1u, count);
  for (var j = j_first; j < j_end; j++) {
    if (j == i) {
      continue;
    }
    let w = me + j - i;
    let d = half_area(min(lo, window_lo[w]), max(hi, window_hi[w]));
    if (best == NONE || pair_before(i, j, d, best, best_distance)) {
      best = j;
      best_distance = d;
    }
  }
  nearest[i] = best;
}

@compute @workgroup_size(PLOC_THREADS)
fn ploc_merge(@builtin(global_invocation_id) gid: vec3u) {
  let i = gid.x;
  if (i >= state.cluster_count) {
    return;
  }
  let j = nearest[i];
  if (nearest[j] != i) {
    merged_nodes[i] = cluster_nodes[i];
    merged[i] = clusters[i];
    keep[i] = 1u;
    return;
  }
  if (i > j) {
    merged_nodes[i] = NONE;
    keep[i] = 0u;
    return;
  }
  let a = clusters[i];
  let b = clusters[j];
  let lo = min(a.lo, b.lo);
  let hi = max(a.hi, b.hi);
  let count = a.count + b.count;
  let area = half_area(lo, hi);
  let split_cost = TRAVERSAL_COST * area + a.cost + b.cost;
  let leaf_cost = INTERSECTION_COST * f32(count) * area;
  let leaf = count <= MAX_LEAF_SIZE && leaf_cost <= split_cost;
  let cost = select(split_cost, leaf_cost, leaf);
  let k = atomicAdd(&state.node_count, 1u);
  nodes[k] = PlocNode(lo, count, hi, cost, cluster_nodes[i], cluster_nodes[j], select(0u, 1u, leaf));
  merged_nodes[i] = ploc_params.prim_count + k;
  merged[i] = Cluster(lo, count, hi, cost);
  keep[i] = 1u;
}

@compute @workgroup_size(PLOC_THREADS)
fn ploc_compact(@builtin(global_invocation_id) gid: vec3u) {
  let i = gid.x;
  if (i >= state.cluster_count) {
    return;
  }
  let node = merged_nodes[i];
  if (node != NONE) {
    let to = keep[i];
    cluster_nodes[to] = node;
    clusters[to] = merged[i];
  }
}

@compute @workgroup_size(1)
fn ploc_finalize() {
  let old = state.cluster_count;
  if (old <= TAIL_CLUSTERS) {
    // This iteration's kernels did not run (ploc_tail's turn, or done).
    return;
  }
  let last = old - 1u;
  let count = keep[last] + select(0u, 1u, merged_nodes[last] != NONE);
  level_end[state.iteration_count] = atomicLoad(&state.node_count);
  state.iteration_count += 1u;
  state.cluster_count = count;
  write_loop_args(count);
}

// The tail: the same iterations as above (nearest, mutual merges, in-order compaction), for at most
// TAIL_CLUSTERS clusters held in workgroup memory, until one is left. level_end and the node ids
// come out as the loop above would write them.
var<workgroup> tail_lo: array<vec3f, TAIL_CLUSTERS>;
var<workgroup> tail_hi: array<vec3f, TAIL_CLUSTERS>;
var<workgroup> tail_count: array<u32, TAIL_CLUSTERS>;
var<workgroup> tail_cost: array<f32, TAIL_CLUSTERS>;
var<workgroup> tail_node: array<u32, TAIL_CLUSTERS>;
var<workgroup> tail_nearest: array<u32, TAIL_CLUSTERS>;
var<workgroup> tail_scan: array<u32, TAIL_CLUSTERS>;
var<workgroup> tail_made: atomic<u32>;
var<workgroup> tail_clusters: u32;

@compute @workgroup_size(PLOC_THREADS)
fn ploc_tail(@builtin(local_invocation_index) lid: u32) {
  if (lid == 0u) {
    tail_clusters = state.cluster_count;
  }
  var count = workgroupUniformLoad(&tail_clusters);
  if (count <= 1u || count > TAIL_CLUSTERS) {
    // Done, or the batch before ended with too many clusters: the next batch continues.
    return;
  }
  if (lid < count) {
    let c = clusters[lid];
    tail_lo[lid] = c.lo;
    tail_hi[lid] = c.hi;
    tail_count[lid] = c.count;
    tail_cost[lid] = c.cost;
    tail_node[lid] = cluster_nodes[lid];
  }
  var iteration = state.iteration_count;
  var made = atomicLoad(&state.node_count);
  workgroupBarrier();
  let radius = min(SEARCH_RADIUS, 32u);
  while (count > 1u) {
    if (lid == 0u) {
      atomicStore(&tail_made, 0u);
    }
    if (lid < count) {
      var best = NONE;
      var best_distance = 0.0;
      let j_end = min(lid + radius + 1u, count);
      for (var j = max(lid, radius) - radius; j < j_end; j++) {
        if (j == lid) {
          continue;
        }
        let d = half_area(min(tail_lo[lid], tail_lo[j]), max(tail_hi[lid], tail_hi[j]));
        if (best == NONE || pair_before(lid, j, d, best, best_distance)) {
          best = j;
          best_distance = d;
        }
      }
      tail_nearest[lid] = best;
    }
    workgroupBarrier();
    var keep = 0u;
    var lo = vec3f(0.0);
    var hi = vec3f(0.0);
    var triangles = 0u;
    var cost = 0.0;
    var node = NONE;
    if (lid < count) {
      let j = tail_nearest[lid];
      lo = tail_lo[lid];
      hi = tail_hi[lid];
      triangles = tail_count[lid];
      cost = tail_cost[lid];
      node = tail_node[lid];
      if (tail_nearest[j] != lid) {
        keep = 1u;
      } else if (lid < j) {
        lo = min(lo, tail_lo[j]);
        hi = max(hi, tail_hi[j]);
        triangles += tail_count[j];
        let area = half_area(lo, hi);
        let split_cost = TRAVERSAL_COST * area + cost + tail_cost[j];
        let leaf_cost = INTERSECTION_COST * f32(triangles) * area;
        let leaf = triangles <= MAX_LEAF_SIZE && leaf_cost <= split_cost;
        cost = select(split_cost, leaf_cost, leaf);
        let k = made + atomicAdd(&tail_made, 1u);
        nodes[k] = PlocNode(lo, triangles, hi, cost, node, tail_node[j], select(0u, 1u, leaf));
        node = ploc_params.prim_count + k;
        keep = 1u;
      }
    }
    // Exclusive scan of `keep` (Hillis–Steele): each survivor's new place, in order.
    tail_scan[lid] = keep;
    workgroupBarrier();
    for (var offset = 1u; offset < PLOC_THREADS; offset <<= 1u) {
      var add = 0u;
      if (lid >= offset) {
        add = tail_scan[lid - offset];
      }
      workgroupBarrier();
      tail_scan[lid] += add;
      workgroupBarrier();
    }
    let to = tail_scan[lid] - keep;
    if (keep == 1u) {
      tail_lo[to] = lo;
      tail_hi[to] = hi;
      tail_count[to] = triangles;
      tail_cost[to] = cost;
      tail_node[to] = node;
    }
    made += atomicLoad(&tail_made);
    if (lid == 0u) {
      level_end[iteration] = made;
      tail_clusters = tail_scan[PLOC_THREADS - 1u];
    }
    iteration += 1u;
    count = workgroupUniformLoad(&tail_clusters);
  }
  if (lid == 0u) {
    cluster_nodes[0] = tail_node[0];
    clusters[0] = Cluster(tail_lo[0], tail_count[0], tail_hi[0], tail_cost[0]);
    state.cluster_count = count;
    state.iteration_count = iteration;
    atomicStore(&state.node_count, made);
    write_loop_args(count);
  }
}
