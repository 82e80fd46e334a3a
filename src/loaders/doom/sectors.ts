/**
 * Floors and ceilings: each sector's area, rebuilt from its linedefs and triangulated.
 *
 * Doom itself never stores sector polygons: the renderer fills floors and ceilings as visplanes
 * between walls, and the node builder's subsectors are only convex pieces of the BSP split. So we
 * rebuild them (https://doomwiki.org/wiki/Sector): every sidedef that names a sector is a piece of
 * that sector's boundary, with the sector on its side of the line. Directing each piece so that the
 * sector lies on its left, the pieces chain into closed loops: outer boundaries run
 * counter-clockwise, holes (pillars, other sectors inside) clockwise. Each outer boundary with the
 * holes inside it is triangulated by earcut.
 *
 * Real maps contain mistakes (https://doomwiki.org/wiki/Unclosed_sector): boundaries with gaps,
 * lines listed twice, zero-length lines. Those are repaired where the intent is clear and reported
 * through `warn`; a sector that still cannot be triangulated is reported as a failure.
 */
import earcut from 'earcut';
import { limits } from '../../budgets.ts';
import { NO_SIDEDEF, type DoomMap } from './map-types.ts';

/** One piece of a sector: a counter-clockwise outer ring and the clockwise rings of its holes. */
export interface SectorPolygon {
  /** x, y pairs in map coordinates. */
  readonly outer: readonly number[];
  readonly holes: readonly (readonly number[])[];
}

export interface SectorShape {
  readonly sector: number;
  /** Triangle corners in map coordinates, x, y pairs. */
  readonly vertices: Float64Array;
  /** Three indices into `vertices` per triangle, counter-clockwise seen from above. */
  readonly indices: Uint32Array;
  /** Sum of the triangles' areas, in square map units. */
  readonly area: number;
  readonly polygons: readonly SectorPolygon[];
}

export interface SectorFailure {
  readonly sector: number;
  readonly reason: string;
}

export interface SectorShapes {
  /** One per sector, in sector order; a sector no sidedef names has no triangles. */
  readonly shapes: readonly SectorShape[];
  readonly failures: readonly SectorFailure[];
}

/**
 * How far apart the loose ends of an unclosed boundary may be for us to join them with a straight
 * edge. Editors leave gaps of a few units (vertices that should have been merged) and single lines
 * whose sidedef names the wrong sector (a gap one line long); much larger gaps are more likely a
 * stray line than a missing one, so those chains are dropped instead.
 */
export const GAP_TOLERANCE = 256;

/** Relative mismatch between triangulated and polygon area above which earcut is deemed to have failed. */
const AREA_TOLERANCE = 1e-3;

interface Edge {
  readonly from: number;
  readonly to: number;
  /** The linedef it comes from, or -1 for an edge we added to close a gap. */
  readonly line: number;
}

export function buildSectorShapes(map: DoomMap, warn: (message: string) => void = () => {}): SectorShapes {
  const points = new PointTable();
  const edgesBySector = collectEdges(map, points, warn);
  const shapes: SectorShape[] = [];
  const failures: SectorFailure[] = [];
  for (let sector = 0; sector < map.sectors.length; sector++) {
    const edges = edgesBySector[sector] ?? [];
    // No edges at all: an unused sector, or one drawn only with self-referencing lines (a mapping
    // trick whose area belongs to the sector around it). Nothing to build, nothing wrong.
    let polygons: SectorPolygon[] = [];
    let shape: SectorShape;
    const work = new SectorWork(limits().sectorWork);
    try {
      if (edges.length > 0) {
        const say = (m: string) => warn(`sector ${sector}: ${m}`);
        polygons = nestLoops(traceLoops(repairChains(edges, points, say, work), points, say), say, work);
        if (polygons.length === 0) failures.push({ sector, reason: `its ${edges.length} boundary lines enclose no area` });
      }
      shape = triangulate(sector, polygons, work);
    } catch (e) {
      if (!(e instanceof SectorOverBudget)) throw e;
      failures.push({ sector, reason: `rebuilding its ${edges.length} boundary lines takes more than sectorWork=${work.limit} steps (raise it with --limits sectorWork=N)` });
      shapes.push({ sector, vertices: new Float64Array(0), indices: new Uint32Array(0), area: 0, polygons: [] });
      continue;
    }
    const expected = polygons.reduce((sum, p) => sum + ringArea(p.outer) + p.holes.reduce((s, h) => s + ringArea(h), 0), 0);
    if (!(Math.abs(shape.area - expected) <= AREA_TOLERANCE * Math.abs(expected))) {
      failures.push({ sector, reason: `its triangles cover ${fmt(shape.area)} of its ${fmt(expected)} square units` });
    }
    shapes.push(shape);
  }
  return { shapes, failures };
}

