/** `lantern bvh-stats <scene>`: how each BVH layout Lantern has comes out on a scene (no GPU needed). */
import type { Command } from 'commander';
import { BVH_LAYOUTS } from '../../bvh/layouts.ts';
import { formatBvhStats } from '../../bvh/stats.ts';
import { reflectModule, structLayout } from '../../gpu/wgsl/reflect.ts';
import { describePrimitives, flattenTriangles, type TriangleList } from '../../scene/triangles.ts';
import { buildLevels, buildStaticBvh } from '../../bvh/levels.ts';
import { buildGrid, describeGrid } from '../../bvh/grid.ts';
import type { Bvh } from '../../bvh/types.ts';
import type { Scene } from '../../scene/types.ts';
import { validateScene } from '../../scene/validate.ts';
import { withoutStudio } from '../../scene/studio.ts';
import { LanternError } from '../../errors.ts';
import type { CliContext } from '../context.ts';
import { buildBvh } from '../../bvh/build.ts';
import { buildBvhParallel, PARALLEL_MIN_PRIMITIVES, type BvhWorkerPool } from '../../bvh/build-parallel.ts';
import { defaultBuildThreads, nodeBvhPool } from '../bvh-workers.ts';
import { choiceOption, integerOption } from '../options.ts';
import { formatGpuBuildReport, GPU_TIMINGS, gpuBuildReport, parseBuilders } from './gpu-build-stats.ts';
import { withSceneOptions, type SceneOptionValues } from '../options.ts';
import { loadSceneArgument, sceneHelp, sceneLoadOptions } from '../scene-source.ts';

/** Both levels of the structure the renderer builds for the scene (bvh/levels.ts). */
function levelStats(scene: Scene, list: TriangleList) {
  const staticBvh = buildStaticBvh(scene, list);
  const t0 = performance.now();
  const levels = buildLevels(scene, staticBvh);
  const s = staticBvh.stats;
  const blas = [...(levels?.blas.values() ?? [])];
  const depthOf = (b: Pick<Bvh, 'nodeCount' | 'leftFirst' | 'triCount'>) => {
    let deepest = 0;
    const walk = (node: number, d: number): void => {
      deepest = Math.max(deepest, d);
      if (b.triCount[node] === 0 && node !== 1 && b.nodeCount > 2) {
        walk(b.leftFirst[node]!, d + 1);
        walk(b.leftFirst[node]! + 1, d + 1);
      }
    };
    walk(0, 0);
    return deepest;
  };
  // The uniform grid `--accel grid` traces the static world through (bvh/grid.ts), over the same leaves.
  const grid = buildGrid(list.positions, list.kinds, staticBvh.triIndices, scene.tileGrid);
  return {
    grid,
    moving: levels?.dynamic.length ?? 0,
    static: { primitives: staticBvh.triIndices.length, nodes: s.nodeCount, maxDepth: s.maxDepth, sahCost: s.sahCost },
    blas: { meshes: blas.length, primitives: blas.reduce((n, b) => n + b.triangles.count, 0), nodes: blas.reduce((n, b) => n + b.bvh.stats.nodeCount, 0), maxDepth: Math.max(0, ...blas.map((b) => b.bvh.stats.maxDepth)) },
    tlas: levels ? { instances: levels.dynamic.length + 1, nodes: levels.tlas.nodeCount - 1, maxDepth: depthOf(levels.tlas), buildMs: levels.tlasMs } : { instances: 1, nodes: 0, maxDepth: 0, buildMs: performance.now() - t0 },
  };
}

/**
 * The binary-SAH build's time on one thread (the best of `single`, the build above, and two more:
 * a process's first build runs partly as cold code) and on the pool's workers (bvh/build-parallel.ts,
 * used here even on small scenes so that it is measured; without a pool, not timed): the first
 * parallel build, which may wait for the workers to start, and the best of three after it.
 * `identical`: whether the parallel tree is bit for bit the single-thread one, as it must be.
 */
interface BuildTimes {
  readonly threads: number;
  readonly singleMs: number;
  readonly sahCost: number;
  readonly parallelFirstMs?: number;
  readonly parallelMs?: number;
  readonly identical?: boolean;
}

