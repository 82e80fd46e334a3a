// Writes the clustered tree (build/ploc) out in the renderer's binary layout (scene/types BvhNode,
// bvh/types.ts): the root at slot 0, slot 1 an inverted box, sibling pairs from slot 2 at even slots,
// and triangle indices in leaf order. Top down, one dispatch per PLOC iteration from the last: a
// node's parent was made in a later iteration, so it is placed before its children. A placed
// interior node takes a pair of slots for its children (an atomic counter: pairs come out in no
// particular order) and hands each child its slot and its first entry of tri_indices; a child marked
// `leaf` (or a triangle) is written at once as one leaf of all the triangles below it.
// Expects build/ploc to have run to one cluster.
#import build/common
#import build/ploc-types
#import scene/types

const EMIT_THREADS: u32 = 64u;
// Deep enough to walk any subtree of up to 32 triangles (the host keeps MAX_LEAF_SIZE <= 32).
const LEAF_STACK: u32 = 32u;

@group(0) @binding(0) var<uniform> emit_params: PlocParams;
@group(0) @binding(1) var<storage, read_write> state: BuildState;
@group(0) @binding(2) var<storage, read_write> dispatch_args: array<u32>;
@group(0) @binding(3) var<storage, read> cluster_nodes: array<u32>;
@group(0) @binding(4) var<storage, read> nodes: array<PlocNode>;
@group(0) @binding(5) var<storage, read> prim_boxes: array<Aabb>;
@group(0) @binding(6) var<storage, read> level_end: array<u32>;
@group(0) @binding(7) var<storage, read_write> node_places: array<vec2u>;
@group(0) @binding(8) var<storage, read_write> bvh_out: array<BvhNode>;
@group(0) @binding(9) var<storage, read_write> tri_indices: array<u32>;

fn is_leaf(id: u32) -> bool {
  let n = emit_params.prim_count;
  return id < n || nodes[id - n].leaf != 0u;
}

fn triangle_count(id: u32) -> u32 {
  let n = emit_params.prim_count;
  return select(nodes[id - n].count, 1u, id < n);
}

// One leaf at `slot` holding every triangle below `id`, left to right, from tri_indices[first].
fn emit_leaf(id: u32, slot: u32, first: u32) {
  let n = emit_params.prim_count;
  var lo: vec3f;
  var hi: vec3f;
  if (id < n) {
    lo = prim_boxes[id].lo;
    hi = prim_boxes[id].hi;
  } else {
    lo = nodes[id - n].lo;
    hi = nodes[id - n].hi;
  }
  var stack: array<u32, LEAF_STACK>;
  var top = 1u;
  stack[0] = id;
  var written = 0u;
  while (top > 0u) {
    top -= 1u;
    let x = stack[top];
    if (x < n) {
      tri_indices[first + written] = x;
      written += 1u;
    } else if (top + 2u <= LEAF_STACK) {
      stack[top] = nodes[x - n].right;
      stack[top + 1u] = nodes[x - n].left;
      top += 2u;
    }
  }
  bvh_out[slot] = BvhNode(lo, first, hi, written);
}

fn place_child(id: u32, slot: u32, first: u32) {
  if (is_leaf(id)) {
    emit_leaf(id, slot, first);
  } else {
    node_places[id - emit_params.prim_count] = vec2u(slot, first);
  }
}

@compute @workgroup_size(1)
fn emit_root() {
  // Slot 1: an inverted but finite box that no ray hits.
  let big = 3.4028234663852886e38;
  bvh_out[1] = BvhNode(vec3f(big), 0u, vec3f(-big), 0u);
  let root = cluster_nodes[0];
  if (is_leaf(root)) {
    emit_leaf(root, 0u, 0u);
  } else {
    node_places[root - emit_params.prim_count] = vec2u(0u, 0u);
  }
  state.emit_level = state.iteration_count;
}

// Moves to the next iteration down and sizes emit_level's dispatch to its nodes.
@compute @workgroup_size(1)
fn emit_step() {
  var groups = 0u;
  if (state.emit_level > 0u) {
    state.emit_level -= 1u;
    let level = state.emit_level;
    state.emit_start = select(0u, level_end[level - 1u], level > 0u);
    state.emit_end = level_end[level];
    groups = (state.emit_end - state.emit_start + EMIT_THREADS - 1u) / EMIT_THREADS;
  }
  dispatch_args[ARGS_EMIT] = groups;
  dispatch_args[ARGS_EMIT + 1u] = 1u;
  dispatch_args[ARGS_EMIT + 2u] = 1u;
}

@compute @workgroup_size(EMIT_THREADS)
fn emit_level(@builtin(global_invocation_id) gid: vec3u) {
  let k = state.emit_start + gid.x;
  if (k >= state.emit_end) {
    return;
  }
  let place = node_places[k];
  if (place.x == NONE) {
    // Inside a subtree written as one leaf.
    return;
  }
  let node = nodes[k];
  let pair = 2u + 2u * atomicAdd(&state.pair_count, 1u);
  bvh_out[place.x] = BvhNode(node.lo, pair, node.hi, 0u);
  place_child(node.left, pair, place.y);
  place_child(node.right, pair + 1u, place.y + triangle_count(node.left));
}