/** The sector whose floor contains map point (x, y), or undefined when none does. */
export function sectorAt(shapes: SectorShapes, x: number, y: number): number | undefined {
  for (const s of shapes.shapes) {
    const v = s.vertices;
    for (let t = 0; t < s.indices.length; t += 3) {
      const a = 2 * s.indices[t]!, b = 2 * s.indices[t + 1]!, c = 2 * s.indices[t + 2]!;
      // Counter-clockwise triangles: inside (or on an edge) when left of all three edges.
      if (
        cross(v[a]!, v[a + 1]!, v[b]!, v[b + 1]!, x, y) >= 0 &&
        cross(v[b]!, v[b + 1]!, v[c]!, v[c + 1]!, x, y) >= 0 &&
        cross(v[c]!, v[c + 1]!, v[a]!, v[a + 1]!, x, y) >= 0
      ) {
        return s.sector;
      }
    }
  }
  return undefined;
}

/** Twice the signed area of triangle (a, b, p): positive when p lies left of a → b. */
function cross(ax: number, ay: number, bx: number, by: number, px: number, py: number): number {
  return (bx - ax) * (py - ay) - (by - ay) * (px - ax);
}

/**
 * Map vertices merged by position: maps often hold two vertices at one spot, and a boundary that
 * passes through either is still closed there.
 */
class PointTable {
  readonly xs: number[] = [];
  readonly ys: number[] = [];
  private readonly ids = new Map<string, number>();

  id(x: number, y: number): number {
    const key = `${x},${y}`;
    let id = this.ids.get(key);
    if (id === undefined) {
      id = this.xs.length;
      this.ids.set(key, id);
      this.xs.push(x);
      this.ys.push(y);
    }
    return id;
  }

  describe(id: number): string {
    return `(${this.xs[id]}, ${this.ys[id]})`;
  }
}

/**
 * Every sector's boundary edges, directed with the sector on the left. The front sidedef lies to the
 * right of v1 → v2 (https://doomwiki.org/wiki/Linedef), so its sector gets v2 → v1; the back
 * sidedef's sector gets v1 → v2. A line with one sector on both sides separates nothing (a
 * self-referencing sector); so do two lines over the same vertices with the sector on both sides,
 * which cancel. An edge listed twice is kept once.
 */
function collectEdges(map: DoomMap, points: PointTable, warn: (m: string) => void): Edge[][] {
  const bySector = new Map<number, Map<string, Edge>>();
  const sectorOf = (side: number, line: number): number | undefined => {
    if (side === NO_SIDEDEF) return undefined;
    const sidedef = map.sidedefs[side];
    if (!sidedef) return void warn(`linedef ${line} names sidedef ${side}, which does not exist`);
    if (!map.sectors[sidedef.sector]) return void warn(`sidedef ${side} names sector ${sidedef.sector}, which does not exist`);
    return sidedef.sector;
  };
  const add = (sector: number, edge: Edge) => {
    let edges = bySector.get(sector);
    if (!edges) bySector.set(sector, (edges = new Map()));
    const key = `${edge.from}>${edge.to}`;
    const reverse = `${edge.to}>${edge.from}`;
    if (edges.has(key)) warn(`sector ${sector}: linedef ${edge.line} repeats linedef ${edges.get(key)!.line}; using it once`);
    else if (edges.has(reverse)) edges.delete(reverse);
    else edges.set(key, edge);
  };
  map.linedefs.forEach((line, index) => {
    const v1 = map.vertices[line.v1];
    const v2 = map.vertices[line.v2];
    if (!v1 || !v2) return warn(`linedef ${index} names a vertex that does not exist (${line.v1}, ${line.v2})`);
    const a = points.id(v1.x, v1.y);
    const b = points.id(v2.x, v2.y);
    if (a === b) return warn(`linedef ${index} has zero length; ignored`);
    const front = sectorOf(line.front, index);
    const back = sectorOf(line.back, index);
    if (front !== undefined && front === back) return;
    if (front !== undefined) add(front, { from: b, to: a, line: index });
    if (back !== undefined) add(back, { from: a, to: b, line: index });
  });
  const out: Edge[][] = [];
  for (const [sector, edges] of bySector) out[sector] = [...edges.values()];
  return out;
}

