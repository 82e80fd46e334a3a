/**
 * CPU costs of the two-level BVH, for `lantern bench` (docs/perf.md holds the H200 host's figures):
 * - a top-level rebuild over `n` instances (the scene's moving instances repeated over its bounds
 *   when it has fewer), as the renderer does it each frame something moves (bvh/tlas.ts);
 * - per moving mesh: refitting its bottom level after a morph against rebuilding it;
 * - the whole update of one frame in which every moving instance moves (updateGeometry's fast path).
 * Medians over `repeats` after a warm-up. Pure (no GPU).
 */
import { buildMeshBlas, refitMeshBlas } from '../bvh/levels.ts';
import { buildTlas } from '../bvh/tlas.ts';
import { seededRandom as makeRandom } from '../math/seeded-random.ts';
import { updateGeometry, type PreparedScene } from './prepare.ts';
import { median } from '../math/median.ts';

export interface LevelBenchmark {
  /** Instances the measured top level was built over, and the median milliseconds of a build. */
  readonly tlas: { readonly instances: number; readonly ms: number };
  /** Σ over the moving meshes: median ms of refitting every bottom level, and of rebuilding every one. */
  readonly blas: { readonly meshes: number; readonly triangles: number; readonly refitMs: number; readonly rebuildMs: number };
  /** Median ms of updateGeometry when every moving instance moves a little (top level, records, lights). */
  readonly updateMs: number;
}


function timed(repeats: number, f: () => void): number {
  for (let i = 0; i < 3; i++) f();
  const ms: number[] = [];
  for (let i = 0; i < repeats; i++) {
    const t0 = performance.now();
    f();
    ms.push(performance.now() - t0);
  }
  return median(ms);
}

export function benchmarkLevels(prepared: PreparedScene, tlasInstances: number, repeats: number): LevelBenchmark {
  // Top level over tlasInstances boxes the size of the scene's instances, spread over its bounds.
  const rnd = makeRandom(12);
  const b = prepared.bvh.bounds;
  const extent = [b[3]! - b[0]!, b[4]! - b[1]!, b[5]! - b[2]!].map((e) => (Number.isFinite(e) && e > 0 ? e : 1));
  const size = Math.max(...extent) / Math.cbrt(Math.max(tlasInstances, 1)) / 2;
  const boxes = new Float32Array(tlasInstances * 6);
  for (let i = 0; i < tlasInstances; i++) {
    const x = (b[0]! || 0) + rnd() * extent[0]!, y = (b[1]! || 0) + rnd() * extent[1]!, z = (b[2]! || 0) + rnd() * extent[2]!;
    boxes.set([x, y, z, x + size, y + size, z + size], i * 6);
  }
  let scratch = buildTlas(boxes);
  const tlasMs = timed(repeats, () => {
    scratch = buildTlas(boxes, scratch);
  });

  const levels = prepared.levels;
  let refitMs = 0, rebuildMs = 0, triangles = 0;
  let updateMs = 0;
  if (levels) {
    const scene = prepared.scene;
    for (const blas of levels.blas.values()) {
      triangles += blas.triangles.count;
      const mesh = scene.meshes[blas.mesh]!;
      refitMs += timed(repeats, () => void refitMeshBlas(scene, blas, mesh));
      rebuildMs += timed(repeats, () => void buildMeshBlas(scene, blas.mesh, mesh));
    }
    let k = 0;
    updateMs = timed(repeats, () => {
      k++;
      const poses = new Map(levels.dynamic.map((ii) => {
        const inst = scene.instances[ii]!;
        const m = [...inst.worldFromObject];
        m[12] = m[12]! + (k % 2) * 1e-3;
        return [inst.id, { worldFromObject: m }];
      }));
      void updateGeometry(prepared, poses, new Map());
    });
  }
  return { tlas: { instances: tlasInstances, ms: tlasMs }, blas: { meshes: levels?.blas.size ?? 0, triangles, refitMs, rebuildMs }, updateMs };
}
