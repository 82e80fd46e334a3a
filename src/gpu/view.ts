/**
 * The view uniform (bind group 1, shaders/view/bindings.wgsl): the camera basis scaled to the image,
 * the thin lens (aperture radius, focus distance; 0, 0 for a pinhole) and the image size. The WGSL struct is reflected; nothing here knows its byte layout. In gpu/, not
 * renderer/, because every pass binds it and passes sit below the renderer.
 */
import { makeStructuredView } from 'webgpu-utils';
import { cross, normalize, scale, type Vec3 } from '../math/vec3.ts';
import type { Camera } from '../scene/types.ts';
import { reflectModule } from './wgsl/reflect.ts';

export interface CameraBasis {
  readonly position: Vec3;
  /** Scaled: the image's right edge is at forward + right. */
  readonly right: Vec3;
  /** Scaled: the image's top edge is at forward + up. */
  readonly up: Vec3;
  readonly forward: Vec3;
}

/**
 * The pinhole basis for an image of the given aspect (width / height). Screen right is
 * forward × up, so a camera looking along +z with +y up sees +x on its left (as in the Cornell box
 * photographs, where the red wall at x ≈ 550 is on the left).
 */
export function cameraBasis(camera: Camera, aspect: number): CameraBasis {
  const forward = normalize(camera.forward);
  const right = normalize(cross(forward, camera.up));
  const up = cross(right, forward);
  const tanHalf = Math.tan((camera.vfovDegrees * Math.PI) / 360);
  return { position: camera.position, forward, right: scale(right, tanHalf * aspect), up: scale(up, tanHalf) };
}

/**
 * The primary ray through the image point (x, y) in pixels ((0, 0) the top-left corner, pixel
 * centres at +0.5) of a width × height image: the pinhole ray, which for a thin lens is the ray
 * through the lens centre (it meets the plane in focus where every ray of that pixel does). The
 * same arithmetic as view/bindings.wgsl camera_ray; unit direction.
 */
export function primaryRay(camera: Camera, width: number, height: number, x: number, y: number): { origin: Vec3; direction: Vec3 } {
  const b = cameraBasis(camera, width / height);
  const nx = (2 * x) / width - 1, ny = (2 * y) / height - 1;
  const d: Vec3 = [0, 1, 2].map((k) => b.forward[k]! + nx * b.right[k]! - ny * b.up[k]!) as unknown as Vec3;
  return { origin: b.position, direction: normalize(d) };
}

/** The WGSL Camera struct's values (view/bindings.wgsl): the pinhole basis and the lens (aperture 0: a pinhole). */
export type CameraUniform = {
  readonly position: Vec3;
  readonly right: Vec3;
  readonly up: Vec3;
  readonly forward: Vec3;
  readonly aperture_radius: number;
  readonly focus_distance: number;
};

export function cameraUniform(camera: Camera, aspect: number): CameraUniform {
  const b = cameraBasis(camera, aspect);
  return {
    position: b.position,
    right: b.right,
    up: b.up,
    forward: b.forward,
    aperture_radius: camera.lens?.apertureRadius ?? 0,
    focus_distance: camera.lens?.focusDistance ?? 0,
  };
}

export class ViewUniform {
  readonly buffer: GPUBuffer;
  private readonly values = makeStructuredView(reflectModule('view/bindings').defs.uniforms.view!);
  /** The image size of the last update (for passes that project into another camera). */
  width = 1;
  height = 1;

  constructor(private readonly device: GPUDevice) {
    this.buffer = device.createBuffer({ label: 'view', size: this.values.arrayBuffer.byteLength, usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST });
  }

  update(camera: Camera, width: number, height: number): void {
    this.width = width;
    this.height = height;
    this.values.set({ camera: cameraUniform(camera, width / height), image_size: [width, height] });
    this.device.queue.writeBuffer(this.buffer, 0, this.values.arrayBuffer);
  }

  destroy(): void {
    this.buffer.destroy();
  }
}
