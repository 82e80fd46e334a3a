// Bind group 1, the view: the camera and the image size shared by the passes of one frame
// (gpu/view.ts fills it). Provides camera_ray (the pinhole ray through the lens centre) and
// camera_sample_ray (a thin-lens ray, pbrt-v4 §5.2.3). Expects scene/types for Ray.

#import lib/constants
#import lib/random
#import lib/sampling
#import scene/types

// A pinhole or thin-lens camera. right and up are scaled so that the image edges lie at ±1 along
// them at unit distance along forward: right = tan(fov_y/2)·aspect·r̂, up = tan(fov_y/2)·û.
// The lens's two scalars sit in the padding after position and right (std140-like vec3 alignment),
// so the struct is no larger than the pinhole's.
struct Camera {
  position: vec3f,
  // Radius of the aperture disk around position, in the plane spanned by right and up (scene
  // units); 0: a pinhole.
  aperture_radius: f32,
  right: vec3f,
  // Distance from the lens to the plane in focus, measured along forward (scene units); used only
  // when aperture_radius > 0.
  focus_distance: f32,
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

// Where `pixel`'s value lies in a per-pixel buffer of the image (row-major).
fn image_index(pixel: vec2u) -> u32 {
  return pixel.y * view.image_size.x + pixel.x;
}

// The ray through a point of the image given in pixels, (0, 0) the top-left corner of the image,
// from the camera position (the lens centre). Unit direction; the valid interval starts at the
// camera. With a lens this is the chief ray: the G-buffer, the debug views and the projections
// (view/projection, the wireframe) use it, so they stay sharp and defined.
fn camera_ray(image_point: vec2f) -> Ray {
  let ndc = 2.0 * image_point / vec2f(view.image_size) - vec2f(1.0);
  let c = view.camera;
  let direction = normalize(c.forward + ndc.x * c.right - ndc.y * c.up);
  return Ray(c.position, 0.0, direction, T_MISS);
}

// The point camera `c` sees through the centre of `pixel` at linear depth `depth` (along camera_ray's
// direction, made with c instead of view.camera): a G-buffer texel's surface point.
fn pixel_centre_point(c: Camera, pixel: vec2u, depth: f32) -> vec3f {
  let ndc = 2.0 * (vec2f(pixel) + 0.5) / vec2f(view.image_size) - vec2f(1.0);
  let direction = normalize(c.forward + ndc.x * c.right - ndc.y * c.up);
  return c.position + direction * (depth / dot(direction, c.forward));
}

// The thin-lens ray through an image point for a lens sample u in [0, 1)² (pbrt-v4 §5.2.3,
// PerspectiveCamera::GenerateRay): a point on the aperture disk (Shirley & Chiu's concentric map)
// aimed at the point where the chief ray meets the plane of focus, so that everything on that
// plane is sharp and a point at depth d is spread over a disk of diameter 2A·|d − F|/d on it.
fn thin_lens_ray(image_point: vec2f, u: vec2f) -> Ray {
  let chief = camera_ray(image_point);
  let c = view.camera;
  // The chief ray reaches the plane of focus (depth focus_distance along forward) at this distance.
  let focus_point = c.position + chief.direction * (c.focus_distance / dot(chief.direction, c.forward));
  let lens = c.aperture_radius * concentric_disk(u);
  let origin = c.position + lens.x * normalize(c.right) + lens.y * normalize(c.up);
  return Ray(origin, 0.0, normalize(focus_point - origin), T_MISS);
}

// A sample's camera ray: the thin-lens ray with a lens point drawn from rng, or, for a pinhole
// (aperture 0), camera_ray exactly, drawing nothing, so a pinhole's random streams and images are
// what they were before lenses existed. The branch is uniform (a view constant) and costs nothing.
fn camera_sample_ray(image_point: vec2f, rng: ptr<function, Rng>) -> Ray {
  if (view.camera.aperture_radius > 0.0) {
    return thin_lens_ray(image_point, rng_next_2d(rng));
  }
  return camera_ray(image_point);
}
