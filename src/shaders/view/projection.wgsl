// Camera projection, the inverse of camera_ray: a world-space point (or direction) to a continuous
// image point in pixels and its linear depth. Used for reprojection into the previous frame.
// Expects view/bindings for the Camera struct.

#import view/bindings

// The image point (pixels, (0, 0) the top-left corner, pixel centres at +0.5) and linear depth (along
// the unit forward axis) of a point at `offset` from the camera. depth ≤ 0: behind the camera.
fn project_offset(c: Camera, image_size: vec2u, offset: vec3f) -> vec3f {
  let depth = dot(offset, c.forward);
  // camera_ray's direction is forward + ndc.x·right − ndc.y·up with right, up ⟂ forward.
  let ndc = vec2f(dot(offset, c.right) / dot(c.right, c.right), -dot(offset, c.up) / dot(c.up, c.up)) / depth;
  return vec3f((ndc + 1.0) * 0.5 * vec2f(image_size), depth);
}

fn project_point(c: Camera, image_size: vec2u, p: vec3f) -> vec3f {
  return project_offset(c, image_size, p - c.position);
}
