/**
 * Walker's alias method (Walker 1977) built with Vose's stable algorithm (Vose 1991, "A Linear
 * Algorithm for Generating Random Numbers with a Given Distribution"): O(n) to build, O(1) to sample.
 * Slot i is chosen uniformly; it yields i with probability keep[i], otherwise alias[i].
 */
export interface AliasTable {
  readonly keep: Float64Array;
  readonly alias: Uint32Array;
  /** The normalised probabilities the table reproduces. */
  readonly pmf: Float64Array;
  readonly total: number;
}

export function buildAliasTable(weights: ArrayLike<number>): AliasTable {
  const n = weights.length;
  let total = 0;
  for (let i = 0; i < n; i++) {
    const w = weights[i]!;
    if (!(w >= 0) || !Number.isFinite(w)) throw new RangeError(`alias table weight ${i} is ${w}`);
    total += w;
  }
  if (n === 0 || !(total > 0)) throw new RangeError('alias table needs at least one positive weight');
  const pmf = new Float64Array(n);
  const scaled = new Float64Array(n);
  for (let i = 0; i < n; i++) {
    pmf[i] = weights[i]! / total;
    scaled[i] = pmf[i]! * n;
  }
  const keep = new Float64Array(n);
  const alias = new Uint32Array(n);
  const small: number[] = [];
  const large: number[] = [];
  for (let i = 0; i < n; i++) (scaled[i]! < 1 ? small : large).push(i);
  while (small.length > 0 && large.length > 0) {
    const s = small.pop()!;
    const l = large.pop()!;
    keep[s] = scaled[s]!;
    alias[s] = l;
    scaled[l] = scaled[l]! + scaled[s]! - 1;
    (scaled[l]! < 1 ? small : large).push(l);
  }
  // Whatever remains is 1 up to rounding: always kept.
  for (const i of [...small, ...large]) {
    keep[i] = 1;
    alias[i] = i;
  }
  return { keep, alias, pmf, total };
}

/** The exact probability of each outcome that a table produces (for tests). */
export function aliasTableProbabilities(table: AliasTable): Float64Array {
  const n = table.keep.length;
  const p = new Float64Array(n);
  for (let i = 0; i < n; i++) {
    p[i] = p[i]! + table.keep[i]! / n;
    p[table.alias[i]!] = p[table.alias[i]!]! + (1 - table.keep[i]!) / n;
  }
  return p;
}
