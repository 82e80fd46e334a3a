/**
 * The top level of the two-level BVH: a tree over instances' world boxes, rebuilt whenever something
 * moves, so it must be fast rather than optimal. A linear BVH (Lauterbach et al. 2009; Karras 2012):
 * box centroids become 30-bit Morton codes, a radix sort orders them, and each node splits its range
 * where the highest differing code bit changes. Leaves hold exactly one instance (`leftFirst` is the
 * instance's index, `triCount` 1), so traversal needs no indirection.
 *
 * Same node layout as the bottom level (bvh/types.ts): root 0, slot 1 unused, siblings adjacent in
 * pairs from slot 2. Node boxes are exact unions of the instance boxes.
 */
import type { Bvh } from './types.ts';

/** A tree over instances: Bvh's node arrays without triangle indices (leaves name their instance). */
export type Tlas = Pick<Bvh, 'nodeCount' | 'bounds' | 'leftFirst' | 'triCount'>;

/** Node slots a TLAS over `n` instances uses at most (root, the unused slot, 2(n − 1) children). */
export function tlasCapacity(n: number): number {
  return Math.max(2, 2 * n);
}

const MORTON_BITS = 10;

/** Spreads the low 10 bits of x so that bit i lands on bit 3i. */
function spread(x: number): number {
  x = (x | (x << 16)) & 0x030000ff;
  x = (x | (x << 8)) & 0x0300f00f;
  x = (x | (x << 4)) & 0x030c30c3;
  x = (x | (x << 2)) & 0x09249249;
  return x >>> 0;
}

/** Scratch arrays reused from one build to the next (a top level is rebuilt every frame something moves). */
const scratch = { size: 0, live: new Uint32Array(0), codes: new Uint32Array(0), order: new Uint32Array(0), codes2: new Uint32Array(0), order2: new Uint32Array(0) };
const counts = new Uint32Array(1024);

function scratchFor(n: number): typeof scratch {
  if (scratch.size < n) {
    const size = Math.max(n, 2 * scratch.size);
    Object.assign(scratch, { size, live: new Uint32Array(size), codes: new Uint32Array(size), order: new Uint32Array(size), codes2: new Uint32Array(size), order2: new Uint32Array(size) });
  }
  return scratch;
}

/**
 * Sorts `index` by `keys` (30-bit unsigned, the first n of each), stably, in three passes of 10 bits;
 * `keys2`/`index2` are scratch. After an odd number of passes the sorted data is in the scratch
 * arrays: returns the arrays that hold it.
 */
function radixSort(n: number, keys: Uint32Array, index: Uint32Array, keys2: Uint32Array, index2: Uint32Array): [Uint32Array, Uint32Array] {
  let k = keys, ix = index, k2 = keys2, ix2 = index2;
  for (let shift = 0; shift < 30; shift += 10) {
    counts.fill(0);
    for (let i = 0; i < n; i++) counts[(k[i]! >>> shift) & 1023]!++;
    let sum = 0;
    for (let b = 0; b < 1024; b++) {
      const c = counts[b]!;
      counts[b] = sum;
      sum += c;
    }
    for (let i = 0; i < n; i++) {
      const key = k[i]!;
      const dst = counts[(key >>> shift) & 1023]!++;
      k2[dst] = key;
      ix2[dst] = ix[i]!;
    }
    const tk = k, ti = ix;
    k = k2;
    ix = ix2;
    k2 = tk;
    ix2 = ti;
  }
  return [k, ix];
}

/**
 * Builds the tree over `boxes` (6 floats per instance: min xyz, max xyz). Instances with an empty
 * box (min > max) are left out. Reuses `into` when it has the capacity (no allocation per frame).
 */