/**
 * A closed boundary enters and leaves every vertex equally often. Where it does not, chains end
 * loose: join each loose end to the nearest loose start within GAP_TOLERANCE (nearest pairs first),
 * then drop what still dangles, repeatedly, since dropping one line can leave another loose.
 *
 * Candidate pairs come from a grid of GAP_TOLERANCE-sized cells (only the 3×3 cells around an end
 * can hold a start close enough), and the dangling lines are peeled off with a work list, so a
 * sector with 20,000 loose segments costs about its size, not its size squared; each candidate
 * pair is charged to the sector's work budget.
 */
function repairChains(edges: readonly Edge[], points: PointTable, say: (m: string) => void, work: SectorWork): Edge[] {
  const balance = new Map<number, number>(); // out − in
  for (const e of edges) {
    balance.set(e.from, (balance.get(e.from) ?? 0) + 1);
    balance.set(e.to, (balance.get(e.to) ?? 0) - 1);
  }
  // Loose starts and ends with their multiplicity, and each one's rank (the order ties are broken in).
  const startsLeft = new Map<number, number>();
  const endsLeft = new Map<number, number>();
  for (const [v, b] of balance) {
    if (b > 0) startsLeft.set(v, b);
    else if (b < 0) endsLeft.set(v, -b);
  }
  if (startsLeft.size === 0) return [...edges];

  const cell = (x: number, y: number) => `${Math.floor(x / GAP_TOLERANCE)},${Math.floor(y / GAP_TOLERANCE)}`;
  const grid = new Map<string, number[]>();
  const startRank = new Map<number, number>();
  for (const start of startsLeft.keys()) {
    startRank.set(start, startRank.size);
    const key = cell(points.xs[start]!, points.ys[start]!);
    const list = grid.get(key);
    if (list) list.push(start);
    else grid.set(key, [start]);
  }
  const result = [...edges];
  // Candidate pairs in parallel arrays (a sector near its work budget has millions of them).
  const pairEnd: number[] = [];
  const pairStart: number[] = [];
  const pairD: number[] = [];
  const pairRank: number[] = [];
  let endRank = 0;
  for (const end of endsLeft.keys()) {
    const [ex, ey] = [points.xs[end]!, points.ys[end]!];
    const [cx, cy] = [Math.floor(ex / GAP_TOLERANCE), Math.floor(ey / GAP_TOLERANCE)];
    for (let dx = -1; dx <= 1; dx++) {
      for (let dy = -1; dy <= 1; dy++) {
        const list = grid.get(`${cx + dx},${cy + dy}`);
        if (!list) continue;
        work.spend(list.length);
        for (const start of list) {
          const d = Math.hypot(ex - points.xs[start]!, ey - points.ys[start]!);
          if (d <= GAP_TOLERANCE) {
            pairEnd.push(end);
            pairStart.push(start);
            pairD.push(d);
            pairRank.push(endRank * startRank.size + startRank.get(start)!);
          }
        }
      }
    }
    endRank++;
  }
  // Nearest first; equal gaps in the order of the ends, then the starts, as they were first seen.
  const order = Uint32Array.from(pairD.keys()).sort((p, q) => pairD[p]! - pairD[q]! || pairRank[p]! - pairRank[q]!);
  let startsOpen = 0;
  for (const n of startsLeft.values()) startsOpen += n;
  for (const p of order) {
    const [end, start] = [pairEnd[p]!, pairStart[p]!];
    const e = endsLeft.get(end)!;
    const s = startsLeft.get(start)!;
    if (e === 0 || s === 0) continue;
    endsLeft.set(end, e - 1);
    startsLeft.set(start, s - 1);
    startsOpen--;
    result.push({ from: end, to: start, line: -1 });
    say(`unclosed boundary: joined ${points.describe(end)} to ${points.describe(start)} (a gap of ${fmt(pairD[p]!)} units)`);
  }
  if (startsOpen === 0) return result;

  // Drop dangling lines: those leaving a vertex nothing enters, or entering one nothing leaves.
  // Peeled with a work list: removing a line can only strand the lines at its two vertices.
  const ins = new Map<number, number>();
  const outs = new Map<number, number>();
  const leaving = new Map<number, number[]>();
  const entering = new Map<number, number[]>();
  result.forEach((e, i) => {
    outs.set(e.from, (outs.get(e.from) ?? 0) + 1);
    ins.set(e.to, (ins.get(e.to) ?? 0) + 1);
    (leaving.get(e.from) ?? leaving.set(e.from, []).get(e.from)!).push(i);
    (entering.get(e.to) ?? entering.set(e.to, []).get(e.to)!).push(i);
  });
  const alive = new Uint8Array(result.length).fill(1);
  const queue: number[] = [];
  result.forEach((e, i) => {
    if (!ins.get(e.from) || !outs.get(e.to)) queue.push(i);
  });
  while (queue.length > 0) {
    const i = queue.pop()!;
    if (!alive[i]) continue;
    const e = result[i]!;
    if (ins.get(e.from)! > 0 && outs.get(e.to)! > 0) continue;
    alive[i] = 0;
    work.spend(1);
    const outsLeft = outs.get(e.from)! - 1;
    const insLeft = ins.get(e.to)! - 1;
    outs.set(e.from, outsLeft);
    ins.set(e.to, insLeft);
    if (outsLeft === 0) for (const j of entering.get(e.from) ?? []) if (alive[j]) queue.push(j);
    if (insLeft === 0) for (const j of leaving.get(e.to) ?? []) if (alive[j]) queue.push(j);
  }
  const kept = result.filter((_, i) => alive[i]);
  const dropped = result.filter((_, i) => !alive[i]).map((e) => e.line);
  if (dropped.length > 0) say(`unclosed boundary: dropped dangling linedef${dropped.length > 1 ? 's' : ''} ${listSome(dropped)}`);
  return kept;
}

