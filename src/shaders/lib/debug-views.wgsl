// The closed sets of debug views and layouts, shared by passes/debug-view (which traces) and
// passes/debug-compose (which colours and composes). The host's names live in renderer/settings.ts
// (DEBUG_VIEWS, DEBUG_LAYOUTS) in the same order; a unit test keeps the two in step. Expects nothing.

const DEBUG_VIEW_NONE: u32 = 0u;
const DEBUG_VIEW_HEAT_NODES: u32 = 1u;
const DEBUG_VIEW_HEAT_TRIANGLES: u32 = 2u;
const DEBUG_VIEW_WIREFRAME: u32 = 3u;
const DEBUG_VIEW_LEAF_SIZE: u32 = 4u;
const DEBUG_VIEW_BVH_DEPTH: u32 = 5u;
const DEBUG_VIEW_NORMALS: u32 = 6u;
const DEBUG_VIEW_ALBEDO: u32 = 7u;
const DEBUG_VIEW_BARYCENTRICS: u32 = 8u;
const DEBUG_VIEW_TRIANGLE_ID: u32 = 9u;

const DEBUG_LAYOUT_REPLACE: u32 = 0u;
const DEBUG_LAYOUT_SIDE_BY_SIDE: u32 = 1u;
const DEBUG_LAYOUT_OVERLAY: u32 = 2u;

// The scalar views (coloured through the colour scale; their maximum is tracked in debug_range).
fn is_scalar_debug_view(kind: u32) -> bool {
  return kind == DEBUG_VIEW_HEAT_NODES || kind == DEBUG_VIEW_HEAT_TRIANGLES || kind == DEBUG_VIEW_LEAF_SIZE || kind == DEBUG_VIEW_BVH_DEPTH;
}
