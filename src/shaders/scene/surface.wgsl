// The surface at a closest hit: position, normals, area, material. Expects the scene bindings (group 0).

#import scene/bindings
#import scene/materials

struct Surface {
  position: vec3f,
  // Unit geometric normal e1 × e2: the emitting side of the triangle.
  geometric_normal: vec3f,
  // Unit interpolated shading normal, on the same side as geometric_normal.
  shading_normal: vec3f,
  // Triangle area in squared scene units.
  area: f32,
  material: u32,
  uv: vec2f,
}

fn surface_at(hit: Hit) -> Surface {
  let tri = triangles_hot[hit.triangle];
  let shading = triangles_shading[hit.triangle];
  let w = 1.0 - hit.u - hit.v;
  let position = tri.v0 + hit.u * tri.e1 + hit.v * tri.e2;
  let cross_e = cross(tri.e1, tri.e2);
  let twice_area = length(cross_e);
  let ng = cross_e / max(twice_area, 1e-30);
  var ns = w * shading.n0 + hit.u * shading.n1 + hit.v * shading.n2;
  let ns_length = length(ns);
  ns = select(ng, ns / ns_length, ns_length > 1e-12);
  ns = select(-ns, ns, dot(ns, ng) >= 0.0);
  return Surface(position, ng, ns, 0.5 * twice_area, shading.material, triangle_uv(hit.triangle, vec2f(hit.u, hit.v)));
}
