/** `lantern bvh-stats <scene>`: how each BVH layout Lantern has comes out on a scene (no GPU needed). */
import type { Command } from 'commander';
import { BVH_LAYOUTS } from '../../bvh/layouts.ts';
import { bvhStats, formatBvhStats } from '../../bvh/stats.ts';
import { reflectModule, structLayout } from '../../gpu/wgsl/reflect.ts';
import { describePrimitives, flattenTriangles, type TriangleList } from '../../scene/triangles.ts';
import { buildLevels, buildStaticBvh } from '../../bvh/levels.ts';
import { buildGrid, describeGrid } from '../../bvh/grid.ts';
import type { Bvh } from '../../bvh/types.ts';
import type { Scene } from '../../scene/types.ts';
import { validateScene } from '../../scene/validate.ts';
import type { CliContext } from '../context.ts';
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
    .option('--json', 'print as JSON');
  withSceneOptions(command).action((sceneArg: string, options: { json?: boolean } & SceneOptionValues) =>
    context.run(async () => {
      const scene = await loadSceneArgument(sceneArg, sceneLoadOptions(options, context.note));
      validateScene(scene);
      const list = flattenTriangles(scene);
      const { positions, count, kinds } = list;
      const perTriangle = triangleBytes();
      const layouts = BVH_LAYOUTS.map((layout) => {
        const bvh = layout.build(positions, kinds);
        const statOptions = { triangleBytes: perTriangle, nodeBytes: layout.nodeBytes, traversalCost: layout.options.traversalCost, intersectionCost: layout.options.intersectionCost };
        const s = bvhStats(bvh, statOptions);
        return { layout, bvh, statOptions, stats: { name: layout.name, description: layout.description, ...s, nodeBytesPerTriangle: s.nodeBytes / count } };
      });
      const twoLevel = levelStats(scene, list);
      if (options.json) {
        const { grid, ...levels } = twoLevel;
        const gridJson = { dims: grid.dims, cellSize: grid.cellSize, lo: grid.lo, hi: grid.hi, ...grid.stats, gpuBytes: gridBytes(grid) };
        context.print(JSON.stringify({ scene: scene.name, triangles: list.kindCounts.triangle, spheres: list.kindCounts.sphere, capsules: list.kindCounts.capsule, primitives: count, triangleBytes: perTriangle, layouts: layouts.map((l) => l.stats), levels, grid: gridJson }, null, 2));
        return;
      }
      const lines = [`${scene.name}: ${describePrimitives(list)} (${perTriangle} GPU bytes each)`];
      for (const { layout, bvh, statOptions, stats } of layouts) {
        lines.push(`${layout.name}: ${layout.description}`, formatBvhStats(bvh, statOptions).replace(/^/gm, '  '), `  nodes alone: ${stats.nodeBytesPerTriangle.toFixed(1)} bytes/triangle`);
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
      context.print(lines.join('\n'));
    }),
  );
}
