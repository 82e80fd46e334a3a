/**
 * A uniform grid over the static world's primitives, the acceleration structure a tile map already
 * is, and its CPU traversal (the oracle of shaders/scene/grid.wgsl): the 3D-DDA of Amanatides & Woo,
 * "A Fast Voxel Traversal Algorithm for Ray Tracing" (Eurographics 1987).
 *
 * The grid indexes exactly the list the static BVH indexes, in its leaf order: an item is a leaf
 * position j of the static BVH (the primitive `triIndices[j]` of the scene's flattened list, record
 * j of triangles_hot), so a hit through the grid is the record a hit through the BVH is (same leaf,
 * same t, same barycentrics, instance 0).
 *
 * Cells are [start, count) ranges into one item list, x fastest then y then z. A primitive is listed
 * in every cell its box overlaps, and a triangle only in the cells it really crosses (the separating
 * axis test of Akenine-Möller, "Fast 3D Triangle-Box Overlap Testing", 2001), each cell widened by a
 * small margin so that rounding on either side (the hit point, the cell the walk computes) never
 * loses a hit. The grid box covers the whole static world: a tile map's hint (Scene.tileGrid) keeps
 * its cells and is widened by whole cells to the world box. Pure.
 */
import { LanternError } from '../errors.ts';
import type { Vec3 } from '../math/vec3.ts';
import type { Scene } from '../scene/types.ts';
import { prepareRay, type Ray } from './ray.ts';
import { Closest, type AnyTrace, type ClosestTrace } from './traverse.ts';
import { computeTriangleBoxes } from './triangle-boxes.ts';
import { PRIMITIVE_KIND } from '../scene/triangles.ts';

/** How the static world is traced: its BVH, its uniform grid, or a wide tree collapsed from its BVH (bvh/wide.ts) (the setting `accel`). */
export const ACCELS = ['bvh', 'grid', 'bvh4', 'cwbvh'] as const;
export type Accel = (typeof ACCELS)[number];

/**
 * Cells per primitive of the automatic resolution (cubic cells, about λ·N of them over the world
 * box). Ize, Shirley and Parker ("Grid creation strategies for efficient ray tracing", 2007) find the
 * optimum between 2 and 8 for scenes of triangles; 4 sits in the middle.
 */
export const GRID_CELLS_PER_PRIMITIVE = 4;
/** The most cells a grid may have (8 bytes each on the GPU: 32 MiB), automatic or hinted. */
export const GRID_MAX_CELLS = 1 << 22;
/** The most items (cell × primitive entries) a grid may list (4 bytes each: 256 MiB). */
export const GRID_MAX_ITEMS = 1 << 26;

export interface GridOptions {
  /**
   * Split a tile map's cells into whole sub-cells near the automatic rule's size (default), or keep
   * one cell per tile.
   */
  readonly subdivideTiles?: boolean;
}

export interface GridStats {
  readonly buildMs: number;
  /** Where the resolution came from. */
  readonly source: 'tile map' | 'automatic';
  readonly cells: number;
  /** Cells listing no primitive. */
  readonly emptyCells: number;
  /** Σ over cells of their counts (a primitive counts once per cell it is listed in). */
  readonly items: number;
  /** Mean count over non-empty cells, and the largest count. */
  readonly meanItems: number;
  readonly maxItems: number;
  /** Primitives indexed (the static world's). */
  readonly primitives: number;
}

export interface Grid {
  /** The corner of cell (0, 0, 0) and the opposite corner of the grid box (f32 values, as the GPU has them). */
  readonly lo: Vec3;
  readonly hi: Vec3;
  /** One cell's size on each axis (f32 values, > 0). */
  readonly cellSize: Vec3;
  readonly dims: readonly [number, number, number];
  /** Per cell (x fastest, then y, then z): the first item of its range, and its count. */
  readonly cellStart: Uint32Array;
  readonly cellCount: Uint32Array;
  /** Leaf positions of the static BVH (records of triangles_hot), cell after cell, ascending within a cell. */
  readonly items: Uint32Array;
  /** Leaf position → source primitive (the static BVH's triIndices): what a hit reports as `triangle`. */
  readonly leafToSource: Uint32Array;
  readonly stats: GridStats;
}

/** The resolution before the grid is filled: box, cell size, cells per axis. */
interface Resolution {
  readonly lo: Vec3;
  readonly cellSize: Vec3;
  readonly dims: readonly [number, number, number];
  readonly source: GridStats['source'];
}

