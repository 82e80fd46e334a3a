/**
 * Exact SAH for small nodes: with only a handful of triangles, sorting their centroids along each
 * axis and scoring every gap between neighbours is cheaper than filling and sweeping B bins per
 * axis (a JS-speed concern: most nodes of a big tree are this small), and it can only find an
 * equal or better split than binning, since every binned plane is one of these gaps.
 *
 * Same conventions as SahBinner: centroids are min + max in float64, the score is
 * A_L·N_L + A_R·N_R (half areas), and two triangles with equal centroids on the axis are never
 * separated (no plane between them), so a node whose centroids all coincide reports no split.
 */
import { emptyBox, growBoxAt, halfArea, sweepMax, sweepMin } from './box-area.ts';

/** Nodes with at most this many triangles use the exact sweep. */
export const SMALL_NODE_MAX = 12;

export class SmallSahSplitter {
  /** The node's triangles: boxes (6 each), copied out of the working array, and their order per axis. */
  private readonly box = new Float64Array(SMALL_NODE_MAX * 6);
  private readonly key = new Float64Array(SMALL_NODE_MAX);
  /** The sorted order on each axis, SMALL_NODE_MAX entries per axis. */
  private readonly orders = new Uint8Array(3 * SMALL_NODE_MAX);
  private readonly prefixCost = new Float64Array(SMALL_NODE_MAX);
  private readonly saved = new Uint32Array(SMALL_NODE_MAX);

  /** Result of the last `findSplit`: best axis (-1: none), its score, left side size and order. */
  axis = -1;
  cost = Infinity;
  leftCount = 0;
  /** Where the best split's order (left side first) starts in `orders`. */
  private bestBase = 0;
  readonly leftBox = new Float64Array(6);
  readonly rightBox = new Float64Array(6);

  /** Scores every centroid gap of work[start..end) (at most SMALL_NODE_MAX triangles) on every axis. */
  findSplit(work: Float32Array, start: number, end: number): boolean {
    const k = end - start, box = this.box, key = this.key;
    const prefixCost = this.prefixCost, orders = this.orders;
    for (let i = 0; i < k * 6; i++) box[i] = work[start * 6 + i]!;
    if (k === 2) return this.findPairSplit();
    let bestCost = Infinity, bestAxis = -1, bestLeft = 0;
    for (let a = 0; a < 3; a++) {
      // Insertion sort by centroid: k is tiny, and it is stable, so equal keys keep their order.
      const o = a * SMALL_NODE_MAX;
      for (let i = 0; i < k; i++) {
        const c = box[i * 6 + a]! + box[i * 6 + 3 + a]!;
        let j = i;
        while (j > 0 && key[j - 1]! > c) {
          key[j] = key[j - 1]!;
          orders[o + j] = orders[o + j - 1]!;
          j--;
        }
        key[j] = c;
        orders[o + j] = i;
      }
      if (key[0] === key[k - 1]) continue; // flat axis: no plane
      // prefixCost[j] = A·N of the first j+1 triangles in sorted order (sweepMin/Max: see box-area.ts).
      let m = orders[o]! * 6;
      let x0 = box[m]!, y0 = box[m + 1]!, z0 = box[m + 2]!, x1 = box[m + 3]!, y1 = box[m + 4]!, z1 = box[m + 5]!;
      prefixCost[0] = halfArea(x0, y0, z0, x1, y1, z1);
      for (let j = 1; j < k - 1; j++) {
        m = orders[o + j]! * 6;
        x0 = sweepMin(x0, box[m]!); y0 = sweepMin(y0, box[m + 1]!); z0 = sweepMin(z0, box[m + 2]!);
        x1 = sweepMax(x1, box[m + 3]!); y1 = sweepMax(y1, box[m + 4]!); z1 = sweepMax(z1, box[m + 5]!);
        prefixCost[j] = halfArea(x0, y0, z0, x1, y1, z1) * (j + 1);
      }
      m = orders[o + k - 1]! * 6;
      x0 = box[m]!; y0 = box[m + 1]!; z0 = box[m + 2]!; x1 = box[m + 3]!; y1 = box[m + 4]!; z1 = box[m + 5]!;
      for (let j = k - 1; j > 0; j--) {
        if (j < k - 1) {
          m = orders[o + j]! * 6;
          x0 = sweepMin(x0, box[m]!); y0 = sweepMin(y0, box[m + 1]!); z0 = sweepMin(z0, box[m + 2]!);
          x1 = sweepMax(x1, box[m + 3]!); y1 = sweepMax(y1, box[m + 4]!); z1 = sweepMax(z1, box[m + 5]!);
        }
        // Gap between sorted positions j-1 and j: left = first j triangles.
        if (key[j - 1] === key[j]) continue;
        const total = prefixCost[j - 1]! + halfArea(x0, y0, z0, x1, y1, z1) * (k - j);
        if (total < bestCost) {
          bestCost = total;
          bestAxis = a;
          bestLeft = j;
        }
      }
    }
    this.axis = bestAxis;
    this.cost = bestCost;
    this.leftCount = bestLeft;
    if (bestAxis < 0) return false;
    this.bestBase = bestAxis * SMALL_NODE_MAX;
    this.sideBox(0, this.leftCount, this.leftBox);
    this.sideBox(this.leftCount, k, this.rightBox);
    return true;
  }

  /**
   * Two triangles (box already copied): the only split puts them apart, on the first axis where
   * their centroids differ (the later axes tie with it), the lower one left: what the sweep above
   * finds, without sorting and sweeping three axes.
   */
  private findPairSplit(): boolean {
    const box = this.box;
    let a = 0;
    while (a < 3 && box[a]! + box[3 + a]! === box[6 + a]! + box[9 + a]!) a++;
    this.axis = a < 3 ? a : -1;
    this.leftCount = 1;
    if (a === 3) {
      this.cost = Infinity;
      return false;
    }
    const order = this.orders;
    const swap = box[a]! + box[3 + a]! > box[6 + a]! + box[9 + a]!;
    order[0] = swap ? 1 : 0;
    order[1] = swap ? 0 : 1;
    this.bestBase = 0;
    const l = order[0]! * 6, r = order[1]! * 6;
    this.cost = halfArea(box[l]!, box[l + 1]!, box[l + 2]!, box[l + 3]!, box[l + 4]!, box[l + 5]!) + halfArea(box[r]!, box[r + 1]!, box[r + 2]!, box[r + 3]!, box[r + 4]!, box[r + 5]!);
    this.sideBox(0, 1, this.leftBox);
    this.sideBox(1, 2, this.rightBox);
    return true;
  }

  /** Reorders index/work[start..end) into the best order found, left side first. */
  apply(index: Uint32Array, work: Float32Array, start: number, end: number): void {
    const k = end - start, box = this.box;
    for (let i = 0; i < k; i++) this.saved[i] = index[start + i]!;
    for (let j = 0; j < k; j++) {
      const src = this.orders[this.bestBase + j]!;
      index[start + j] = this.saved[src]!;
      for (let c = 0; c < 6; c++) work[(start + j) * 6 + c] = box[src * 6 + c]!;
    }
  }

  private sideBox(from: number, to: number, out: Float64Array): void {
    const box = this.box;
    emptyBox(out);
    for (let j = from; j < to; j++) {
      const m = this.orders[this.bestBase + j]! * 6;
      growBoxAt(out, 0, box[m]!, box[m + 1]!, box[m + 2]!, box[m + 3]!, box[m + 4]!, box[m + 5]!);
    }
  }
}