/** At most 20 numbers, then how many more: a message quoting 20,000 linedefs helps nobody. */
function listSome(items: readonly number[]): string {
  return items.length <= 20 ? items.join(', ') : `${items.slice(0, 20).join(', ')} and ${items.length - 20} more`;
}

/**
 * The work one sector's repair and nesting may do (candidate pairs, lines peeled, ring vertices
 * tested). Past the limit the sector is reported as failed and the rest of the map still loads.
 */
class SectorWork {
  private spent = 0;
  constructor(readonly limit: number) {}
  spend(n: number): void {
    this.spent += n;
    if (this.spent > this.limit) throw new SectorOverBudget();
  }
}

class SectorOverBudget extends Error {}

/**
 * Chains edges into closed loops. At a vertex where several boundaries meet (two rooms of one sector
 * touching at a corner, a pillar touching a wall), the next edge is the first one clockwise from
 * the way we came in: the sharpest left turn, which keeps to the region on our left and so never
 * crosses into a neighbouring loop. Whenever the walk returns to a vertex already on its path, the
 * part since then is a closed loop and is cut off.
 */
function traceLoops(edges: readonly Edge[], points: PointTable, say: (m: string) => void): number[][] {
  const outgoing = new Map<number, number[]>();
  edges.forEach((e, i) => {
    const list = outgoing.get(e.from);
    if (list) list.push(i);
    else outgoing.set(e.from, [i]);
  });
  const used = new Array<boolean>(edges.length).fill(false);
  const angle = (from: number, to: number) => Math.atan2(points.ys[to]! - points.ys[from]!, points.xs[to]! - points.xs[from]!);
  const loops: number[][] = [];

  for (let first = 0; first < edges.length; first++) {
    if (used[first]) continue;
    used[first] = true;
    const path = [first];
    const onPath = new Map<number, number>([[edges[first]!.from, 0]]); // vertex → index of the path edge leaving it
    while (path.length > 0) {
      const last = edges[path[path.length - 1]!]!;
      const v = last.to;
      const at = onPath.get(v);
      if (at !== undefined) {
        const loop = path.splice(at);
        for (const i of loop) onPath.delete(edges[i]!.from);
        loops.push(loop.map((i) => edges[i]!.from));
        continue;
      }
      const back = angle(v, last.from);
      let best = -1;
      let bestTurn = Infinity;
      for (const i of outgoing.get(v) ?? []) {
        if (used[i]) continue;
        // Clockwise sweep from the reversed incoming direction, in (0, 2π]; going straight back is last.
        let turn = (back - angle(v, edges[i]!.to)) % (2 * Math.PI);
        if (turn <= 0) turn += 2 * Math.PI;
        if (turn < bestTurn) [best, bestTurn] = [i, turn];
      }
      if (best < 0) {
        const lines = path.map((i) => edges[i]!.line).filter((l) => l >= 0);
        say(`unclosed boundary: linedefs ${listSome(lines)} lead nowhere; dropped`);
        break;
      }
      used[best] = true;
      onPath.set(v, path.length);
      path.push(best);
    }
  }
  return loops.map((loop) => loop.flatMap((v) => [points.xs[v]!, points.ys[v]!]));
}

