/**
 * The renderer's side of per-tile distance culling (scene/tile-culling.ts; Lantern issue #12 §4): one
 * prepared scene per walkable tile, each with its own BVH over the triangles within the culling
 * distance, and the choice of which to trace as the camera moves. Not yet connected to `Renderer`:
 * the wiring (behind a `tileCulling` setting, off until measured) is a swap of the geometry buffers
 * (TILE_SWAP_BUFFERS and the triangle attributes: materials, textures and the environment are shared
 * with the full scene, packed once) followed by `applySceneUpdate(selection.catchUp)`; the grid and
 * distance come from `defaultTileCulling(scene)` (2 m tiles, 10 m), and each world step's update goes
 * to `noteUpdate` as well as to the renderer.
 *
 * Precomputation reuses the full scene's packed materials and environment, so a tile costs only its
 * geometry (flatten, BVH build, geometry packing). Pure (no GPU): it runs in a worker or a test.
 */
import { buildGrid } from '../bvh/grid.ts';
import { buildWideBvh } from '../bvh/wide.ts';
import { buildLevels, buildStaticBvh } from '../bvh/levels.ts';
import { packGeometry } from '../gpu/pack/scene-pack.ts';
import type { Vec3 } from '../math/vec3.ts';
import { emptySceneUpdate, type InstancePose, type SceneUpdate } from '../scene/dynamics.ts';
import type { MaterialEdit } from '../scene/material-edit.ts';
import { cullSceneToTile, tileAt, walkableTiles, type TileGrid } from '../scene/tile-culling.ts';
import { flattenTriangles } from '../scene/triangles.ts';
import { GEOMETRY_BUFFERS, type PreparedScene } from './prepare.ts';

/** The group-0 buffers that differ between tiles (besides the triangle-attribute texture). */
export const TILE_SWAP_BUFFERS = GEOMETRY_BUFFERS;

/** Which prepared scene to trace from a camera position. */
export interface TileSelection {
  /** The walkable tile under the camera, or undefined (off the floor: the full scene). */
  readonly tile: number | undefined;
  readonly prepared: PreparedScene;
  /** The choice differs from the previous selection's (the first selection counts as changed). */
  readonly changed: boolean;
  /**
   * Everything that moved or changed since the scene was loaded (the latest pose of each instance,
   * weights of each mesh, edits of each material), to apply to `prepared` after a change (its geometry
   * is at rest); empty when nothing moved.
   */
  readonly catchUp: SceneUpdate;
}

export interface TileCullingStats {
  readonly tiles: number;
  /** Triangles of the full scene. */
  readonly fullTriangles: number;
  readonly meanTriangles: number;
  readonly maxTriangles: number;
  /** Bytes of the swapped geometry: the full scene's, and all tiles' together. */
  readonly fullGeometryBytes: number;
  readonly tilesGeometryBytes: number;
  /** Wall-clock milliseconds to cull, build and pack every tile. */
  readonly precomputeMs: number;
}

/** Bytes of a prepared scene's per-tile geometry (what a swap uploads). */
export function geometryBytes(p: PreparedScene): number {
  return TILE_SWAP_BUFFERS.reduce((n, name) => n + p.packed[name].byteLength, 0) + p.packed.triangleAttributes.data.byteLength;
}

/** One tile's prepared scene, sharing the full scene's packed materials and environment. */
export function prepareTile(full: PreparedScene, grid: TileGrid, tile: number, distance: number): PreparedScene {
  const t0 = performance.now();
  const scene = cullSceneToTile(full.scene, grid, tile, distance);
  const triangles = flattenTriangles(scene);
  const t1 = performance.now();
  const bvh = buildStaticBvh(scene, triangles);
  const levels = buildLevels(scene, bvh);
  const t2 = performance.now();
  // Traced as the full scene is (its pipelines walk a grid where it has one).
  const tileGrid = full.grid ? buildGrid(triangles.positions, triangles.kinds, bvh.triIndices, full.scene.tileGrid) : undefined;
  const tileWide = full.wide ? buildWideBvh(bvh, full.wide.layout) : undefined;
  const packed = packGeometry(scene, triangles, bvh, full.packed.packedMaterials, full.packed.environment, levels, tileGrid ?? tileWide);
  const t3 = performance.now();
  // The full scene's features: the pipelines compiled for it serve every tile (a superset is always correct).
  return { scene, triangles, bvh, ...(levels ? { levels } : {}), ...(tileGrid ? { grid: tileGrid } : {}), ...(tileWide ? { wide: tileWide } : {}), packed: { ...packed, features: full.packed.features }, timings: { flattenMs: t1 - t0, bvhMs: t2 - t1, packMs: t3 - t2 } };
}

export class TileCulledScenes {
  private last: number | undefined | null = null;
  private readonly poses = new Map<number, InstancePose>();
  private readonly weights = new Map<number, Float32Array>();
  private readonly edits = new Map<number, MaterialEdit>();

  constructor(
    readonly grid: TileGrid,
    /** The whole scene, traced where the camera stands on no walkable tile. */
    readonly full: PreparedScene,
    readonly tiles: ReadonlyMap<number, PreparedScene>,
    readonly precomputeMs = 0,
  ) {}

  /** Culls, builds and packs every walkable tile of `grid` (everything within `distance` of it, scene units). */
  static prepare(full: PreparedScene, grid: TileGrid, distance: number): TileCulledScenes {
    const t0 = performance.now();
    const tiles = new Map(walkableTiles(grid).map((tile) => [tile, prepareTile(full, grid, tile, distance)]));
    return new TileCulledScenes(grid, full, tiles, performance.now() - t0);
  }

  /** Remembers what a world step changed, for the catch-up of the next swap. */
  noteUpdate(update: SceneUpdate): void {
    for (const [id, pose] of update.instances) this.poses.set(id, { ...this.poses.get(id), ...pose });
    for (const [mesh, w] of update.morphWeights) this.weights.set(mesh, w);
    for (const [material, edit] of update.materials) this.edits.set(material, { ...this.edits.get(material), ...edit });
  }

  /** The prepared scene to trace with the camera at `position`. */
  select(position: Vec3): TileSelection {
    const tile = tileAt(this.grid, position[0], position[2]);
    const prepared = (tile === undefined ? undefined : this.tiles.get(tile)) ?? this.full;
    const chosen = prepared === this.full ? undefined : tile;
    const changed = this.last === null || this.last !== chosen;
    this.last = chosen;
    return { tile: chosen, prepared, changed, catchUp: this.catchUp() };
  }

  /** Everything the world changed since the scenes were prepared (what a swapped-in scene must apply). */
  catchUp(): SceneUpdate {
    return { ...emptySceneUpdate(), instances: new Map(this.poses), morphWeights: new Map(this.weights), materials: new Map(this.edits) };
  }

  stats(): TileCullingStats {
    const counts = [...this.tiles.values()].map((p) => p.triangles.count);
    return {
      tiles: counts.length,
      fullTriangles: this.full.triangles.count,
      meanTriangles: counts.reduce((a, b) => a + b, 0) / Math.max(1, counts.length),
      maxTriangles: Math.max(0, ...counts),
      fullGeometryBytes: geometryBytes(this.full),
      tilesGeometryBytes: [...this.tiles.values()].reduce((n, p) => n + geometryBytes(p), 0),
      precomputeMs: this.precomputeMs,
    };
  }
}
