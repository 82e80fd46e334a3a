// The static world traced through its uniform grid: the 3D-DDA of Amanatides & Woo ("A Fast Voxel
// Traversal Algorithm for Ray Tracing", 1987), closest and any hit, with its mailbox. The CPU oracle is bvh/grid.ts
// (traceGrid, traceGridAny), step for step. Expects the scene bindings (group 0): the grid lives in
// bvh_nodes from record scene_info.grid_base (gpu/pack/scene-pack.ts packGrid: a two-record header,
// cell ranges two words a cell, items one word each: leaf positions of the static world, so a hit is
// the record the static BVH would give).

#import scene/hit-filter
#import scene/bindings
#import scene/intersect
#import scene/accel

struct GridHeader {
  lo: vec3f,
  hi: vec3f,
  cell_size: vec3f,
  dims: vec3u,
  // Word indices (from record 0 of bvh_nodes) of the first cell range and of the first item.
  cells_word: u32,
  items_word: u32,
}

fn grid_header() -> GridHeader {
  let a = scene_bvh_node(scene_info.grid_base);
  let b = scene_bvh_node(scene_info.grid_base + 1u);
  return GridHeader(a.aabb_min, a.aabb_max, b.aabb_min, vec3u(a.left_first, a.tri_count, b.left_first), bitcast<u32>(b.aabb_max.x), bitcast<u32>(b.aabb_max.y));
}

// The four words of bvh_nodes that hold word `w` (w & 3 picks one).
fn grid_quad(w: u32) -> vec4u {
  let n = scene_bvh_node(w >> 3u);
  return select(vec4u(bitcast<vec3u>(n.aabb_min), n.left_first), vec4u(bitcast<vec3u>(n.aabb_max), n.tri_count), (w & 4u) != 0u);
}

// The range of items of the cell at `cell`: (first item, count).
fn grid_cell(h: GridHeader, cell: vec3i) -> vec2u {
  let c = vec3u(cell);
  let w = h.cells_word + 2u * (c.x + h.dims.x * (c.y + h.dims.y * c.z));
  let q = grid_quad(w);
  return select(q.xy, q.zw, (w & 2u) != 0u);
}

fn grid_item(h: GridHeader, i: u32) -> u32 {
  let w = h.items_word + i;
  return grid_quad(w)[w & 3u];
}

// The state of a walk: the cell (as signed coordinates), the step on each axis and the t of the next
// cell boundary on each axis.
struct GridWalk {
  cell: vec3i,
  step: vec3i,
  next: vec3f,
  // Cells visited (the heat map's count).
  visited: u32,
}

fn boundary_t(h: GridHeader, cell: vec3i, step: vec3i, origin: vec3f, inv_dir: vec3f) -> vec3f {
  let up = select(vec3f(0.0), vec3f(1.0), step > vec3i(0));
  return (h.lo + (vec3f(cell) + up) * h.cell_size - origin) * inv_dir;
}

// Where the walk starts: the ray clipped to the grid box over (t_min, t_best); visited = 0xffffffff
// (GRID_MISSED) when it misses the box there.
const GRID_MISSED: u32 = 0xffffffffu;

fn grid_start(h: GridHeader, origin: vec3f, direction: vec3f, inv_dir: vec3f, t_min: f32, t_best: f32) -> GridWalk {
  let a = (h.lo - origin) * inv_dir;
  let b = (h.hi - origin) * inv_dir;
  let lo_t = min(a, b);
  let hi_t = max(a, b);
  let t_near = max(t_min, max(lo_t.x, max(lo_t.y, lo_t.z)));
  let t_far = min(t_best, min(hi_t.x, min(hi_t.y, hi_t.z)));
  var walk: GridWalk;
  if (!(t_near <= t_far)) {
    walk.visited = GRID_MISSED;
    return walk;
  }
  let p = origin + t_near * direction;
  let dims = vec3i(h.dims);
  walk.cell = clamp(vec3i(floor((p - h.lo) / h.cell_size)), vec3i(0), dims - vec3i(1));
  walk.step = select(vec3i(-1), vec3i(1), inv_dir >= vec3f(0.0));
  walk.next = boundary_t(h, walk.cell, walk.step, origin, inv_dir);
  walk.visited = 0u;
  return walk;
}

