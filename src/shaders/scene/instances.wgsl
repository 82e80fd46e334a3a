// The instances of the two-level BVH (Instance in scene/types): their transforms, and the primitive
// records of a hit in world space whichever level they are stored at (the static world's in world
// space, a moving instance's in object space). Without moving instances (SCENE_HAS_INSTANCES false)
// everything here is the identity and folds away. Expects the scene bindings (group 0).

#import scene/bindings

// Whether the scene has moving instances (a top-level tree over instances). A pipeline constant
// (gpu/kernel.ts, from the packed scene's features): a frozen scene compiles the single-level code.
override SCENE_HAS_INSTANCES: bool = false;

// Texel k of instance g's record.
fn instance_texel(g: u32, k: u32) -> vec4u {
  return textureLoad(instance_data, vec2u((g % INSTANCES_PER_ROW) * INSTANCE_TEXELS + k, g / INSTANCES_PER_ROW), 0);
}

// Instance g's record (scene/types Instance), from instance_data.
fn instance_record(g: u32) -> Instance {
  let last = instance_texel(g, 9u);
  return Instance(
    bitcast<vec4f>(instance_texel(g, 0u)), bitcast<vec4f>(instance_texel(g, 1u)), bitcast<vec4f>(instance_texel(g, 2u)),
    bitcast<vec4f>(instance_texel(g, 3u)), bitcast<vec4f>(instance_texel(g, 4u)), bitcast<vec4f>(instance_texel(g, 5u)),
    bitcast<vec4f>(instance_texel(g, 6u)), bitcast<vec4f>(instance_texel(g, 7u)), bitcast<vec4f>(instance_texel(g, 8u)),
    last.x, last.y, last.z, last.w,
  );
}

fn instance_is_static(instance: u32) -> bool {
  return !SCENE_HAS_INSTANCES || instance == 0u;
}

fn rows_point(r0: vec4f, r1: vec4f, r2: vec4f, p: vec3f) -> vec3f {
  return vec3f(dot(r0.xyz, p) + r0.w, dot(r1.xyz, p) + r1.w, dot(r2.xyz, p) + r2.w);
}

fn rows_vector(r0: vec4f, r1: vec4f, r2: vec4f, v: vec3f) -> vec3f {
  return vec3f(dot(r0.xyz, v), dot(r1.xyz, v), dot(r2.xyz, v));
}

fn world_point(inst: Instance, p: vec3f) -> vec3f {
  return rows_point(inst.world_from_object_0, inst.world_from_object_1, inst.world_from_object_2, p);
}

fn world_vector(inst: Instance, v: vec3f) -> vec3f {
  return rows_vector(inst.world_from_object_0, inst.world_from_object_1, inst.world_from_object_2, v);
}

fn object_point(inst: Instance, p: vec3f) -> vec3f {
  return rows_point(inst.object_from_world_0, inst.object_from_world_1, inst.object_from_world_2, p);
}

fn object_vector(inst: Instance, v: vec3f) -> vec3f {
  return rows_vector(inst.object_from_world_0, inst.object_from_world_1, inst.object_from_world_2, v);
}

// A normal to world space: the transpose of object_from_world's linear part (the inverse transpose
// of world_from_object), normalised.
fn world_normal(inst: Instance, n: vec3f) -> vec3f {
  let w = n.x * inst.object_from_world_0.xyz + n.y * inst.object_from_world_1.xyz + n.z * inst.object_from_world_2.xyz;
  let len = length(w);
  return select(n, w / len, len > 0.0);
}

// Where the world point p (on `instance` now) was in the previous frame: through object space and
// the previous transform. The static world does not move.
fn previous_world_point(instance: u32, p: vec3f) -> vec3f {
  if (instance_is_static(instance)) {
    return p;
  }
  let inst = instance_record(instance);
  return rows_point(inst.previous_0, inst.previous_1, inst.previous_2, object_point(inst, p));
}

