// The hit filter traversal applies to a candidate: alpha-masked and alpha-blended triangles count only
// where their coverage says so (scene/materials alpha_test_passes). Shared by scene/bvh and
// scene/traversal-unrolled (the specialised kernels' traversal), which must filter alike.
// Expects the scene bindings (group 0).

#import scene/bindings
#import scene/materials
#import scene/instances

// Whether the scene has alpha-masked or alpha-blended triangles. A pipeline constant: without them
// the alpha test folds away and traversal keeps its registers (5–8% faster on an H200 than testing the flag).
override SCENE_HAS_ALPHA_MASKS: bool = true;

// Identifies the ray being traced, so stochastic transparency draws a new number for every ray.
var<private> alpha_salt: u32;

// The instance whose bottom level traversal is in (two-level BVH): its material may replace the mesh's.
var<private> filter_instance: u32;
var<private> filter_instance_alpha: bool;

// Called as traversal enters an instance's bottom level.
fn set_filter_instance(instance: u32) {
  if (SCENE_HAS_ALPHA_MASKS && SCENE_HAS_INSTANCES) {
    filter_instance = instance;
    filter_instance_alpha = instance != 0u && (instance_record(instance).flags & INSTANCE_ALPHA_FILTER) != 0u;
  }
}

// A candidate hit that survives the alpha test, if the triangle (or its instance's material) has one.
// The barycentrics are the stored triangle's (object space for a moving instance).
fn accept_hit(tri: TriangleHot, triangle: u32, bary: vec2f) -> bool {
  if (!SCENE_HAS_ALPHA_MASKS) {
    return true;
  }
  if (SCENE_HAS_INSTANCES) {
    if ((tri.flags & TRIANGLE_ALPHA_MASKED) == 0u && !filter_instance_alpha) {
      return true;
    }
    return alpha_test_passes(instance_material(filter_instance, triangle), triangle, bary, alpha_salt);
  }
  return (tri.flags & TRIANGLE_ALPHA_MASKED) == 0u || alpha_test_passes(scene_triangle_material(triangle), triangle, bary, alpha_salt);
}

fn set_alpha_salt(ray: Ray) {
  set_filter_instance(0u);
  if (SCENE_HAS_ALPHA_MASKS) {
    let d = bitcast<vec3u>(ray.direction);
    alpha_salt = d.x ^ (d.y * 0x9e3779b9u) ^ (d.z * 0x85ebca6bu);
  }
}
