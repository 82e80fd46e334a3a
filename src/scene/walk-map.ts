/**
 * A 2.5D walk map: the floor plan of a level as line segments in the horizontal (x, z) plane, each
 * between two sectors with a floor and ceiling height, and the rules of walking on it: a body of
 * some radius and height stays at eye height above the floor of the sector it stands in, is stopped
 * by walls, by steps higher than `stepHeight` and by openings lower than `bodyHeight`, and slides
 * along whatever stops it. Doom maps produce one (loaders/doom/walk-map.ts); a viewer walks on it.
 *
 * World coordinates, y up. Pure: no DOM, no GPU.
 */

export interface WalkMap {
  /** Four numbers per line: x0, z0, x1, z1. */
  readonly lines: Float32Array;
  /**
   * Two sector indices per line: the sector on the side where cross((x1−x0, z1−z0), (px−x0, pz−z0))
   * is positive (seen from +y with x right and z down, the left side), then the other side's; −1
   * where there is no sector (a one-sided wall).
   */
  readonly lineSectors: Int32Array;
  /** 1 where a line blocks whatever the heights on both sides (Doom's "impassable" flag). */
  readonly lineBlocks: Uint8Array;
  /** Floor and ceiling height of each sector. */
  readonly floors: Float32Array;
  readonly ceilings: Float32Array;
  /** The walker's eye above the floor, the highest step it climbs, its height and radius (world units). */
  readonly eyeHeight: number;
  readonly stepHeight: number;
  readonly bodyHeight: number;
  readonly radius: number;
}

export const NO_SECTOR = -1;

export function lineCount(map: WalkMap): number {
  return map.lines.length / 4;
}

/**
 * The sector containing (x, z), or NO_SECTOR outside the map: the side of the nearest line crossed
 * by a ray from the point toward +x (correct for closed sectors, nested ones included).
 */
export function sectorAt(map: WalkMap, x: number, z: number): number {
  const L = map.lines;
  let best = Infinity;
  let sector = NO_SECTOR;
  for (let i = 0; i < L.length; i += 4) {
    const x0 = L[i]!, z0 = L[i + 1]!, x1 = L[i + 2]!, z1 = L[i + 3]!;
    if (z0 > z === z1 > z) continue;
    const xi = x0 + ((z - z0) * (x1 - x0)) / (z1 - z0);
    if (xi < x || xi >= best) continue;
    best = xi;
    const cross = (x1 - x0) * (z - z0) - (z1 - z0) * (x - x0);
    sector = map.lineSectors[(i / 4) * 2 + (cross > 0 ? 0 : 1)]!;
  }
  return sector;
}

/** Whether line `i` stops a walker whose feet are at height `floor`. */
export function lineBlocksAt(map: WalkMap, i: number, floor: number): boolean {
  if (map.lineBlocks[i]) return true;
  const a = map.lineSectors[i * 2]!, b = map.lineSectors[i * 2 + 1]!;
  if (a === NO_SECTOR || b === NO_SECTOR) return true;
  const highFloor = Math.max(map.floors[a]!, map.floors[b]!);
  const lowCeiling = Math.min(map.ceilings[a]!, map.ceilings[b]!);
  return highFloor - floor > map.stepHeight || lowCeiling - Math.max(highFloor, floor) < map.bodyHeight;
}

export interface WalkPosition {
  readonly x: number;
  readonly z: number;
  readonly sector: number;
}

/** Where a walker standing at `from` ends up after trying to move by (dx, dz): it slides along what stops it. */
export function moveWalker(map: WalkMap, from: WalkPosition, dx: number, dz: number): WalkPosition {
  const r = map.radius;
  // Sub-steps of at most half the radius, so that no wall is jumped over.
  const steps = Math.max(1, Math.ceil(Math.hypot(dx, dz) / (r * 0.5)));
  let at = from;
  for (let s = 0; s < steps; s++) {
    const floor = at.sector === NO_SECTOR ? -Infinity : map.floors[at.sector]!;
    let x = at.x + dx / steps, z = at.z + dz / steps;
    // Push out of every blocking line within the radius; a few rounds settle corners.
    for (let round = 0; round < 4; round++) {
      let pushed = false;
      const L = map.lines;
      for (let i = 0; i < L.length; i += 4) {
        const x0 = L[i]!, z0 = L[i + 1]!, ex = L[i + 2]! - x0, ez = L[i + 3]! - z0;
        const len2 = ex * ex + ez * ez;
        const t = len2 > 0 ? Math.min(1, Math.max(0, ((x - x0) * ex + (z - z0) * ez) / len2)) : 0;
        const qx = x0 + t * ex, qz = z0 + t * ez;
        const d = Math.hypot(x - qx, z - qz);
        if (d >= r || !lineBlocksAt(map, i / 4, floor)) continue;
        // Away from the line, toward the side the walker came from when it stands on the line itself.
        let nx = x - qx, nz = z - qz;
        if (d < 1e-6) {
          const side = ex * (at.z - z0) - ez * (at.x - x0) > 0 ? 1 : -1;
          nx = -ez * side;
          nz = ex * side;
        }
        const n = Math.hypot(nx, nz) || 1;
        x = qx + (nx / n) * r * 1.0001;
        z = qz + (nz / n) * r * 1.0001;
        pushed = true;
      }
      if (!pushed) break;
    }
    const sector = sectorAt(map, x, z);
    // Never leave the map: stay put when the step ends outside every sector.
    if (sector === NO_SECTOR && at.sector !== NO_SECTOR) break;
    at = { x, z, sector };
  }
  return at;
}

/** Eye height for a walker in `sector`: eye height above the floor, kept under the ceiling. */
export function eyeLevel(map: WalkMap, sector: number): number | undefined {
  if (sector === NO_SECTOR) return undefined;
  const floor = map.floors[sector]!;
  return Math.max(floor + 1, Math.min(floor + map.eyeHeight, map.ceilings[sector]! - 4));
}