const f = Math.fround;

/** The box of the listed primitives' boxes (6 floats), or undefined when there are none. */
function worldBox(boxes: Float32Array, leaves: Uint32Array): number[] | undefined {
  if (leaves.length === 0) return undefined;
  const b = [Infinity, Infinity, Infinity, -Infinity, -Infinity, -Infinity];
  for (const src of leaves) {
    for (let k = 0; k < 3; k++) {
      b[k] = Math.min(b[k]!, boxes[src * 6 + k]!);
      b[k + 3] = Math.max(b[k + 3]!, boxes[src * 6 + 3 + k]!);
    }
  }
  return b;
}

/** The side of the automatic rule's cubic cells over `world` for n primitives. */
function cubicCellSize(world: readonly number[], n: number): number {
  const extent = [0, 1, 2].map((k) => world[k + 3]! - world[k]!);
  const largest = Math.max(...extent, 1e-6);
  const sized = extent.map((e) => Math.max(e, largest * 1e-3));
  return Math.cbrt((sized[0]! * sized[1]! * sized[2]!) / Math.max(1, GRID_CELLS_PER_PRIMITIVE * n));
}

/** Cells of size `cs` about `world` (≈ λ·n of them, cubic), at most GRID_MAX_CELLS. */
function automaticResolution(world: number[], n: number): Resolution {
  const extent = [0, 1, 2].map((k) => world[k + 3]! - world[k]!);
  const largest = Math.max(...extent, 1e-6);
  // A flat axis (a floor alone) gets one cell as thick as a thousandth of the largest extent.
  const sized = extent.map((e) => Math.max(e, largest * 1e-3));
  const volume = sized[0]! * sized[1]! * sized[2]!;
  let cs = Math.cbrt(volume / Math.max(1, GRID_CELLS_PER_PRIMITIVE * n));
  let dims = sized.map((e) => Math.max(1, Math.ceil(e / cs)));
  while (dims[0]! * dims[1]! * dims[2]! > GRID_MAX_CELLS) {
    cs *= 1.25;
    dims = sized.map((e) => Math.max(1, Math.ceil(e / cs)));
  }
  // Centred on the world box, the cells an f32 size; hi follows from them.
  const cellSize = sized.map((e, k) => f(Math.max(e / dims[k]!, cs * 1e-6))) as unknown as Vec3;
  const lo = [0, 1, 2].map((k) => f(world[k]! - (dims[k]! * cellSize[k]! - extent[k]!) / 2)) as unknown as Vec3;
  return { lo, cellSize, dims: dims as unknown as [number, number, number], source: 'automatic' };
}

/** Refuses a malformed Scene.tileGrid with a message naming the problem. */
function checkHint(hint: NonNullable<Scene['tileGrid']>): void {
  const ok = (v: readonly number[], test: (x: number) => boolean) => v.length === 3 && v.every(test);
  if (!ok(hint.origin, Number.isFinite)) throw new LanternError(`the scene's tile grid origin must be three finite numbers, not ${hint.origin.join(', ')}`);
  if (!ok(hint.cellSize, (x) => Number.isFinite(x) && x > 0)) throw new LanternError(`the scene's tile grid cell size must be three positive numbers, not ${hint.cellSize.join(', ')}`);
  if (!ok(hint.dims, (x) => Number.isInteger(x) && x >= 1)) throw new LanternError(`the scene's tile grid must have a whole number ≥ 1 of cells on each axis, not ${hint.dims.join(' × ')}`);
}

/** The hint's cells, widened by whole cells until they cover the world box; undefined when that would be too many. */
function hintedResolution(hint: NonNullable<Scene['tileGrid']>, world: number[] | undefined, n: number, subdivide: boolean): Resolution | undefined {
  checkHint(hint);
  // Each tile split into whole sub-cells near the automatic rule's cubic size (walls on tile edges
  // stay on cell boundaries), where the tiles are coarser than that.
  const box = world ?? [hint.origin[0], hint.origin[1], hint.origin[2], ...hint.origin.map((o, k) => o + hint.dims[k]! * hint.cellSize[k]!)];
  const target = subdivide ? cubicCellSize(box, n) : Infinity;
  const split = hint.cellSize.map((c) => Math.max(1, Math.round(c / target)));
  const cellSize = hint.cellSize.map((c, k) => f(c / split[k]!)) as unknown as Vec3;
  const lo: number[] = [], dims: number[] = [];
  for (let k = 0; k < 3; k++) {
    const cs = cellSize[k]!;
    let o = hint.origin[k]!, d = hint.dims[k]! * split[k]!;
    if (world) {
      const below = Math.max(0, Math.ceil((o - world[k]!) / cs));
      o -= below * cs;
      d += below;
      // Up to a ten-thousandth of a cell short is no new layer: the box's top is raised to the world's (buildGrid).
      d += Math.max(0, Math.ceil((world[k + 3]! - (o + d * cs)) / cs - 1e-4));
    }
    lo.push(f(o));
    dims.push(d);
  }
  if (dims[0]! * dims[1]! * dims[2]! > GRID_MAX_CELLS) return undefined;
  return { lo: lo as unknown as Vec3, cellSize, dims: dims as unknown as [number, number, number], source: 'tile map' };
}

