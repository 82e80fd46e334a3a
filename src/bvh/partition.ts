/**
 * In-place partition of a node's triangle range by a centroid plane, the step after the SAH picked
 * one. Hoare's two-scan scheme: walk i up over triangles already on the left, j down over those
 * already on the right, swap the misplaced pair, repeat; each triangle is classified once and only
 * misplaced pairs move. The index array and the working box array move together.
 */

/** A plane in bin space: a triangle goes left iff  ((lo + hi - origin)·scale) | 0  <= lastLeftBin. */
export interface BinPlane {
  axis: number;
  origin: number;
  scale: number;
  lastLeftBin: number;
}

/** Returns the number of triangles moved to the left part of [start, end). */
export function partitionByPlane(plane: BinPlane, index: Uint32Array, work: Float32Array, workBits: Uint32Array, start: number, end: number): number {
  const { axis, origin, scale, lastLeftBin } = plane;
  // The binning's own expression, so a triangle lands on the side its bin was counted on.
  let i = start, j = end; // [start, i) is left, [j, end) is right
  for (;;) {
    while (i < j && (((work[i * 6 + axis]! + work[i * 6 + 3 + axis]! - origin) * scale) | 0) <= lastLeftBin) i++;
    while (i < j && (((work[j * 6 - 6 + axis]! + work[j * 6 - 3 + axis]! - origin) * scale) | 0) > lastLeftBin) j--;
    if (i >= j) return i - start;
    // Triangle i belongs right and j-1 belongs left (they differ, else a scan would have passed it).
    j--;
    swapTriangles(index, workBits, i, j);
    i++;
  }
}

/** Swaps triangles a and b: index entries and boxes (moved as raw 32-bit words, bit-exact). */
export function swapTriangles(index: Uint32Array, workBits: Uint32Array, a: number, b: number): void {
  const t = index[a]!;
  index[a] = index[b]!;
  index[b] = t;
  const pa = a * 6, pb = b * 6;
  for (let c = 0; c < 6; c++) {
    const w = workBits[pa + c]!;
    workBits[pa + c] = workBits[pb + c]!;
    workBits[pb + c] = w;
  }
}