/**
 * Sorts loops into polygons: counter-clockwise loops are outer boundaries, clockwise ones are holes,
 * and a hole belongs to the smallest outer boundary around it (a sector may surround a pillar that
 * surrounds another part of the same sector). A hole nothing surrounds is an outer boundary drawn
 * with its sidedefs on the wrong side; we flip it.
 */
function nestLoops(loops: readonly number[][], say: (m: string) => void, work: SectorWork): SectorPolygon[] {
  const outers: Array<{ ring: number[]; area: number; holes: number[][] }> = [];
  const holes: number[][] = [];
  for (const ring of loops) {
    const area = ringArea(ring);
    // Integer vertices give areas in multiples of 1/2: anything smaller is a degenerate sliver.
    if (Math.abs(area) < 0.25) continue;
    if (area > 0) outers.push({ ring, area, holes: [] });
    else holes.push(ring);
  }
  outers.sort((a, b) => a.area - b.area);
  for (const hole of holes) {
    const [px, py] = probeOutside(hole);
    const parent = outers.find((o) => {
      work.spend(o.ring.length / 2);
      return pointInRing(o.ring, px, py);
    });
    if (parent) parent.holes.push(hole);
    else {
      say(`a boundary at (${hole[0]}, ${hole[1]}) runs clockwise with nothing around it; treated as an outer boundary`);
      const ring = reverseRing(hole);
      outers.push({ ring, area: ringArea(ring), holes: [] });
    }
  }
  return outers.map((o) => ({ outer: o.ring, holes: o.holes }));
}

/**
 * A point just outside a hole: a hair to the left of the middle of its longest edge, where the
 * sector is. Testing that point, rather than a vertex of the hole, still works when the hole touches
 * its outer boundary at a vertex.
 */
function probeOutside(ring: readonly number[]): [number, number] {
  let best = 0;
  let bestLength = -1;
  const n = ring.length / 2;
  for (let i = 0; i < n; i++) {
    const j = (i + 1) % n;
    const length = Math.hypot(ring[2 * j]! - ring[2 * i]!, ring[2 * j + 1]! - ring[2 * i + 1]!);
    if (length > bestLength) [best, bestLength] = [i, length];
  }
  const j = (best + 1) % n;
  const [ax, ay, bx, by] = [ring[2 * best]!, ring[2 * best + 1]!, ring[2 * j]!, ring[2 * j + 1]!];
  const e = 1e-3 / bestLength;
  return [(ax + bx) / 2 - (by - ay) * e, (ay + by) / 2 + (bx - ax) * e];
}