async function buildTimes(positions: Float32Array, kinds: Uint8Array, single: Bvh, pool: BvhWorkerPool | undefined): Promise<BuildTimes> {
  const o = BVH_LAYOUTS[0]!.options;
  let singleMs = single.stats.buildMs;
  for (let i = 0; i < 2; i++) singleMs = Math.min(singleMs, buildBvh(positions, o, kinds).stats.buildMs);
  if (!pool) return { threads: 1, singleMs, sahCost: single.stats.sahCost };
  const first = await buildBvhParallel(positions, o, kinds, pool, { minPrimitives: 0 });
  let best = Infinity;
  for (let i = 0; i < 3; i++) best = Math.min(best, (await buildBvhParallel(positions, o, kinds, pool, { minPrimitives: 0 })).stats.buildMs);
  const same = (a: ArrayBufferView, b: ArrayBufferView) => a.byteLength === b.byteLength && Buffer.compare(new Uint8Array(a.buffer, a.byteOffset, a.byteLength), new Uint8Array(b.buffer, b.byteOffset, b.byteLength)) === 0;
  const identical = same(first.bounds, single.bounds) && same(first.leftFirst, single.leftFirst) && same(first.triCount, single.triCount) && same(first.triIndices, single.triIndices);
  return { threads: pool.size, singleMs, parallelFirstMs: first.stats.buildMs, parallelMs: best, identical, sahCost: single.stats.sahCost };
}

function describeBuild(b: BuildTimes): string {
  const f = (ms: number) => ms.toFixed(1);
  const parallel = b.parallelMs !== undefined ? `${f(b.parallelMs)} ms on ${b.threads} threads (${f(b.parallelFirstMs!)} ms with worker start), ${b.identical ? 'the same tree' : 'A DIFFERENT TREE (a bug)'}` : 'no parallel build (--threads N, N >= 2, times one)';
  return `binary-SAH build: ${f(b.singleMs)} ms on one thread; ${parallel}`;
}

/** GPU bytes of a grid as gpu/pack/scene-pack.ts packGrid writes it: a 64-byte header, 8 bytes a cell, 4 an item. */
const gridBytes = (grid: ReturnType<typeof buildGrid>) => 64 + 8 * grid.stats.cells + 4 * grid.stats.items;

/** GPU bytes of one primitive: its hot (traversal) and cold (shading) records, from the WGSL structs. */
function triangleBytes(): number {
  const { defs } = reflectModule('scene/bindings');
  return structLayout(defs, 'TriangleHot').stride + structLayout(defs, 'TriangleShading').stride;
}

