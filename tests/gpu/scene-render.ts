/**
 * Helpers for the light, environment and instance tests: render a small scene into the accumulation
 * buffer, read luminance and its standard error, and build floors seen from straight above (where a
 * pixel's footprint on the floor is an axis-aligned square, so expected pixel values are averages of
 * a closed form over that square).
 */
import type { Vec3 } from '../../src/math/vec3.ts';
import { translation } from '../../src/math/mat4.ts';
import { renderProgressive } from '../../src/renderer/progressive.ts';
import type { PreparedScene } from '../../src/renderer/prepare.ts';
import { Renderer, type Accumulation } from '../../src/renderer/renderer.ts';
import type { LightSampling } from '../../src/renderer/settings.ts';
import { floorSquare } from '../../src/scene/shapes.ts';
import type { Camera, Material, Mesh, Scene } from '../../src/scene/types.ts';
import { testGpu } from './gpu-context.ts';

export interface RenderOptions {
  readonly width: number;
  readonly height: number;
  readonly spp: number;
  readonly maxBounces: number;
  readonly lightSampling?: LightSampling;
  readonly seed?: number;
}

/** Renders `spp` samples per pixel; `between` runs after setScene (e.g. updateInstances, setEnvironment). */
export async function renderScene(scene: Scene | PreparedScene, o: RenderOptions, between?: (r: Renderer) => Promise<void> | void): Promise<Accumulation> {
  const renderer = await Renderer.create(await testGpu());
  try {
    await renderer.setScene(scene);
    await renderer.resize(o.width, o.height);
    renderer.updateSettings({ maxBounces: o.maxBounces, lightSampling: o.lightSampling ?? 'mis', seed: o.seed ?? 1, torch: { enabled: false } });
    await between?.(renderer);
    await renderProgressive(renderer, { spp: o.spp });
    return await renderer.readAccumulation();
  } finally {
    renderer.destroy();
  }
}

export const lum = (a: Accumulation, i: number): number => 0.2126 * a.radiance[i * 3]! + 0.7152 * a.radiance[i * 3 + 1]! + 0.0722 * a.radiance[i * 3 + 2]!;

/** Standard error of pixel i's mean luminance, from its own sample variance. */
export const se = (a: Accumulation, i: number): number => Math.sqrt(a.luminanceVariance[i]! / a.samples);

/** Mean luminance over pixels and the standard error of that mean. */
export function regionStats(a: Accumulation, pixels: readonly number[]): { mean: number; se: number } {
  let sum = 0, v = 0;
  for (const i of pixels) {
    sum += lum(a, i);
    v += a.luminanceVariance[i]! / a.samples;
  }
  return { mean: sum / pixels.length, se: Math.sqrt(v) / pixels.length };
}

/**
 * A camera at (cx, height, cz) looking straight down (−y) with screen right = +x and screen up = −z
 * (view.ts: right = forward × up). The pixel (px, py) of a w × h image then covers the floor square
 * x ∈ cx + halfWidth·[2px/w − 1, 2(px+1)/w − 1], z ∈ cz + halfHeight·[2py/h − 1, 2(py+1)/h − 1], where
 * halfHeight = height·tan(fov/2), halfWidth = halfHeight·w/h: the hit point is linear in the image point.
 */
export function topDownCamera(center: [number, number], height: number, halfExtent: number): Camera {
  return { position: [center[0], height, center[1]], forward: [0, -1, 0], up: [0, 0, -1], vfovDegrees: (2 * Math.atan(halfExtent / height) * 180) / Math.PI };
}

/** The floor square (x0, z0, x1, z1) seen by pixel (px, py) of a square image from topDownCamera. */
export function pixelFootprint(center: [number, number], halfExtent: number, size: number, px: number, py: number): [number, number, number, number] {
  const s = (2 * halfExtent) / size;
  return [center[0] - halfExtent + px * s, center[1] - halfExtent + py * s, center[0] - halfExtent + (px + 1) * s, center[1] - halfExtent + (py + 1) * s];
}

/** Mean of f(x, z) over a square by an n × n midpoint rule. */
export function squareMean(f: (x: number, z: number) => number, [x0, z0, x1, z1]: readonly number[], n = 8): number {
  let s = 0;
  for (let j = 0; j < n; j++) for (let i = 0; i < n; i++) s += f(x0! + ((i + 0.5) / n) * (x1! - x0!), z0! + ((j + 0.5) / n) * (z1! - z0!));
  return s / (n * n);
}

/** A large floor at y = 0 (mesh 0, material 0) with these materials. */
export function floorScene(name: string, materials: Material[], extra: Partial<Scene> = {}, extraMeshes: Mesh[] = []): Scene {
  return {
    name,
    meshes: [floorSquare('floor', 200, 1, 0), ...extraMeshes],
    instances: [{ id: 0, mesh: 0, worldFromObject: translation([0, 0, 0]) }],
    materials,
    camera: topDownCamera([0, 0], 2, 1),
    ...extra,
  };
}

export const grey = (v: number): Vec3 => [v, v, v];