/**
 * Whether triangle (a, b, c) overlaps the box of centre `c0` and half-size `h` (closed: touching
 * counts). The separating axis theorem over 13 axes: the box's three normals (the boxes overlap), the
 * triangle's normal (the plane crosses the box), and the nine cross products of box and triangle edges.
 */
export function triangleOverlapsBox(p: ArrayLike<number>, o: number, c0: Vec3, h: Vec3): boolean {
  return overlaps(p, o, c0[0], c0[1], c0[2], h[0], h[1], h[2]);
}

/** The separating-axis test with scalars only (it runs once per candidate cell of every triangle). */
function overlaps(p: ArrayLike<number>, o: number, cx: number, cy: number, cz: number, hx: number, hy: number, hz: number): boolean {
  const ax = p[o]! - cx, ay = p[o + 1]! - cy, az = p[o + 2]! - cz;
  const bx = p[o + 3]! - cx, by = p[o + 4]! - cy, bz = p[o + 5]! - cz;
  const qx = p[o + 6]! - cx, qy = p[o + 7]! - cy, qz = p[o + 8]! - cz;
  if (Math.min(ax, bx, qx) > hx || Math.max(ax, bx, qx) < -hx) return false;
  if (Math.min(ay, by, qy) > hy || Math.max(ay, by, qy) < -hy) return false;
  if (Math.min(az, bz, qz) > hz || Math.max(az, bz, qz) < -hz) return false;
  // Edges.
  const e0x = bx - ax, e0y = by - ay, e0z = bz - az;
  const e1x = qx - bx, e1y = qy - by, e1z = qz - bz;
  const e2x = ax - qx, e2y = ay - qy, e2z = az - qz;
  // The triangle's plane: n · a against the box's projected radius.
  const nx = e0y * e1z - e0z * e1y, ny = e0z * e1x - e0x * e1z, nz = e0x * e1y - e0y * e1x;
  if (Math.abs(nx * ax + ny * ay + nz * az) > hx * Math.abs(nx) + hy * Math.abs(ny) + hz * Math.abs(nz)) return false;
  // Box axis × edge: x × e = (0, -ez, ey), y × e = (ez, 0, -ex), z × e = (-ey, ex, 0); for each, the
  // three vertices' projections against the box's radius on that axis.
  return (
    axisOverlaps(0, -e0z, e0y, ax, ay, az, bx, by, bz, qx, qy, qz, hx, hy, hz) &&
    axisOverlaps(e0z, 0, -e0x, ax, ay, az, bx, by, bz, qx, qy, qz, hx, hy, hz) &&
    axisOverlaps(-e0y, e0x, 0, ax, ay, az, bx, by, bz, qx, qy, qz, hx, hy, hz) &&
    axisOverlaps(0, -e1z, e1y, ax, ay, az, bx, by, bz, qx, qy, qz, hx, hy, hz) &&
    axisOverlaps(e1z, 0, -e1x, ax, ay, az, bx, by, bz, qx, qy, qz, hx, hy, hz) &&
    axisOverlaps(-e1y, e1x, 0, ax, ay, az, bx, by, bz, qx, qy, qz, hx, hy, hz) &&
    axisOverlaps(0, -e2z, e2y, ax, ay, az, bx, by, bz, qx, qy, qz, hx, hy, hz) &&
    axisOverlaps(e2z, 0, -e2x, ax, ay, az, bx, by, bz, qx, qy, qz, hx, hy, hz) &&
    axisOverlaps(-e2y, e2x, 0, ax, ay, az, bx, by, bz, qx, qy, qz, hx, hy, hz)
  );
}

