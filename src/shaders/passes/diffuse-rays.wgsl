// Incoherent "diffuse" rays for the traversal benchmark: from each primary hit point a uniformly
// random direction back into the half-space the primary ray came from; primary misses start at the
// camera in a uniformly random direction. Inputs and outputs are group 2.

#import lib/random
#import lib/sampling
#import lib/ray-offset
#import scene/types

struct DiffuseRaysParams {
  ray_count: u32,
  seed: u32,
}

@group(2) @binding(0) var<uniform> params: DiffuseRaysParams;
@group(2) @binding(1) var<storage, read_write> rays: array<Ray>;
@group(2) @binding(2) var<storage, read> primary_rays: array<Ray>;
@group(2) @binding(3) var<storage, read> primary_hits: array<HitRecord>;

@compute @workgroup_size(64)
fn generate_diffuse_rays(@builtin(global_invocation_id) id: vec3u, @builtin(num_workgroups) groups: vec3u) {
  let i = id.y * groups.x * 64u + id.x;
  if (i >= params.ray_count) {
    return;
  }
  var rng = rng_seed(i, 0u, params.seed);
  let primary = primary_rays[i];
  let hit = primary_hits[i];
  var direction = sample_sphere_uniform(rng_next_2d(&rng));
  var origin = primary.origin;
  if (hit.triangle != NO_TRIANGLE) {
    direction = select(direction, -direction, dot(direction, primary.direction) > 0.0);
    origin = offset_ray_origin(primary.origin + hit.t * primary.direction, -primary.direction);
  }
  rays[i] = Ray(origin, 0.0, direction, T_MISS);
}
