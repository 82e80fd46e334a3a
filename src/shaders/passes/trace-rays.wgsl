// Closest-hit tracing of a buffer of pre-generated rays, one invocation per ray: the traversal
// benchmark (as tinybvh's speed test measures it) and the GPU side of the traversal-versus-oracle
// test. Expects the scene (group 0); its own inputs and outputs are group 2.

#import lib/workgroup
#import scene/bvh

struct TraceRaysParams {
  ray_count: u32,
}

@group(2) @binding(0) var<uniform> params: TraceRaysParams;
@group(2) @binding(1) var<storage, read> rays: array<Ray>;
@group(2) @binding(2) var<storage, read_write> hits: array<HitRecord>;

// Rays are laid out in rows of 65535 × RAY_GROUP so that large batches fit the dispatch-size limit.
@compute @workgroup_size(RAY_GROUP)
fn trace_rays(@builtin(global_invocation_id) id: vec3u, @builtin(num_workgroups) groups: vec3u) {
  let i = id.y * groups.x * RAY_GROUP + id.x;
  if (i >= params.ray_count) {
    return;
  }
  let hit = trace_closest(rays[i]);
  var source = NO_TRIANGLE;
  if (hit.triangle != NO_TRIANGLE) {
    source = world_shading(hit.instance, hit.triangle).source_index;
  }
  hits[i] = HitRecord(hit.t, source, hit.u, hit.v);
}