function axisOverlaps(nx: number, ny: number, nz: number, ax: number, ay: number, az: number, bx: number, by: number, bz: number, qx: number, qy: number, qz: number, hx: number, hy: number, hz: number): boolean {
  const p0 = nx * ax + ny * ay + nz * az, p1 = nx * bx + ny * by + nz * bz, p2 = nx * qx + ny * qy + nz * qz;
  const r = hx * Math.abs(nx) + hy * Math.abs(ny) + hz * Math.abs(nz);
  return !(Math.min(p0, p1, p2) > r || Math.max(p0, p1, p2) < -r);
}

/**
 * Whether triangle `o` meets the cell of centre `c` only within the margin about one of its faces
 * while reaching on beyond that face: it then lies in the neighbouring cell (listed there), and a
 * hit on it within the margin is at the boundary the walk crosses into that cell. Without this,
 * every floor tile would be listed in its eight neighbours too (they touch along the tile edges).
 * A triangle lying in the face's plane (a wall between two tiles) reaches no further and stays
 * listed in both cells.
 */
function onlyGrazes(p: ArrayLike<number>, o: number, c: Vec3, cs: Vec3, pad: Vec3): boolean {
  for (let k = 0; k < 3; k++) {
    const a = p[o + k]!, b = p[o + 3 + k]!, d = p[o + 6 + k]!;
    const hiFace = c[k]! + cs[k]! / 2, loFace = c[k]! - cs[k]! / 2, m = pad[k]!;
    if (Math.min(a, b, d) >= hiFace - m && Math.max(a, b, d) > hiFace + m) return true;
    if (Math.max(a, b, d) <= loFace + m && Math.min(a, b, d) < loFace - m) return true;
  }
  return false;
}

/**
 * The grid over the static world: `leafToSource` is the static BVH's triIndices (leaf position →
 * primitive of `positions`, the scene's flattened list); `hint` a tile map's own grid.
 */
