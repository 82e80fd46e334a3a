/**
 * Per-primitive bounding boxes, computed once before the build so the hot loops read 6 floats per
 * primitive instead of re-deriving them from the 9 position floats at every level of the tree.
 * Primitives are triangles, spheres and capsules in the layout of scene/triangles.ts.
 */
import { LanternError } from '../errors.ts';
import { PRIMITIVE_KIND } from '../scene/triangles.ts';

/** The largest finite float32. */
export const F32_MAX = 3.4028234663852886e38;

const f32 = new Float32Array(1);
const u32 = new Uint32Array(f32.buffer);

/** The largest float32 <= x (x finite). */
export function f32Down(x: number): number {
  f32[0] = x;
  if (f32[0]! <= x) return f32[0]!;
  if (f32[0] === 0) return -1.401298464324817e-45;
  u32[0] = f32[0]! > 0 ? u32[0]! - 1 : u32[0]! + 1;
  return f32[0]!;
}

/** The smallest float32 >= x (x finite). */
export function f32Up(x: number): number {
  return -f32Down(-x);
}

/**
 * 6 floats per primitive: min xyz, max xyz. Triangle boxes are exact (min/max of float32 inputs
 * are float32 values); sphere and capsule boxes (centre ± radius) are rounded outward, so the float32
 * box always contains the shape. Without `kinds` every primitive is a triangle. Throws a
 * LanternError for a malformed array or a NaN / infinite coordinate, which would otherwise poison
 * every box above it without a trace.
 */
export function computeTriangleBoxes(positions: Float32Array, kinds?: Uint8Array): Float32Array {
  if (positions.length % 9 !== 0) {
    throw new LanternError(`a primitive position array must hold 9 floats per primitive, got ${positions.length} floats`);
  }
  const count = positions.length / 9;
  const boxes = new Float32Array(count * 6);
  for (let t = 0; t < count; t++) {
    const p = t * 9, b = t * 6;
    const kind = kinds ? kinds[t]! : PRIMITIVE_KIND.triangle;
    if (kind === PRIMITIVE_KIND.triangle) {
      for (let a = 0; a < 3; a++) {
        const v0 = positions[p + a]!, v1 = positions[p + 3 + a]!, v2 = positions[p + 6 + a]!;
        // x - x is 0 for every finite x and NaN for NaN and ±Infinity.
        if ((v0 - v0) + (v1 - v1) + (v2 - v2) !== 0) {
          throw new LanternError(`triangle ${t} has a non-finite vertex coordinate`, 'check the mesh for NaN or infinite positions');
        }
        boxes[b + a] = v0 < v1 ? (v0 < v2 ? v0 : v2) : v1 < v2 ? v1 : v2;
        boxes[b + 3 + a] = v0 > v1 ? (v0 > v2 ? v0 : v2) : v1 > v2 ? v1 : v2;
      }
      continue;
    }
    const sphere = kind === PRIMITIVE_KIND.sphere;
    const r = positions[p + (sphere ? 3 : 6)]!;
    if (!(r > 0 && r < Infinity)) throw new LanternError(`${sphere ? 'sphere' : 'capsule'} ${t} has radius ${r}, not a positive finite number`);
    for (let a = 0; a < 3; a++) {
      const c0 = positions[p + a]!, c1 = sphere ? c0 : positions[p + 3 + a]!;
      if ((c0 - c0) + (c1 - c1) !== 0) throw new LanternError(`${sphere ? 'sphere' : 'capsule'} ${t} has a non-finite coordinate`);
      boxes[b + a] = f32Down(Math.min(c0, c1) - r);
      boxes[b + 3 + a] = f32Up(Math.max(c0, c1) + r);
    }
  }
  return boxes;
}