export function buildTlas(boxes: Float32Array, into?: Tlas): Tlas {
  const total = boxes.length / 6;
  const work = scratchFor(total);
  const live = work.live;
  let n = 0;
  for (let i = 0; i < total; i++) if (boxes[i * 6]! <= boxes[i * 6 + 3]!) live[n++] = i;
  const capacity = tlasCapacity(n);
  const out: Tlas =
    into && into.bounds.length >= capacity * 6
      ? into
      : { nodeCount: 0, bounds: new Float32Array(capacity * 6), leftFirst: new Uint32Array(capacity), triCount: new Uint32Array(capacity) };
  const { bounds, leftFirst, triCount } = out;
  // The unused slot 1 (and an empty tree's root): an inverted, finite box.
  const empty = (node: number) => {
    bounds.set([3.4e38, 3.4e38, 3.4e38, -3.4e38, -3.4e38, -3.4e38], node * 6);
    leftFirst[node] = 0;
    triCount[node] = 0;
  };
  empty(0);
  empty(1);
  if (n === 0) return { ...out, nodeCount: 2 };

  // Morton codes of the centroids within the centroids' bounds.
  let lx = Infinity, ly = Infinity, lz = Infinity, hx = -Infinity, hy = -Infinity, hz = -Infinity;
  for (let j = 0; j < n; j++) {
    const o = live[j]! * 6;
    const cx = boxes[o]! + boxes[o + 3]!, cy = boxes[o + 1]! + boxes[o + 4]!, cz = boxes[o + 2]! + boxes[o + 5]!;
    if (cx < lx) lx = cx;
    if (cx > hx) hx = cx;
    if (cy < ly) ly = cy;
    if (cy > hy) hy = cy;
    if (cz < lz) lz = cz;
    if (cz > hz) hz = cz;
  }
  const q = (1 << MORTON_BITS) - 1;
  const sx = hx > lx ? q / (hx - lx) : 0, sy = hy > ly ? q / (hy - ly) : 0, sz = hz > lz ? q / (hz - lz) : 0;
  for (let j = 0; j < n; j++) {
    const o = live[j]! * 6;
    const x = ((boxes[o]! + boxes[o + 3]! - lx) * sx) | 0, y = ((boxes[o + 1]! + boxes[o + 4]! - ly) * sy) | 0, z = ((boxes[o + 2]! + boxes[o + 5]! - lz) * sz) | 0;
    work.codes[j] = ((spread(x) << 2) | (spread(y) << 1) | spread(z)) >>> 0;
    work.order[j] = live[j]!;
  }
  const [codes, order] = radixSort(n, work.codes, work.order, work.codes2, work.order2);

  // Top-down over ranges of the sorted order: the left child next, the right one's [node, lo, hi) on a stack.
  const stack = new Uint32Array(3 * 96);
  let sp = 0;
  let next = 2;
  let node = 0, lo = 0, hi = n;
  for (;;) {
    if (hi - lo === 1) {
      const item = order[lo]!;
      leftFirst[node] = item;
      triCount[node] = 1;
      const o = node * 6, b = item * 6;
      bounds[o] = boxes[b]!;
      bounds[o + 1] = boxes[b + 1]!;
      bounds[o + 2] = boxes[b + 2]!;
      bounds[o + 3] = boxes[b + 3]!;
      bounds[o + 4] = boxes[b + 4]!;
      bounds[o + 5] = boxes[b + 5]!;
      if (sp === 0) break;
      hi = stack[--sp]!;
      lo = stack[--sp]!;
      node = stack[--sp]!;
      continue;
    }
    const first = codes[lo]!, last = codes[hi - 1]!;
    let split: number;
    if (first === last) {
      split = (lo + hi) >>> 1;
    } else {
      // The first index whose code has the highest differing bit set.
      const bit = 31 - Math.clz32(first ^ last);
      let a = lo, b = hi - 1;
      while (a < b) {
        const m = (a + b) >>> 1;
        if ((codes[m]! >>> bit) & 1) b = m;
        else a = m + 1;
      }
      split = a;
    }
    const left = next;
    next += 2;
    leftFirst[node] = left;
    triCount[node] = 0;
    if (sp + 3 > stack.length) throw new Error('buildTlas: stack overflow');
    stack[sp++] = left + 1;
    stack[sp++] = split;
    stack[sp++] = hi;
    node = left;
    hi = split;
  }
  // Interior boxes bottom-up: children always sit after their parent.
  for (let node = next - 1; node >= 0; node--) {
    if (node === 1 || triCount[node] !== 0) continue;
    const l = leftFirst[node]! * 6, r = l + 6, o = node * 6;
    for (let c = 0; c < 3; c++) {
      const a = bounds[l + c]!, b = bounds[r + c]!, A = bounds[l + 3 + c]!, B = bounds[r + 3 + c]!;
      bounds[o + c] = a < b ? a : b;
      bounds[o + 3 + c] = A > B ? A : B;
    }
  }
  return { ...out, nodeCount: next };
}
