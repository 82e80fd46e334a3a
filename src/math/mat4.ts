/**
 * 4×4 affine transforms, column-major (element (row r, column c) at index c·4 + r), as glTF and WGSL
 * store matrices. Names read destination-from-source: worldFromObject maps object points to world.
 * For scene set-up and packing, not for hot loops over vertices (those inline the arithmetic).
 */
import type { Vec3 } from './vec3.ts';

export type Mat4 = readonly number[];

export const IDENTITY: Mat4 = Object.freeze([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]);

export const isIdentity = (m: Mat4): boolean => m.every((x, i) => x === IDENTITY[i]);

/** a · b (apply b first). */
export function multiply(a: Mat4, b: Mat4): Mat4 {
  const out = new Array<number>(16);
  for (let c = 0; c < 4; c++) {
    for (let r = 0; r < 4; r++) {
      let s = 0;
      for (let k = 0; k < 4; k++) s += a[k * 4 + r]! * b[c * 4 + k]!;
      out[c * 4 + r] = s;
    }
  }
  return out;
}

export const translation = (t: Vec3): Mat4 => [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, t[0], t[1], t[2], 1];

/** Translation · rotation (unit quaternion x, y, z, w) · scale, as a glTF node's TRS. */
export function fromTrs(t: Vec3, q: readonly [number, number, number, number], s: Vec3): Mat4 {
  const [x, y, z, w] = q;
  const xx = x * x, yy = y * y, zz = z * z, xy = x * y, xz = x * z, yz = y * z, wx = w * x, wy = w * y, wz = w * z;
  return [
    (1 - 2 * (yy + zz)) * s[0], 2 * (xy + wz) * s[0], 2 * (xz - wy) * s[0], 0,
    2 * (xy - wz) * s[1], (1 - 2 * (xx + zz)) * s[1], 2 * (yz + wx) * s[1], 0,
    2 * (xz + wy) * s[2], 2 * (yz - wx) * s[2], (1 - 2 * (xx + yy)) * s[2], 0,
    t[0], t[1], t[2], 1,
  ];
}

export const transformPoint = (m: Mat4, p: Vec3): Vec3 => [
  m[0]! * p[0] + m[4]! * p[1] + m[8]! * p[2] + m[12]!,
  m[1]! * p[0] + m[5]! * p[1] + m[9]! * p[2] + m[13]!,
  m[2]! * p[0] + m[6]! * p[1] + m[10]! * p[2] + m[14]!,
];

export const transformDirection = (m: Mat4, d: Vec3): Vec3 => [
  m[0]! * d[0] + m[4]! * d[1] + m[8]! * d[2],
  m[1]! * d[0] + m[5]! * d[1] + m[9]! * d[2],
  m[2]! * d[0] + m[6]! * d[1] + m[10]! * d[2],
];

/** Determinant of the upper-left 3×3 (negative: the transform mirrors, and flips triangle winding). */
export function determinant3(m: Mat4): number {
  return (
    m[0]! * (m[5]! * m[10]! - m[9]! * m[6]!) -
    m[4]! * (m[1]! * m[10]! - m[9]! * m[2]!) +
    m[8]! * (m[1]! * m[6]! - m[5]! * m[2]!)
  );
}

/**
 * The matrix that transforms normals: the inverse transpose of the upper-left 3×3, as a column-major
 * 3×3 (9 numbers), scaled by the determinant's sign only (normals are renormalised after use, so the
 * cofactor matrix is enough and never divides by a tiny determinant).
 */
export function normalMatrix(m: Mat4): number[] {
  const a = m[0]!, b = m[1]!, c = m[2]!, d = m[4]!, e = m[5]!, f = m[6]!, g = m[8]!, h = m[9]!, i = m[10]!;
  // Cofactors of the 3×3 [[a d g] [b e h] [c f i]] (rows), which equal det · inverse-transpose.
  const cof = [e * i - f * h, -(d * i - f * g), d * h - e * g, -(b * i - c * h), a * i - c * g, -(a * h - b * g), b * f - c * e, -(a * f - c * d), a * e - b * d];
  // cof is the inverse transpose times det, row-major; det expands along the first row.
  const s = a * cof[0]! + d * cof[1]! + g * cof[2]! < 0 ? -1 : 1;
  return [cof[0]! * s, cof[3]! * s, cof[6]! * s, cof[1]! * s, cof[4]! * s, cof[7]! * s, cof[2]! * s, cof[5]! * s, cof[8]! * s];
}

/**
 * The inverse of an affine transform (last row 0 0 0 1): the inverse 3×3 and −inverse·translation.
 * A singular 3×3 (a mesh flattened to a plane or a point) has no inverse: throws a RangeError.
 */
export function invertAffine(m: Mat4): Mat4 {
  const a = m[0]!, b = m[1]!, c = m[2]!, d = m[4]!, e = m[5]!, f = m[6]!, g = m[8]!, h = m[9]!, i = m[10]!;
  // Column-major 3×3 A with columns (a b c), (d e f), (g h i); inverse = adjugate / det.
  const c00 = e * i - f * h, c01 = -(b * i - c * h), c02 = b * f - c * e;
  const det = a * c00 + d * c01 + g * c02;
  if (!(Math.abs(det) > 0) || !Number.isFinite(det)) throw new RangeError('invertAffine: the transform is singular');
  const s = 1 / det;
  // Inverse, column-major: column j holds row j of the adjugate's transpose.
  const r = [
    c00 * s, c01 * s, c02 * s,
    -(d * i - f * g) * s, (a * i - c * g) * s, -(a * f - c * d) * s,
    (d * h - e * g) * s, -(a * h - b * g) * s, (a * e - b * d) * s,
  ];
  const tx = m[12]!, ty = m[13]!, tz = m[14]!;
  return [
    r[0]!, r[1]!, r[2]!, 0,
    r[3]!, r[4]!, r[5]!, 0,
    r[6]!, r[7]!, r[8]!, 0,
    -(r[0]! * tx + r[3]! * ty + r[6]! * tz), -(r[1]! * tx + r[4]! * ty + r[7]! * tz), -(r[2]! * tx + r[5]! * ty + r[8]! * tz), 1,
  ];
}
