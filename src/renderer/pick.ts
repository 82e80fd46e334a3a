/**
 * Renderer.pick: what the primary ray through a pixel hits, traced on the GPU by the scene's own
 * traversal (alpha tests included), one ray in a buffer and one hit read back.
 */
import { LanternError } from '../errors.ts';
import { createBufferWithData, readBuffer } from '../gpu/readback.ts';
import { primaryRay } from '../gpu/view.ts';
import { dot, type Vec3 } from '../math/vec3.ts';
import { packRays, rayBufferStrides, type TraceRaysPass, unpackHits } from '../passes/trace-rays-pass.ts';
import type { Camera } from '../scene/types.ts';
import type { FrameContext } from './frame.ts';

/** What one primary ray through a pixel hit (Renderer.pick). */
export interface PickResult {
  /** Distance from the camera along the ray (scene units). */
  readonly distance: number;
  /** Distance along the camera's forward axis: what a thin lens's focusDistance measures. */
  readonly depth: number;
  /** World-space hit point. */
  readonly position: Vec3;
  /** Index into Scene.instances, and that instance's id. */
  readonly instanceIndex: number;
  readonly instanceId: number;
  /** Index into Scene.materials. */
  readonly material: number;
  /** Source primitive index (scene/triangles.ts order). */
  readonly primitive: number;
}

/** A miss in a HitRecord (shaders/scene/types.wgsl NO_TRIANGLE). */
const NO_PRIMITIVE = 0xffffffff;

/** Traces the ray through the centre of pixel (x, y) of the frame's image (the lens centre's for a thin lens); null for a miss. */
export async function pickPixel(frame: FrameContext, pass: TraceRaysPass, x: number, y: number): Promise<PickResult | null> {
  const { device, scene: resources, prepared, camera, targets: size } = frame;
  if (!(x >= 0 && x < size.width && y >= 0 && y < size.height)) throw new LanternError(`pixel (${x}, ${y}) is outside the ${size.width}×${size.height} image`);
  const ray = primaryRay(camera, size.width, size.height, Math.floor(x) + 0.5, Math.floor(y) + 0.5);
  const rays = createBufferWithData(device, 'pick ray', packRays([ray]), GPUBufferUsage.STORAGE);
  const hits = device.createBuffer({ label: 'pick hit', size: rayBufferStrides().hit, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC });
  try {
    const encoder = device.createCommandEncoder({ label: 'pick' });
    pass.encode(encoder, { binding: await pass.bind(resources, rays, hits, 1), label: 'pick' });
    device.queue.submit([encoder.finish()]);
    const hit = unpackHits(await readBuffer(device, hits), 1)[0]!;
    if (hit.triangle === NO_PRIMITIVE || hit.triangle >= prepared.triangles.count) return null;
    const instanceIndex = prepared.triangles.instanceIds[hit.triangle]!;
    const { origin, direction } = ray;
    return {
      distance: hit.t,
      depth: hit.t * dot(direction, cameraForward(camera)),
      position: [origin[0] + hit.t * direction[0], origin[1] + hit.t * direction[1], origin[2] + hit.t * direction[2]],
      instanceIndex,
      instanceId: prepared.scene.instances[instanceIndex]!.id,
      material: prepared.triangles.materialIds[hit.triangle]!,
      primitive: hit.triangle,
    };
  } finally {
    rays.destroy();
    hits.destroy();
  }
}

function cameraForward(camera: Camera): Vec3 {
  const [x, y, z] = camera.forward;
  const len = Math.hypot(x, y, z);
  return [x / len, y / len, z / len];
}