/** Even-odd rule. */
function pointInRing(ring: readonly number[], x: number, y: number): boolean {
  let inside = false;
  const n = ring.length / 2;
  for (let i = 0, j = n - 1; i < n; j = i++) {
    const [xi, yi, xj, yj] = [ring[2 * i]!, ring[2 * i + 1]!, ring[2 * j]!, ring[2 * j + 1]!];
    if (yi > y !== yj > y && x < ((xj - xi) * (y - yi)) / (yj - yi) + xi) inside = !inside;
  }
  return inside;
}

/** Signed area (shoelace): positive for counter-clockwise rings. */
export function ringArea(ring: readonly number[]): number {
  let twice = 0;
  const n = ring.length / 2;
  for (let i = 0, j = n - 1; i < n; j = i++) twice += ring[2 * j]! * ring[2 * i + 1]! - ring[2 * i]! * ring[2 * j + 1]!;
  return twice / 2;
}

function reverseRing(ring: readonly number[]): number[] {
  const out: number[] = [];
  for (let i = ring.length - 2; i >= 0; i -= 2) out.push(ring[i]!, ring[i + 1]!);
  return out;
}

function triangulate(sector: number, polygons: readonly SectorPolygon[], work: SectorWork): SectorShape {
  const vertices: number[] = [];
  const indices: number[] = [];
  let area = 0;
  for (const p of polygons) {
    const base = vertices.length / 2;
    const holeStarts: number[] = [];
    // Appended element by element: push(...ring) with a 65k-vertex ring overflows the call stack.
    const coords = p.outer.slice();
    for (const h of p.holes) {
      holeStarts.push(coords.length / 2);
      for (const c of h) coords.push(c);
    }
    const expected = ringArea(p.outer) + p.holes.reduce((sum, h) => sum + ringArea(h), 0);
    // earcut bridges each hole to the outer ring by a scan of the ring: about vertices × holes steps.
    work.spend((coords.length / 2) * (holeStarts.length + 1));
    const piece = earcutChecked(coords, holeStarts, expected);
    area += piece.area;
    for (const i of piece.triangles) indices.push(base + i);
    for (const c of coords) vertices.push(c);
  }
  return { sector, vertices: new Float64Array(vertices), indices: new Uint32Array(indices), area, polygons };
}

/**
 * Quarter turns (exact for any coordinates) tried in turn. earcut joins each hole to the outer ring
 * by a bridge it finds looking left (−x) from the hole's leftmost vertex, and with many holes a
 * bridge occasionally crosses another, which makes triangles cover a hole (E1M4 of Freedoom has such
 * a sector). Turning the polygon makes earcut look in another direction and build other bridges.
 */
const TURNS: ReadonlyArray<(x: number, y: number) => [number, number]> = [
  (x, y) => [x, y],
  (x, y) => [-y, x],
  (x, y) => [-x, -y],
  (x, y) => [y, -x],
];

/**
 * earcut's triangles, counter-clockwise, from the first quarter turn whose triangles cover the
 * polygon's area (or else the closest attempt).
 */
function earcutChecked(coords: readonly number[], holeStarts: readonly number[], expected: number): { triangles: number[]; area: number } {
  let best = { triangles: [] as number[], area: 0 };
  for (const turn of TURNS) {
    const turned: number[] = [];
    for (let i = 0; i < coords.length; i += 2) {
      const [x, y] = turn(coords[i]!, coords[i + 1]!);
      turned.push(x, y);
    }
    const tris = earcut(turned, holeStarts);
    const triangles: number[] = [];
    let area = 0;
    for (let t = 0; t < tris.length; t += 3) {
      let [a, b, c] = [tris[t]!, tris[t + 1]!, tris[t + 2]!];
      const twice = cross(coords[2 * a]!, coords[2 * a + 1]!, coords[2 * b]!, coords[2 * b + 1]!, coords[2 * c]!, coords[2 * c + 1]!);
      if (twice < 0) [b, c] = [c, b];
      area += Math.abs(twice) / 2;
      triangles.push(a, b, c);
    }
    if (Math.abs(area - expected) <= AREA_TOLERANCE * expected) return { triangles, area };
    if (Math.abs(area - expected) < Math.abs(best.area - expected)) best = { triangles, area };
  }
  return best;
}

function fmt(n: number): string {
  return Number.isInteger(n) ? String(n) : n.toFixed(1);
}
