/**
 * Binned surface area heuristic (Wald 2007): instead of sorting a node's triangles along each axis,
 * drop each centroid into one of B equal-width bins per axis, keep a triangle count and a box per
 * bin, then score the planes between bins with one prefix sweep and one suffix sweep. Cost per
 * node: O(count) for the binning plus O(B) per axis for the sweeps.
 *
 * The split that minimises  C = Ct + (A_L·N_L + A_R·N_R)/A · Ci  is the one with the smallest
 * A_L·N_L + A_R·N_R (Ct, Ci and A are fixed per node), so the binner only ranks by that sum and the
 * builder decides whether splitting beats a leaf.
 *
 * Triangles are read from the builder's working array: 6 floats per triangle (min xyz, max xyz),
 * kept in the same order as the index range being split. A centroid is never stored: it is taken as
 * min + max (twice the box centre; the factor 2 cancels in the binning), computed by the same
 * float64 expression everywhere so the binning and the partition always agree.
 *
 * Bin boxes are exact unions of float32 triangle boxes (float64 holds them exactly), so the child
 * boxes reported for the chosen plane are exact and need no extra pass over the triangles.
 */
import { emptyBox, growBoxAt, halfArea, sweepMax, sweepMin } from './box-area.ts';
import type { BinPlane } from './partition.ts';

export class SahBinner {
  readonly bins: number;
  /** Per axis a and bin k, slot a·B + k: triangle count, and box (min xyz, max xyz at slot·6). */
  private readonly counts: Uint32Array;
  private readonly binBox: Float64Array;
  /** Sweep scratch: the non-empty bins of one axis in order, and A·N / N of the prefix ending at each. */
  private readonly filled: Uint32Array;
  private readonly prefixCost: Float64Array;
  private readonly prefixCount: Uint32Array;
  /** Per axis: centroid-bounds minimum, and bins per unit length (0 for a flat axis). */
  private readonly origin = new Float64Array(3);
  private readonly scale = new Float64Array(3);

  /** Result of the last `findSplit`: axis (-1: none), last bin of the left side, A_L·N_L + A_R·N_R. */
  axis = -1;
  splitBin = -1;
  cost = Infinity;
  leftCount = 0;
  /** The same split as a plane in bin space, for the partition (refilled by each `findSplit`). */
  readonly plane: BinPlane = { axis: 0, origin: 0, scale: 0, lastLeftBin: 0 };
  /** min xyz, max xyz of each side of the best split. */
  readonly leftBox = new Float64Array(6);
  readonly rightBox = new Float64Array(6);

  constructor(bins: number) {
    this.bins = bins;
    this.counts = new Uint32Array(3 * bins);
    this.binBox = new Float64Array(18 * bins);
    this.filled = new Uint32Array(bins);
    this.prefixCost = new Float64Array(bins);
    this.prefixCount = new Uint32Array(bins);
  }

  /**
   * Bins work[start..end) into bins spanning `range` (min xyz, max xyz in centroid units, i.e.
   * min + max of a triangle box; it must contain every centroid) and finds the cheapest plane over
   * its non-flat axes. Returns false when there is none: every axis flat, or every centroid in one bin.
   */
  findSplit(work: Float32Array, start: number, end: number, range: Float64Array): boolean {
    const B = this.bins;
    let anyAxis = false;
    for (let a = 0; a < 3; a++) {
      const lo = range[a]!, extent = range[3 + a]! - lo;
      this.origin[a] = lo;
      // A flat axis gets scale 0: everything falls into its bin 0 and the sweep skips it.
      this.scale[a] = extent > 0 ? B / extent : 0;
      if (extent > 0) anyAxis = true;
    }
    this.axis = -1;
    this.cost = Infinity;
    if (!anyAxis) return false;

    const counts = this.counts, box = this.binBox;
    counts.fill(0);
    // Empty bins start inverted, so the loop below needs no first-triangle case; the sweeps and
    // sideBox only read bins whose count is non-zero.
    for (let m = 0; m < 18 * B; m += 6) {
      box[m] = Infinity; box[m + 1] = Infinity; box[m + 2] = Infinity;
      box[m + 3] = -Infinity; box[m + 4] = -Infinity; box[m + 5] = -Infinity;
    }
    const ox = this.origin[0]!, oy = this.origin[1]!, oz = this.origin[2]!;
    const sx = this.scale[0]!, sy = this.scale[1]!, sz = this.scale[2]!;
    const last = B - 1;
    for (let b = start * 6, bEnd = end * 6; b < bEnd; b += 6) {
      const x0 = work[b]!, y0 = work[b + 1]!, z0 = work[b + 2]!;
      const x1 = work[b + 3]!, y1 = work[b + 4]!, z1 = work[b + 5]!;
      // (c - origin)·B/extent, truncated; the clamp catches the maximum centroid, which lands on B.
      let kx = ((x0 + x1 - ox) * sx) | 0;
      let ky = ((y0 + y1 - oy) * sy) | 0;
      let kz = ((z0 + z1 - oz) * sz) | 0;
      if (kx > last) kx = last;
      if (ky > last) ky = last;
      if (kz > last) kz = last;
      ky += B;
      kz += 2 * B;
      counts[kx] = counts[kx]! + 1; counts[ky] = counts[ky]! + 1; counts[kz] = counts[kz]! + 1;
      growBoxAt(box, kx * 6, x0, y0, z0, x1, y1, z1);
      growBoxAt(box, ky * 6, x0, y0, z0, x1, y1, z1);
      growBoxAt(box, kz * 6, x0, y0, z0, x1, y1, z1);
    }
    for (let a = 0; a < 3; a++) if (this.scale[a]! > 0) this.sweep(a);
    if (this.axis < 0) return false;
    this.plane.axis = this.axis;
    this.plane.origin = this.origin[this.axis]!;
    this.plane.scale = this.scale[this.axis]!;
    this.plane.lastLeftBin = this.splitBin;
    this.sideBox(this.axis, 0, this.splitBin, this.leftBox);
    this.sideBox(this.axis, this.splitBin + 1, B - 1, this.rightBox);
    return true;
  }

