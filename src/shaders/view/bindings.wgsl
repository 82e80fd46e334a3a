// Bind group 1, the view: the camera and the image size shared by the passes of one frame
// (renderer/view.ts fills it). Provides camera_ray. Expects scene/types for Ray.

#import lib/constants
#import scene/types

// A pinhole camera. right and up are scaled so that the image edges lie at ±1 along them at unit
// distance along forward: right = tan(fov_y/2)·aspect·r̂, up = tan(fov_y/2)·û.
struct Camera {
  position: vec3f,
  right: vec3f,
  up: vec3f,
  // Unit viewing direction.
  forward: vec3f,
}

struct View {
  camera: Camera,
  // Pixels.
  image_size: vec2u,
}

@group(1) @binding(0) var<uniform> view: View;

// The ray through a point of the image given in pixels, (0, 0) the top-left corner of the image.
// Unit direction; the valid interval starts at the camera.
fn camera_ray(image_point: vec2f) -> Ray {
  let ndc = 2.0 * image_point / vec2f(view.image_size) - vec2f(1.0);
  let c = view.camera;
  let direction = normalize(c.forward + ndc.x * c.right - ndc.y * c.up);
  return Ray(c.position, 0.0, direction, T_MISS);
}
