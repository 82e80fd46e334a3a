/**
 * Small immutable 3-vectors as tuples for scene descriptions and camera set-up (not hot loops: those
 * work on typed arrays directly).
 */
export type Vec3 = readonly [number, number, number];

export const add = (a: Vec3, b: Vec3): Vec3 => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
export const sub = (a: Vec3, b: Vec3): Vec3 => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
export const scale = (a: Vec3, s: number): Vec3 => [a[0] * s, a[1] * s, a[2] * s];
export const dot = (a: Vec3, b: Vec3): number => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
export const cross = (a: Vec3, b: Vec3): Vec3 => [
  a[1] * b[2] - a[2] * b[1],
  a[2] * b[0] - a[0] * b[2],
  a[0] * b[1] - a[1] * b[0],
];
export const length = (a: Vec3): number => Math.sqrt(dot(a, a));
export function normalize(a: Vec3): Vec3 {
  const len = length(a);
  if (!(len > 0)) throw new RangeError(`cannot normalize a zero-length vector (${a.join(', ')})`);
  return scale(a, 1 / len);
}
export const isFiniteVec3 = (a: Vec3): boolean => a.every(Number.isFinite);
/** `a` at unit length, or undefined when it has none to scale (zero, or not finite): for directions read from files. */
export function unitOrUndefined(a: Vec3): Vec3 | undefined {
  const len = length(a);
  return len > 0 && Number.isFinite(len) ? scale(a, 1 / len) : undefined;
}

/** Rec. 709 / sRGB luminance of a linear RGB triple. The WGSL twin is `luminance` in lib/color.wgsl. */
export const luminance = (c: Vec3): number => 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];

/**
 * Two unit vectors completing the unit n to a right-handed frame (t, b, n) (Duff et al. 2017,
 * "Building an Orthonormal Basis, Revisited"), exactly as shaders/lib/sampling.wgsl orthonormal_basis.
 */
export function orthonormalFrame(n: readonly [number, number, number]): [Vec3, Vec3] {
  const [nx, ny, nz] = n;
  const sign = nz >= 0 ? 1 : -1;
  const a = -1 / (sign + nz);
  const b = nx * ny * a;
  return [
    [1 + sign * nx * nx * a, sign * b, -sign * nx],
    [b, sign + ny * ny * a, -ny],
  ];
}