export function buildGrid(positions: Float32Array, kinds: Uint8Array | undefined, leafToSource: Uint32Array, hint?: Scene['tileGrid'], options: GridOptions = {}): Grid {
  const t0 = performance.now();
  const boxes = computeTriangleBoxes(positions, kinds);
  const world = worldBox(boxes, leafToSource);
  const res = (hint ? hintedResolution(hint, world, leafToSource.length, options.subdivideTiles ?? true) : undefined) ?? (world ? automaticResolution(world, leafToSource.length) : { lo: [0, 0, 0] as Vec3, cellSize: [1, 1, 1] as Vec3, dims: [1, 1, 1] as const, source: 'automatic' as const });
  const { lo, cellSize: cs, dims } = res;
  const [nx, ny, nz] = dims;
  const cellTotal = nx * ny * nz;
  // The box's top: the last cells' far faces, raised to the world box where rounding left them short.
  const hi = [0, 1, 2].map((k) => Math.max(f(lo[k]! + dims[k]! * cs[k]!), world ? world[k + 3]! : -Infinity)) as unknown as Vec3;
  // The margin each cell is widened by: a ten-thousandth of a cell, and a few f32 ulps of the coordinates.
  const magnitude = [0, 1, 2].map((k) => Math.max(Math.abs(lo[k]!), Math.abs(hi[k]!)));
  const pad = [0, 1, 2].map((k) => 1e-4 * cs[k]! + 1e-6 * magnitude[k]!) as unknown as Vec3;
  const half: Vec3 = [cs[0] / 2 + pad[0], cs[1] / 2 + pad[1], cs[2] / 2 + pad[2]];
  const cellRange = (src: number, k: number): [number, number] => {
    const a = Math.floor((boxes[src * 6 + k]! - pad[k]! - lo[k]!) / cs[k]!);
    const b = Math.floor((boxes[src * 6 + 3 + k]! + pad[k]! - lo[k]!) / cs[k]!);
    const n = dims[k]!;
    return [Math.min(n - 1, Math.max(0, a)), Math.min(n - 1, Math.max(0, b))];
  };
  // One pass collects (cell, leaf) pairs; a counting sort by cell then lays them out, leaves
  // ascending within a cell (they were collected in leaf order).
  let pairCells = new Uint32Array(Math.max(16, leafToSource.length * 4)), pairLeaves = new Uint32Array(pairCells.length);
  let itemTotal = 0;
  const counts = new Uint32Array(cellTotal);
  for (let leaf = 0; leaf < leafToSource.length; leaf++) {
    const src = leafToSource[leaf]!;
    const [x0, x1] = cellRange(src, 0), [y0, y1] = cellRange(src, 1), [z0, z1] = cellRange(src, 2);
    const triangle = (kinds ? kinds[src]! : PRIMITIVE_KIND.triangle) === PRIMITIVE_KIND.triangle;
    const single = x0 === x1 && y0 === y1 && z0 === z1;
    for (let z = z0; z <= z1; z++) {
      for (let y = y0; y <= y1; y++) {
        for (let x = x0; x <= x1; x++) {
          if (triangle && !single) {
            const cx = lo[0] + (x + 0.5) * cs[0], cy = lo[1] + (y + 0.5) * cs[1], cz = lo[2] + (z + 0.5) * cs[2];
            if (!overlaps(positions, src * 9, cx, cy, cz, half[0], half[1], half[2]) || onlyGrazes(positions, src * 9, [cx, cy, cz], cs, pad)) continue;
          }
          if (itemTotal === pairCells.length) {
            if (itemTotal >= GRID_MAX_ITEMS) throw new LanternError(`the grid lists more than ${GRID_MAX_ITEMS} primitive entries over ${nx} × ${ny} × ${nz} cells: too large primitives for a uniform grid`, "Use the BVH (accel 'bvh')");
            const grow = (a: Uint32Array) => {
              const b = new Uint32Array(a.length * 2);
              b.set(a);
              return b;
            };
            pairCells = grow(pairCells);
            pairLeaves = grow(pairLeaves);
          }
          const cell = x + nx * (y + ny * z);
          pairCells[itemTotal] = cell;
          pairLeaves[itemTotal++] = leaf;
          counts[cell]!++;
        }
      }
    }
  }
  const cellStart = new Uint32Array(cellTotal);
  let emptyCells = 0, maxItems = 0;
  for (let c = 0, s = 0; c < cellTotal; c++) {
    cellStart[c] = s;
    s += counts[c]!;
    if (counts[c] === 0) emptyCells++;
    maxItems = Math.max(maxItems, counts[c]!);
  }
  const items = new Uint32Array(itemTotal);
  const fill = cellStart.slice();
  for (let i = 0; i < itemTotal; i++) items[fill[pairCells[i]!]!++] = pairLeaves[i]!;
  const nonEmpty = cellTotal - emptyCells;
  return {
    lo, hi, cellSize: cs, dims, cellStart, cellCount: counts, items, leafToSource,
    stats: {
      buildMs: performance.now() - t0,
      source: res.source,
      cells: cellTotal,
      emptyCells,
      items: itemTotal,
      meanItems: nonEmpty > 0 ? itemTotal / nonEmpty : 0,
      maxItems,
      primitives: leafToSource.length,
    },
  };
}

/** One line of the grid's figures, for `lantern bvh-stats` and `info`. */
export function describeGrid(grid: Grid): string {
  const s = grid.stats;
  const pct = s.cells > 0 ? ((100 * s.emptyCells) / s.cells).toFixed(1) : '0';
  return `grid (${s.source}): ${grid.dims.join(' × ')} = ${s.cells} cells of ${grid.cellSize.map((c) => +c.toPrecision(4)).join(' × ')}, ${pct} % empty; ${s.items} entries for ${s.primitives} primitives, per non-empty cell mean ${s.meanItems.toFixed(2)}, max ${s.maxItems}; built in ${s.buildMs.toFixed(1)} ms`;
}

/**
 * The walk: calls `visit(cell, tExit)` for each cell the ray crosses in (t0, ...), in order, until it
 * returns true or the ray leaves the grid. Cell indices from the entry point, then one step at a time
 * along the axis whose next cell boundary is nearest (ties: x, then y, then z); each boundary's t is
 * computed afresh from its plane rather than accumulated, so long walks do not drift. Returns the
 * number of cells visited. As walk_grid in shaders/scene/grid.wgsl.
 */