fn instance_mirrored(instance: u32) -> bool {
  return !instance_is_static(instance) && (instance_record(instance).flags & INSTANCE_MIRRORED) != 0u;
}

// The uniform scale of a similarity transform (spheres and capsules): the length of a transformed axis.
fn instance_scale(inst: Instance) -> f32 {
  return length(vec3f(inst.world_from_object_0.x, inst.world_from_object_1.x, inst.world_from_object_2.x));
}

// The primitive `leaf` of `instance` in world space. A mirroring instance's triangles have e1 and e2
// swapped, so that e1 × e2 still points out of the front face (as scene/triangles.ts writes them).
fn world_primitive(instance: u32, leaf: u32) -> TriangleHot {
  let prim = scene_triangle_hot(leaf);
  if (instance_is_static(instance)) {
    return prim;
  }
  let inst = instance_record(instance);
  var out = prim;
  out.v0 = world_point(inst, prim.v0);
  if ((prim.flags & PRIMITIVE_SPHERE) != 0u) {
    out.e1 = vec3f(prim.e1.x * instance_scale(inst), 0.0, 0.0);
  } else if ((prim.flags & PRIMITIVE_CAPSULE) != 0u) {
    out.e1 = world_vector(inst, prim.e1);
    out.e2 = vec3f(prim.e2.x * instance_scale(inst), 0.0, 0.0);
  } else if ((inst.flags & INSTANCE_MIRRORED) != 0u) {
    out.e1 = world_vector(inst, prim.e2);
    out.e2 = world_vector(inst, prim.e1);
  } else {
    out.e1 = world_vector(inst, prim.e1);
    out.e2 = world_vector(inst, prim.e2);
  }
  return out;
}

// The shading record of `leaf` of `instance` in world space: normals transformed (vertices 1 and 2
// swapped with a mirror, like the positions), the instance's material where it replaces the mesh's,
// and the source index in the scene's flattened list.
fn world_shading(instance: u32, leaf: u32) -> TriangleShading {
  let s = scene_triangle_shading(leaf);
  if (instance_is_static(instance)) {
    return s;
  }
  let inst = instance_record(instance);
  var out = s;
  let mirrored = (inst.flags & INSTANCE_MIRRORED) != 0u && (scene_triangle_flags(leaf) & PRIMITIVE_ANALYTIC) == 0u;
  out.n0 = world_normal(inst, s.n0);
  out.n1 = world_normal(inst, select(s.n1, s.n2, mirrored));
  out.n2 = world_normal(inst, select(s.n2, s.n1, mirrored));
  out.uv1 = select(s.uv1, s.uv2, mirrored);
  out.uv2 = select(s.uv2, s.uv1, mirrored);
  out.material = select(inst.material, s.material, inst.material == NO_MATERIAL);
  out.source_index = inst.source_base + s.source_index;
  return out;
}

// The material of `leaf` as `instance` shows it.
fn instance_material(instance: u32, leaf: u32) -> u32 {
  let own = scene_triangle_material(leaf);
  if (instance_is_static(instance)) {
    return own;
  }
  let m = instance_record(instance).material;
  return select(m, own, m == NO_MATERIAL);
}

// Which stored vertex (0, 1, 2) of `leaf` is vertex k of the world-space primitive.
fn stored_vertex(instance: u32, leaf: u32, k: u32) -> u32 {
  if (k == 0u || !instance_mirrored(instance) || (scene_triangle_flags(leaf) & PRIMITIVE_ANALYTIC) != 0u) {
    return k;
  }
  return 3u - k;
}

// A hit's barycentrics in the stored vertex order (trace_closest swaps them for mirroring instances).
fn stored_bary(hit: Hit) -> vec2f {
  let bary = vec2f(hit.u, hit.v);
  return select(bary, bary.yx, instance_mirrored(hit.instance) && (scene_triangle_flags(hit.triangle) & PRIMITIVE_ANALYTIC) == 0u);
}
