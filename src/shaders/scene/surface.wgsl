// The surface at a closest hit: position, normals, area, material, for triangles and for the
// analytic spheres and capsules. Expects the scene bindings (group 0).

#import lib/constants
#import lib/ray-offset
#import scene/bindings
#import scene/intersect
#import scene/materials
#import scene/instances

struct Surface {
  position: vec3f,
  // Unit geometric normal: e1 × e2 for a triangle (its emitting side), outward for a sphere or capsule.
  geometric_normal: vec3f,
  // Unit interpolated shading normal, on the same side as geometric_normal.
  shading_normal: vec3f,
  // Area of the whole primitive in squared scene units (a triangle, the whole sphere or capsule).
  area: f32,
  material: u32,
  uv: vec2f,
  // The primitive's PRIMITIVE_* bits (0 for a triangle).
  kind: u32,
  // Extra distance a ray leaving an analytic primitive starts off its surface (see spawn_point).
  spawn_offset: f32,
}

// Where ray tracing loses precision on an analytic primitive: its test forms f = origin − centre, so
// f carries a rounding error of about ulp(|centre| + r). A ray leaving the surface must start a few of
// those away, or the test may find the surface it leaves (the ground sphere of radius 1000 under a
// camera at distance 10 shows that acne). 4 ulps of float32 (2^-23 each).
const ANALYTIC_SPAWN_ULPS: f32 = 4.0 / 8388608.0;

// Texture coordinates at barycentrics (u, v) of v1 and v2 of a shading record.
fn shading_uv(s: TriangleShading, bary: vec2f) -> vec2f {
  return (1.0 - bary.x - bary.y) * s.uv0 + bary.x * s.uv1 + bary.y * s.uv2;
}

fn surface_at(hit: Hit, ray: Ray) -> Surface {
  let tri = world_primitive(hit.instance, hit.triangle);
  let shading = world_shading(hit.instance, hit.triangle);
  if (SCENE_HAS_ANALYTIC_PRIMITIVES && (tri.flags & PRIMITIVE_ANALYTIC) != 0u) {
    return analytic_surface(hit, ray, tri, shading.material);
  }
  let w = 1.0 - hit.u - hit.v;
  let position = tri.v0 + hit.u * tri.e1 + hit.v * tri.e2;
  let cross_e = cross(tri.e1, tri.e2);
  let twice_area = length(cross_e);
  let ng = cross_e / max(twice_area, 1e-30);
  var ns = w * shading.n0 + hit.u * shading.n1 + hit.v * shading.n2;
  let ns_length = length(ns);
  ns = select(ng, ns / ns_length, ns_length > 1e-12);
  ns = select(-ns, ns, dot(ns, ng) >= 0.0);
  return Surface(position, ng, ns, 0.5 * twice_area, shading.material, shading_uv(shading, vec2f(hit.u, hit.v)), 0u, 0.0);
}

// A sphere or capsule: the point along the ray (as precise as the root), its outward normal from the
// centre or from the nearest point of the axis, and the uv the test computed.
fn analytic_surface(hit: Hit, ray: Ray, prim: TriangleHot, material: u32) -> Surface {
  let position = ray.origin + hit.t * ray.direction;
  var n: vec3f;
  var area: f32;
  var extent: f32;
  if ((prim.flags & PRIMITIVE_SPHERE) != 0u) {
    let r = prim.e1.x;
    n = normalize(position - prim.v0);
    area = 4.0 * PI * r * r;
    extent = max_abs(prim.v0) + r;
  } else {
    let r = prim.e2.x;
    let axis2 = dot(prim.e1, prim.e1);
    let y = select(0.0, clamp(dot(position - prim.v0, prim.e1) / axis2, 0.0, 1.0), axis2 > 0.0);
    n = normalize(position - (prim.v0 + y * prim.e1));
    area = 2.0 * PI * r * sqrt(axis2) + 4.0 * PI * r * r;
    extent = max(max_abs(prim.v0), max_abs(prim.v0 + prim.e1)) + r;
  }
  return Surface(position, n, n, area, material, vec2f(hit.u, hit.v), prim.flags & PRIMITIVE_ANALYTIC, extent * ANALYTIC_SPAWN_ULPS);
}

fn max_abs(v: vec3f) -> f32 {
  let a = abs(v);
  return max(a.x, max(a.y, a.z));
}

// The origin of a ray leaving `surface` to the side of the unit normal n: offset_ray_origin (a few
// ulps of the position, for triangles), plus for a sphere or capsule the distance its own test needs.
fn spawn_point(surface: Surface, n: vec3f) -> vec3f {
  return offset_ray_origin(surface.position, n) + n * surface.spawn_offset;
}