function walk(grid: Grid, r: ReturnType<typeof prepareRay>, tBest: number, visit: (cell: number, tExit: number) => boolean): number {
  const { lo, hi, cellSize: cs, dims } = grid;
  const o = [r.ox, r.oy, r.oz], d = [r.dx, r.dy, r.dz], inv = [r.ix, r.iy, r.iz];
  let tNear = r.tMin, tFar = tBest;
  for (let k = 0; k < 3; k++) {
    const a = (lo[k]! - o[k]!) * inv[k]!, b = (hi[k]! - o[k]!) * inv[k]!;
    tNear = Math.max(tNear, Math.min(a, b));
    tFar = Math.min(tFar, Math.max(a, b));
  }
  if (!(tNear <= tFar)) return 0;
  const cell = [0, 0, 0], step = [0, 0, 0], next = [0, 0, 0];
  for (let k = 0; k < 3; k++) {
    const p = o[k]! + tNear * d[k]!;
    cell[k] = Math.min(dims[k]! - 1, Math.max(0, Math.floor((p - lo[k]!) / cs[k]!)));
    step[k] = inv[k]! >= 0 ? 1 : -1;
    next[k] = (lo[k]! + (cell[k]! + (step[k]! > 0 ? 1 : 0)) * cs[k]! - o[k]!) * inv[k]!;
  }
  let visited = 0;
  for (;;) {
    visited++;
    const axis = next[0]! <= next[1]! ? (next[0]! <= next[2]! ? 0 : 2) : next[1]! <= next[2]! ? 1 : 2;
    if (visit(cell[0]! + dims[0] * (cell[1]! + dims[1] * cell[2]!), next[axis]!)) return visited;
    cell[axis]! += step[axis]!;
    if (cell[axis]! < 0 || cell[axis]! >= dims[axis]!) return visited;
    next[axis] = (lo[axis]! + (cell[axis]! + (step[axis]! > 0 ? 1 : 0)) * cs[axis]! - o[axis]!) * inv[axis]!;
  }
}

/** Leaves a walk remembers having tested (GRID_MAILBOX_SIZE in shaders/scene/grid.wgsl). */
export const GRID_MAILBOX_SIZE = 8;

/**
 * The mailbox of Amanatides & Woo: a primitive spanning several cells is tested once per ray. A ring
 * of the last GRID_MAILBOX_SIZE leaves tested; skipping a repeat changes nothing (its test against a
 * smaller best distance can only miss again, and a hit is already the best), so this saves work only.
 */
class Mailbox {
  private readonly ring = new Int32Array(GRID_MAILBOX_SIZE).fill(-1);
  private next = 0;
  /** Whether `leaf` was tested already; if not, remembers it. */
  seen(leaf: number): boolean {
    for (let k = 0; k < GRID_MAILBOX_SIZE; k++) if (this.ring[k] === leaf) return true;
    this.ring[this.next] = leaf;
    this.next = (this.next + 1) % GRID_MAILBOX_SIZE;
    return false;
  }
}

/**
 * Closest hit through the grid, with the counts of traverse.ts (nodesVisited: cells visited, 0 when
 * the ray misses the grid box; trianglesTested: primitive tests run). A cell's primitives are tested
 * against the best distance so far, and the walk stops once that distance lies within the current
 * cell (a primitive that spans cells may be hit beyond the cell it was tested in; then the walk goes
 * on until it reaches the cell of that hit).
 */
export function traceGrid(grid: Grid, positions: Float32Array, ray: Ray, kinds?: Uint8Array): ClosestTrace {
  const { cellStart, cellCount, items, leafToSource } = grid;
  const state = new Closest(positions, kinds, leafToSource, prepareRay(ray));
  const box = new Mailbox();
  state.nodesVisited = walk(grid, state.r, state.tBest, (cell, tExit) => {
    const first = cellStart[cell]!, end = first + cellCount[cell]!;
    for (let i = first; i < end; i++) {
      const leaf = items[i]!;
      if (!box.seen(leaf)) state.test(leaf);
    }
    return state.tBest <= tExit;
  });
  return state.result();
}

/** Any hit at tMin < t < tMax through the grid (shadow rays): the first accepted test ends the walk. */
export function traceGridAny(grid: Grid, positions: Float32Array, ray: Ray, kinds?: Uint8Array): AnyTrace {
  const { cellStart, cellCount, items, leafToSource } = grid;
  const state = new Closest(positions, kinds, leafToSource, prepareRay(ray));
  const box = new Mailbox();
  let found = false;
  state.nodesVisited = walk(grid, state.r, state.r.tMax, (cell, tExit) => {
    const first = cellStart[cell]!, end = first + cellCount[cell]!;
    for (let i = first; i < end; i++) {
      const leaf = items[i]!;
      if (!box.seen(leaf) && state.testAny(leaf)) {
        found = true;
        return true;
      }
    }
    return state.r.tMax <= tExit;
  });
  return state.anyResult(found);
}
