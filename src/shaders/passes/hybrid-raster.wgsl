// The hybrid recipe's raster first hit: a render pipeline draws every primitive of the scene (the
// static world's, then each moving instance's through its transform) into the visibility buffer
// (hybrid/visibility) with a depth buffer. Vertices are pulled from the same primitive records the
// ray tracer reads, so there is one copy of the geometry. Triangles are drawn as themselves; spheres
// and capsules as their bounding boxes, whose fragments intersect the ray with the primitive and
// write its depth. Opaque triangles are drawn first (early depth test), then the alpha-masked ones,
// which run the ray tracer's alpha test (scene/hit-filter) per fragment. The projection follows view/bindings' camera_ray exactly, shifted by this frame's
// subpixel jitter, with a reversed, infinite depth range (depth = near / linear depth: precise at
// every distance, whatever the scene's units).
// Expects the scene (group 0) and the view (group 1); group 2 holds the raster parameters.

#import scene/hit-filter
#import hybrid/visibility

struct RasterParams {
  // This frame's subpixel offset in pixels (Halton (2, 3) − 0.5): every pixel samples its centre + jitter.
  jitter: vec2f,
  // Linear depth (scene units) of the near plane.
  near: f32,
}

@group(2) @binding(0) var<uniform> raster: RasterParams;

struct RasterVertex {
  @builtin(position) clip: vec4f,
  // (instance, primitive): what the fragment stores.
  @location(0) @interpolate(flat) id: vec2u,
}

// A vertex that the rasteriser drops (outside the depth range): primitives of the other draw.
const DROPPED_VERTEX: vec4f = vec4f(0.0, 0.0, 2.0, 1.0);

// Clip-space position of a world point: image coordinates as project_offset gives them, moved by
// −jitter so that pixel centres sample the jittered points, and z = near (z/w = near / depth).
fn clip_position(p: vec3f) -> vec4f {
  let c = view.camera;
  let o = p - c.position;
  let depth = dot(o, c.forward);
  let x = dot(o, c.right) / dot(c.right, c.right);
  let y = dot(o, c.up) / dot(c.up, c.up);
  let shift = 2.0 * raster.jitter / vec2f(view.image_size);
  return vec4f(x - shift.x * depth, y + shift.y * depth, raster.near, depth);
}

fn world_position(instance: u32, p: vec3f) -> vec3f {
  if (instance_is_static(instance)) {
    return p;
  }
  return world_point(instance_record(instance), p);
}

// The camera ray of the pixel whose centre is at framebuffer position `fragment` (pixels).
fn fragment_ray(fragment: vec2f) -> Ray {
  return camera_ray(fragment + raster.jitter);
}

// Whether a primitive drawn through `instance` runs the alpha test (its own mask, or its instance's material's).
fn raster_masked(tri: TriangleHot, instance: u32) -> bool {
  if (!SCENE_HAS_ALPHA_MASKS) {
    return false;
  }
  if ((tri.flags & TRIANGLE_ALPHA_MASKED) != 0u) {
    return true;
  }
  return !instance_is_static(instance) && (instance_record(instance).flags & INSTANCE_ALPHA_FILTER) != 0u;
}

// A triangle's corner, or DROPPED_VERTEX when the triangle belongs to the other draw (analytic, or
// masked when opaque ones are drawn and the reverse).
fn triangle_vertex(vertex: u32, instance: u32, masked: bool) -> RasterVertex {
  let primitive = vertex / 3u;
  let corner = vertex % 3u;
  let tri = scene_triangle_hot(primitive);
  var out: RasterVertex;
  out.id = vec2u(instance, primitive);
  if ((tri.flags & PRIMITIVE_ANALYTIC) != 0u || raster_masked(tri, instance) != masked) {
    out.clip = DROPPED_VERTEX;
    return out;
  }
  var p = tri.v0;
  if (corner == 1u) {
    p += tri.e1;
  } else if (corner == 2u) {
    p += tri.e2;
  }
  out.clip = clip_position(world_position(instance, p));
  return out;
}

