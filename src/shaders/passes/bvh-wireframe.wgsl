// The wireframe debug view: the 12 edges of every listed BVH box drawn as lines (a render pipeline,
// line-list, 24 vertices per box, one instance per box), interior boxes and leaves in different
// colours, without depth test, so boxes behind walls show too. The projection is the view's pinhole
// camera (the one camera_ray inverts), so a box corner lands on the pixel whose centre ray passes
// through it. Expects the scene (group 0) and view (group 1); its own inputs are group 2.

#import scene/bindings
#import view/bindings

// sRGB-encoded line colours.
const WIREFRAME_INTERIOR_COLOR: vec3f = vec3f(1.0, 0.72, 0.1);
const WIREFRAME_LEAF_COLOR: vec3f = vec3f(0.1, 0.9, 1.0);

struct WireframeParams {
  // Points nearer than this along the viewing direction (scene units) are clipped away.
  near: f32,
}

@group(2) @binding(0) var<uniform> params: WireframeParams;
// Indices into bvh_nodes of the boxes to draw (bvh/depths.ts nodesAtDepth).
@group(2) @binding(1) var<storage, read> wireframe_nodes: array<u32>;

struct WireframeVertex {
  @builtin(position) position: vec4f,
  @location(0) color: vec3f,
}

// Corner `corner` of a box: bit 0 picks max x, bit 1 max y, bit 2 max z.
fn box_corner(n: BvhNode, corner: u32) -> vec3f {
  return select(n.aabb_min, n.aabb_max, vec3<bool>((corner & 1u) != 0u, (corner & 2u) != 0u, (corner & 4u) != 0u));
}

@vertex
fn wireframe_vertex(@builtin(vertex_index) index: u32, @builtin(instance_index) instance: u32) -> WireframeVertex {
  let n = scene_bvh_node(wireframe_nodes[instance]);
  // Edge e runs along axis e / 4; its other two corner bits are the two bits of e % 4.
  let edge = index / 2u;
  let axis = edge / 4u;
  let k = edge % 4u;
  let low = k & ((1u << axis) - 1u);
  let high = (k >> axis) << (axis + 1u);
  let corner = low | high | select(0u, 1u << axis, (index & 1u) == 1u);
  let q = box_corner(n, corner) - view.camera.position;
  let c = view.camera;
  // camera_ray: direction ∝ forward + ndc.x·right − ndc.y·up, so ndc = (q·right/|right|², q·up/|up|²) / (q·forward).
  let depth = dot(q, c.forward);
  var out: WireframeVertex;
  out.position = vec4f(dot(q, c.right) / dot(c.right, c.right), dot(q, c.up) / dot(c.up, c.up), depth - params.near, depth);
  out.color = select(WIREFRAME_INTERIOR_COLOR, WIREFRAME_LEAF_COLOR, n.tri_count > 0u);
  return out;
}

@fragment
fn wireframe_fragment(in: WireframeVertex) -> @location(0) vec4f {
  return vec4f(in.color, 1.0);
}