// The shading normal perturbed by the material's tangent-space normal map (glTF normalTexture:
// n = normalize((2·rgb − 1) · (scale, scale, 1)) in the frame (t, b, n)). The tangent is the mesh's
// per-vertex tangent (glTF TANGENT, or MikkTSpace's when the file has none) interpolated, made
// orthogonal to the shading normal, with b = w · n × t. A mesh without tangents falls back to the
// triangle's dp/du, with the bitangent toward decreasing v as glTF's "+Y up in the image" requires.
// Spheres and capsules keep their analytic normal (normal maps on them are ignored).
fn normal_mapped(surface: Surface, hit: Hit, material: Material) -> vec3f {
  if (material.normal_texture == NO_TEXTURE || surface.kind != 0u) {
    return surface.shading_normal;
  }
  let triangle = hit.triangle;
  let n = surface.shading_normal;
  // Tangents are stored like the positions (object space for a moving instance): to world space.
  let t0 = instance_tangent(hit.instance, triangle_attribute(triangle, stored_vertex(hit.instance, triangle, 0u)));
  let t1 = instance_tangent(hit.instance, triangle_attribute(triangle, stored_vertex(hit.instance, triangle, 1u)));
  let t2 = instance_tangent(hit.instance, triangle_attribute(triangle, stored_vertex(hit.instance, triangle, 2u)));
  var t_raw = (1.0 - hit.u - hit.v) * t0.xyz + hit.u * t1.xyz + hit.v * t2.xyz;
  var sign = select(1.0, -1.0, t0.w < 0.0);
  if (t0.w == 0.0) {
    // No tangents: the triangle's uv parameterisation.
    let tri = world_primitive(hit.instance, triangle);
    let s = world_shading(hit.instance, triangle);
    let duv1 = s.uv1 - s.uv0;
    let duv2 = s.uv2 - s.uv0;
    let det = duv1.x * duv2.y - duv1.y * duv2.x;
    if (abs(det) < 1e-20) {
      return n;
    }
    let dpdu = (tri.e1 * duv2.y - tri.e2 * duv1.y) / det;
    let dpdv = (tri.e2 * duv1.x - tri.e1 * duv2.x) / det;
    t_raw = dpdu;
    sign = select(1.0, -1.0, dot(cross(n, dpdu), dpdv) > 0.0);
  }
  t_raw -= n * dot(n, t_raw);
  if (dot(t_raw, t_raw) < 1e-30) {
    return n;
  }
  let t = normalize(t_raw);
  let b = cross(n, t) * sign;
  let texel = texture_texel(material.normal_texture, surface.uv).rgb * 2.0 - 1.0;
  let local = vec3f(texel.xy * material.normal_scale, texel.z);
  let mapped = t * local.x + b * local.y + n * local.z;
  let len = length(mapped);
  return select(n, mapped / len, len > 1e-12);
}

// A stored tangent (xyz, w = bitangent sign) of `instance` in world space: the direction transformed,
// the handedness flipped by a mirror.
fn instance_tangent(instance: u32, t: vec4f) -> vec4f {
  if (instance_is_static(instance) || t.w == 0.0) {
    return t;
  }
  let inst = instance_record(instance);
  let w = select(t.w, -t.w, (inst.flags & INSTANCE_MIRRORED) != 0u);
  return vec4f(world_vector(inst, t.xyz), w);
}

// log2 of the footprint, in uv units, of a ray cone of width `cone_width` (scene units) arriving along
// `direction`: the cone's width widened by 1/|cos| on the surface, times the triangle's uv per world
// length, sqrt(uv area / world area). scene/materials.wgsl adds log2 of the texture's size to pick
// the mip level (Akenine-Möller et al. 2021, "Improved Shader and Texture Level of Detail Using Ray
// Cones", JCGT 10(1), §3).
// Spheres and capsules cover the unit uv square once, so their uv area is 1.
fn texture_lod_at(surface: Surface, triangle: u32, cone_width: f32, direction: vec3f) -> f32 {
  let s = scene_triangle_shading(triangle);
  let duv1 = s.uv1 - s.uv0;
  let duv2 = s.uv2 - s.uv0;
  let uv_area = select(0.5 * abs(duv1.x * duv2.y - duv1.y * duv2.x), 1.0, surface.kind != 0u);
  let cos_theta = max(abs(dot(surface.geometric_normal, direction)), 1e-4);
  return log2(max(cone_width, 1e-30) / cos_theta) + 0.5 * log2(max(uv_area, 1e-30) / max(surface.area, 1e-30));
}