  /**
   * Scores the planes of one axis. Planes next to an empty bin split the triangles exactly as their
   * neighbours do, so the non-empty bins are listed first and only the gaps between consecutive
   * ones are scored: prefix sweep left to right, suffix sweep right to left.
   */
  private sweep(axis: number): void {
    const base = axis * this.bins, counts = this.counts, box = this.binBox;
    const filled = this.filled, prefixCost = this.prefixCost, prefixCount = this.prefixCount;
    let f = 0;
    for (let k = 0; k < this.bins; k++) if (counts[base + k]! > 0) filled[f++] = base + k;
    if (f < 2) return;

    let m = filled[0]! * 6;
    let x0 = box[m]!, y0 = box[m + 1]!, z0 = box[m + 2]!, x1 = box[m + 3]!, y1 = box[m + 4]!, z1 = box[m + 5]!;
    let n = counts[filled[0]!]!;
    prefixCount[0] = n;
    prefixCost[0] = halfArea(x0, y0, z0, x1, y1, z1) * n;
    for (let i = 1; i < f - 1; i++) {
      m = filled[i]! * 6;
      // Branch-free union for the estimate only (see box-area.ts); stored boxes use sideBox.
      x0 = sweepMin(x0, box[m]!); y0 = sweepMin(y0, box[m + 1]!); z0 = sweepMin(z0, box[m + 2]!);
      x1 = sweepMax(x1, box[m + 3]!); y1 = sweepMax(y1, box[m + 4]!); z1 = sweepMax(z1, box[m + 5]!);
      n += counts[filled[i]!]!;
      prefixCount[i] = n;
      prefixCost[i] = halfArea(x0, y0, z0, x1, y1, z1) * n;
    }

    m = filled[f - 1]! * 6;
    x0 = box[m]!; y0 = box[m + 1]!; z0 = box[m + 2]!; x1 = box[m + 3]!; y1 = box[m + 4]!; z1 = box[m + 5]!;
    n = counts[filled[f - 1]!]!;
    for (let i = f - 1; i > 0; i--) {
      if (i < f - 1) {
        m = filled[i]! * 6;
        x0 = sweepMin(x0, box[m]!); y0 = sweepMin(y0, box[m + 1]!); z0 = sweepMin(z0, box[m + 2]!);
        x1 = sweepMax(x1, box[m + 3]!); y1 = sweepMax(y1, box[m + 4]!); z1 = sweepMax(z1, box[m + 5]!);
        n += counts[filled[i]!]!;
      }
      // Gap between filled bins i-1 and i: the left side is everything up to bin filled[i-1].
      const total = prefixCost[i - 1]! + halfArea(x0, y0, z0, x1, y1, z1) * n;
      if (total < this.cost) {
        this.cost = total;
        this.axis = axis;
        this.splitBin = filled[i - 1]! - base;
        this.leftCount = prefixCount[i - 1]!;
      }
    }
  }

  /** Exact union of the boxes of the non-empty bins first..last on `axis`, into out (min xyz, max xyz). */
  private sideBox(axis: number, first: number, last: number, out: Float64Array): void {
    const box = this.binBox;
    emptyBox(out);
    for (let s = axis * this.bins + first, sEnd = axis * this.bins + last; s <= sEnd; s++) {
      if (this.counts[s] === 0) continue;
      const m = s * 6;
      growBoxAt(out, 0, box[m]!, box[m + 1]!, box[m + 2]!, box[m + 3]!, box[m + 4]!, box[m + 5]!);
    }
  }
}
