/**
 * Half the surface area of an axis-aligned box, the quantity the surface area heuristic weighs
 * nodes by. For a convex body inside a convex box, the chance that a random ray hitting the box
 * also hits the body is area(body)/area(box) (Cauchy's formula), so only ratios of areas matter and
 * the factor 2 is dropped. Computed in float64 so huge float32 coordinates (up to ~3.4e38, area up
 * to ~1e78) neither overflow nor lose the small terms.
 */
export function halfArea(minX: number, minY: number, minZ: number, maxX: number, maxY: number, maxZ: number): number {
  const dx = maxX - minX, dy = maxY - minY, dz = maxZ - minZ;
  return dx * dy + dy * dz + dz * dx;
}

/** Half area of box `i` of a flat min-xyz/max-xyz array (6 numbers per box). */
export function halfAreaAt(boxes: ArrayLike<number>, i: number): number {
  const o = i * 6;
  return halfArea(boxes[o]!, boxes[o + 1]!, boxes[o + 2]!, boxes[o + 3]!, boxes[o + 4]!, boxes[o + 5]!);
}

/**
 * Branch-free min and max, (a + b ∓ |a - b|) / 2, for the SAH sweeps only. Those sweeps grow boxes
 * over triangles in spatially random order, where compare-and-branch min/max mispredicts about half
 * the time and dominated the build of small nodes. The result can be off by about one ulp of
 * max(|a|, |b|), i.e. ~1e-16 of the coordinates' magnitude: it nudges a cost estimate only for boxes
 * some 1e10 times smaller than their distance from the origin, and then only which of two nearly
 * equal splits wins. Boxes that are stored (node bounds) always come from exact comparisons.
 * Both arguments must be finite: no ±Infinity sentinels (Inf - Inf is NaN), so a sweep starts
 * from its first box.
 */
export const sweepMin = (a: number, b: number): number => 0.5 * (a + b - Math.abs(a - b));
export const sweepMax = (a: number, b: number): number => 0.5 * (a + b + Math.abs(a - b));

/** Grows box `m` of a flat min-xyz/max-xyz array (its 6 numbers from index m) to hold the box (x0, y0, z0)–(x1, y1, z1). */
export function growBoxAt(boxes: Float64Array, m: number, x0: number, y0: number, z0: number, x1: number, y1: number, z1: number): void {
  if (x0 < boxes[m]!) boxes[m] = x0;
  if (y0 < boxes[m + 1]!) boxes[m + 1] = y0;
  if (z0 < boxes[m + 2]!) boxes[m + 2] = z0;
  if (x1 > boxes[m + 3]!) boxes[m + 3] = x1;
  if (y1 > boxes[m + 4]!) boxes[m + 4] = y1;
  if (z1 > boxes[m + 5]!) boxes[m + 5] = z1;
}

/** Empties `out` (a min-xyz/max-xyz box: +∞ minima, −∞ maxima) for growBoxAt to grow. */
export function emptyBox(out: Float64Array): void {
  out[0] = Infinity; out[1] = Infinity; out[2] = Infinity;
  out[3] = -Infinity; out[4] = -Infinity; out[5] = -Infinity;
}