// The axis whose next boundary is nearest (ties: x, then y, then z), as bvh/grid.ts walk picks it.
fn grid_axis(next: vec3f) -> u32 {
  if (next.x <= next.y) {
    return select(2u, 0u, next.x <= next.z);
  }
  return select(2u, 1u, next.y <= next.z);
}

// One step along `axis`; false when it leaves the grid.
fn grid_step(h: GridHeader, walk: ptr<function, GridWalk>, axis: u32, origin: vec3f, inv_dir: vec3f) -> bool {
  (*walk).cell[axis] += (*walk).step[axis];
  let c = (*walk).cell[axis];
  if (c < 0 || c >= i32(h.dims[axis])) {
    return false;
  }
  (*walk).next[axis] = boundary_t(h, (*walk).cell, (*walk).step, origin, inv_dir)[axis];
  return true;
}

// The mailbox of Amanatides & Woo: the last eight leaves tested (bvh/grid.ts GRID_MAILBOX_SIZE), so
// a primitive spanning several cells is tested once per ray. Two vectors shifted on insertion (no
// dynamically indexed array: it stays in registers). Skipping a repeat changes no result.
struct Mailbox {
  newer: vec4u,
  older: vec4u,
}

fn empty_mailbox() -> Mailbox {
  return Mailbox(vec4u(NO_TRIANGLE), vec4u(NO_TRIANGLE));
}

// Whether `leaf` was tested already on this walk; if not, remembers it.
fn mailbox_seen(box: ptr<function, Mailbox>, leaf: u32) -> bool {
  let l = vec4u(leaf);
  if (any((*box).newer == l) || any((*box).older == l)) {
    return true;
  }
  (*box).older = vec4u((*box).newer.w, (*box).older.xyz);
  (*box).newer = vec4u(leaf, (*box).newer.xyz);
  return false;
}

// The closest hit of the static world before (*hit).t, written to `hit` (instance 0). Returns the
// cells visited and the primitives tested (the heat map's counts).
fn grid_closest(origin: vec3f, direction: vec3f, inv_dir: vec3f, t_min: f32, hit: ptr<function, Hit>) -> vec2u {
  let h = grid_header();
  var walk = grid_start(h, origin, direction, inv_dir, t_min, (*hit).t);
  if (walk.visited == GRID_MISSED) {
    return vec2u(0u);
  }
  var tested = 0u;
  var seen = empty_mailbox();
  loop {
    walk.visited += 1u;
    let axis = grid_axis(walk.next);
    let t_exit = walk.next[axis];
    let range = grid_cell(h, walk.cell);
    for (var i = range.x; i < range.x + range.y; i++) {
      let leaf = grid_item(h, i);
      if (mailbox_seen(&seen, leaf)) {
        continue;
      }
      let tri = scene_triangle_hot(leaf);
      let r = intersect_primitive(origin, direction, tri, t_min, (*hit).t);
      tested += 1u;
      if (r.x < (*hit).t && accept_hit(tri, leaf, r.yz)) {
        *hit = Hit(r.x, leaf, r.y, r.z, 0u);
      }
    }
    if ((*hit).t <= t_exit || !grid_step(h, &walk, axis, origin, inv_dir)) {
      break;
    }
  }
  return vec2u(walk.visited, tested);
}

// Whether the static world has anything strictly between t_min and t_max along the ray.
fn grid_any(origin: vec3f, direction: vec3f, inv_dir: vec3f, t_min: f32, t_max: f32) -> bool {
  let h = grid_header();
  var walk = grid_start(h, origin, direction, inv_dir, t_min, t_max);
  if (walk.visited == GRID_MISSED) {
    return false;
  }
  var seen = empty_mailbox();
  loop {
    let axis = grid_axis(walk.next);
    let t_exit = walk.next[axis];
    let range = grid_cell(h, walk.cell);
    for (var i = range.x; i < range.x + range.y; i++) {
      let leaf = grid_item(h, i);
      if (mailbox_seen(&seen, leaf)) {
        continue;
      }
      let tri = scene_triangle_hot(leaf);
      let r = intersect_primitive(origin, direction, tri, t_min, t_max);
      if (r.x < t_max && accept_hit(tri, leaf, r.yz)) {
        return true;
      }
    }
    if (t_max <= t_exit || !grid_step(h, &walk, axis, origin, inv_dir)) {
      break;
    }
  }
  // After the loop, not inside it: naga (the fragment tracer's GLSL translation) wants a return at
  // the end of a function that returns a value.
  return false;
}
