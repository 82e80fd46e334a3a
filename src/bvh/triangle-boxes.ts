/**
 * Per-triangle bounding boxes, computed once before the build so the hot loops read 6 floats per
 * triangle instead of re-deriving them from the 9 vertex floats at every level of the tree.
 */
import { LanternError } from '../errors.ts';

/** The largest finite float32. */
export const F32_MAX = 3.4028234663852886e38;

/**
 * 6 floats per triangle: min xyz, max xyz. Exact: min/max of float32 inputs are float32 values.
 * Throws a LanternError for a malformed array or a NaN / infinite coordinate, which would otherwise
 * poison every box above it without a trace.
 */
export function computeTriangleBoxes(positions: Float32Array): Float32Array {
  if (positions.length % 9 !== 0) {
    throw new LanternError(`a triangle position array must hold 9 floats per triangle, got ${positions.length} floats`);
  }
  const count = positions.length / 9;
  const boxes = new Float32Array(count * 6);
  for (let t = 0; t < count; t++) {
    const p = t * 9, b = t * 6;
    for (let a = 0; a < 3; a++) {
      const v0 = positions[p + a]!, v1 = positions[p + 3 + a]!, v2 = positions[p + 6 + a]!;
      // x - x is 0 for every finite x and NaN for NaN and ±Infinity.
      if ((v0 - v0) + (v1 - v1) + (v2 - v2) !== 0) {
        throw new LanternError(`triangle ${t} has a non-finite vertex coordinate`, 'check the mesh for NaN or infinite positions');
      }
      boxes[b + a] = v0 < v1 ? (v0 < v2 ? v0 : v2) : v1 < v2 ? v1 : v2;
      boxes[b + 3 + a] = v0 > v1 ? (v0 > v2 ? v0 : v2) : v1 > v2 ? v1 : v2;
    }
  }
  return boxes;
}