// Opaque triangles first: their fragment shader never discards, so the depth test runs before it
// (early-Z) and hidden surfaces cost nothing.
@vertex
fn raster_triangle(@builtin(vertex_index) vertex: u32, @builtin(instance_index) instance: u32) -> RasterVertex {
  return triangle_vertex(vertex, instance, false);
}

@fragment
fn raster_fragment(v: RasterVertex) -> @location(0) vec2u {
  return v.id;
}

// Then the alpha-masked ones (Doom's sprites and masked middle textures), tested per fragment.
@vertex
fn raster_masked_triangle(@builtin(vertex_index) vertex: u32, @builtin(instance_index) instance: u32) -> RasterVertex {
  return triangle_vertex(vertex, instance, true);
}

@fragment
fn raster_masked_fragment(v: RasterVertex) -> @location(0) vec2u {
  let ray = fragment_ray(v.clip.xy);
  set_alpha_salt(ray);
  set_filter_instance(v.id.x);
  let tri = scene_triangle_hot(v.id.y);
  let h = triangle_plane_hit(local_ray(ray, v.id.x), tri);
  if (!accept_hit(tri, v.id.y, h.yz)) {
    discard;
  }
  return v.id;
}

// The 36 corners (12 triangles) of a box, as bit masks: bit 0 = max x, bit 1 = max y, bit 2 = max z.
const BOX_CORNERS = array<u32, 36>(
  0u, 1u, 3u, 0u, 3u, 2u, 4u, 6u, 7u, 4u, 7u, 5u,
  0u, 4u, 5u, 0u, 5u, 1u, 2u, 3u, 7u, 2u, 7u, 6u,
  0u, 2u, 6u, 0u, 6u, 4u, 1u, 5u, 7u, 1u, 7u, 3u,
);

// Object-space bounds of a sphere (centre v0, radius e1.x) or capsule (axis v0 → v0 + e1, radius e2.x).
fn analytic_bounds(tri: TriangleHot) -> array<vec3f, 2> {
  if ((tri.flags & PRIMITIVE_SPHERE) != 0u) {
    let r = vec3f(tri.e1.x);
    return array<vec3f, 2>(tri.v0 - r, tri.v0 + r);
  }
  let r = vec3f(tri.e2.x);
  let a = tri.v0;
  let b = tri.v0 + tri.e1;
  return array<vec3f, 2>(min(a, b) - r, max(a, b) + r);
}

@vertex
fn raster_analytic(@builtin(vertex_index) vertex: u32, @builtin(instance_index) instance: u32) -> RasterVertex {
  let primitive = vertex / 36u;
  let tri = scene_triangle_hot(primitive);
  var out: RasterVertex;
  out.id = vec2u(instance, primitive);
  if ((tri.flags & PRIMITIVE_ANALYTIC) == 0u) {
    out.clip = DROPPED_VERTEX;
    return out;
  }
  let bounds = analytic_bounds(tri);
  let corner = BOX_CORNERS[vertex % 36u];
  let p = select(bounds[0], bounds[1], vec3<bool>((corner & 1u) != 0u, (corner & 2u) != 0u, (corner & 4u) != 0u));
  out.clip = clip_position(world_position(instance, p));
  return out;
}

struct AnalyticFragment {
  @location(0) id: vec2u,
  @builtin(frag_depth) depth: f32,
}

@fragment
fn raster_analytic_fragment(v: RasterVertex) -> AnalyticFragment {
  let ray = fragment_ray(v.clip.xy);
  let hit = visible_hit(ray, v.id);
  if (hit.triangle == NO_TRIANGLE) {
    discard;
  }
  let depth = hit.t * dot(ray.direction, view.camera.forward);
  if (depth < raster.near) {
    discard;
  }
  return AnalyticFragment(v.id, raster.near / depth);
}