export function registerBvhStats(program: Command, context: CliContext): void {
  const command = program
    .command('bvh-stats')
    .description('build every BVH layout Lantern has for a scene and print its statistics: nodes, leaves, depth, leaf sizes, SAH cost, memory, build time')
    .argument('<scene>', sceneHelp())
    .option('--json', 'print as JSON')
    .option('--threads <n>', 'threads for the parallel build timed beside the single-thread one (default: the cores, here ' + defaultBuildThreads() + ')', integerOption('--threads', 1, 256))
    .option('--builder <list>', 'which builders to run: cpu (every layout, the two levels, the grid), gpu (the GPU PLOC builder beside the CPU binned SAH), or cpu,gpu', 'cpu')
    .option('--bare', 'a PLY mesh or molecule alone, without the studio floor and lights (the mesh bench --protocol traces)')
    .option('--gpu-timing <how>', 'stages: one timestamped pass per stage (the build time); kernels: one per dispatch, summed by kernel (where the time goes)', choiceOption('--gpu-timing', GPU_TIMINGS), 'stages')
    .option('--gpu-repeats <n>', 'timed GPU builds after one warm-up (the median is reported)', integerOption('--gpu-repeats', 1, 100), 5);
  withSceneOptions(command).action((sceneArg: string, options: { json?: boolean; threads?: number; builder: string; gpuRepeats: number; gpuTiming: (typeof GPU_TIMINGS)[number]; bare?: boolean } & SceneOptionValues) =>
    context.run(async () => {
      const builders = parseBuilders(options.builder);
      // The workers start (and warm up) while the scene loads.
      // With --threads the workers start now (and warm up while the scene loads); without, only for
      // a scene big enough for render to use them (so small scenes and the tests spawn none).
      let pool = options.threads !== undefined ? nodeBvhPool(options.threads) : undefined;
      pool?.start();
      const loaded = await loadSceneArgument(sceneArg, sceneLoadOptions(options, context.warn));
      const scene = options.bare ? withoutStudio(loaded) : loaded;
      if (!scene) throw new LanternError(`--bare takes the mesh out of its studio: '${loaded.name}' is not a PLY mesh (or molecule) in the studio`);
      validateScene(scene);
      const list = flattenTriangles(scene);
      const { positions, count, kinds } = list;
      if (!builders.includes('cpu')) {
        // The GPU builder alone, beside the CPU binned SAH it is measured against.
        const report = await gpuBuildReport(list, BVH_LAYOUTS[0]!.build(positions, kinds), options.gpuRepeats, context, options.gpuTiming);
        context.print(options.json ? JSON.stringify({ scene: scene.name, primitives: count, gpuBuild: report }, null, 2) : `${scene.name}: ${describePrimitives(list)}\n${formatGpuBuildReport(report)}`);
        return;
      }
      const perTriangle = triangleBytes();
      const layouts = BVH_LAYOUTS.map((layout) => {
        const bvh = layout.build(positions, kinds);
        const statOptions = { triangleBytes: perTriangle, nodeBytes: layout.nodeBytes, traversalCost: layout.options.traversalCost, intersectionCost: layout.options.intersectionCost };
        const s = layout.stats(bvh, statOptions);
        return { layout, bvh, statOptions, s, stats: { name: layout.name, description: layout.description, ...s, nodeBytesPerTriangle: s.nodeBytes / count } };
      });
      const twoLevel = levelStats(scene, list);
      if (options.threads === undefined && count >= PARALLEL_MIN_PRIMITIVES) pool = nodeBvhPool();
      const build = await buildTimes(positions, kinds, layouts[0]!.bvh, pool);
      const gpuBuild = builders.includes('gpu') ? await gpuBuildReport(list, layouts[0]!.bvh, options.gpuRepeats, context, options.gpuTiming) : undefined;
      if (options.json) {
        const { grid, ...levels } = twoLevel;
        const gridJson = { dims: grid.dims, cellSize: grid.cellSize, lo: grid.lo, hi: grid.hi, ...grid.stats, gpuBytes: gridBytes(grid) };
        context.print(JSON.stringify({ scene: scene.name, triangles: list.kindCounts.triangle, spheres: list.kindCounts.sphere, capsules: list.kindCounts.capsule, primitives: count, triangleBytes: perTriangle, layouts: layouts.map((l) => l.stats), build, levels, grid: gridJson, ...(gpuBuild ? { gpuBuild } : {}) }, null, 2));
        return;
      }
      const lines = [`${scene.name}: ${describePrimitives(list)} (${perTriangle} GPU bytes each)`, describeBuild(build)];
      for (const { layout, bvh, statOptions, s, stats } of layouts) {
        lines.push(`${layout.name}: ${layout.description}`, formatBvhStats(bvh, statOptions, s).replace(/^/gm, '  '), `  nodes alone: ${stats.nodeBytesPerTriangle.toFixed(1)} bytes/triangle`);
      }
      if (twoLevel.moving === 0) {
        lines.push('two levels: nothing moves, so the renderer traces the one BVH above (binned SAH) as the static world');
      } else {
        lines.push(
          `two levels (what the renderer builds: ${twoLevel.moving} moving instance(s) in a top level over the static world):`,
          `  static world: ${twoLevel.static.primitives.toLocaleString('en-US')} primitives, ${twoLevel.static.nodes.toLocaleString('en-US')} nodes, depth ${twoLevel.static.maxDepth}, SAH cost ${twoLevel.static.sahCost.toFixed(2)}`,
          `  bottom levels: ${twoLevel.blas.meshes} moving mesh(es), ${twoLevel.blas.primitives.toLocaleString('en-US')} primitives in object space, ${twoLevel.blas.nodes.toLocaleString('en-US')} nodes, deepest ${twoLevel.blas.maxDepth}`,
          `  top level: ${twoLevel.tlas.instances} instances, ${twoLevel.tlas.nodes} nodes, depth ${twoLevel.tlas.maxDepth}, built in ${twoLevel.tlas.buildMs.toFixed(3)} ms`,
        );
      }
      lines.push(`static world as a uniform grid (--accel grid): ${describeGrid(twoLevel.grid)}, ${(gridBytes(twoLevel.grid) / 1024).toFixed(1)} KiB on the GPU`);
      if (gpuBuild) lines.push(formatGpuBuildReport(gpuBuild));
      context.print(lines.join('\n'));
    }),
  );
}
