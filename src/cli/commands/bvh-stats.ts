/** `lantern bvh-stats <scene>`: how each BVH layout Lantern has comes out on a scene (no GPU needed). */
import type { Command } from 'commander';
import { BVH_LAYOUTS } from '../../bvh/layouts.ts';
import { bvhStats, formatBvhStats } from '../../bvh/stats.ts';
import { reflectModule, structLayout } from '../../gpu/wgsl/reflect.ts';
import { describePrimitives, flattenTriangles } from '../../scene/triangles.ts';
import { validateScene } from '../../scene/validate.ts';
import type { CliContext } from '../context.ts';
import { withSceneOptions, type SceneOptionValues } from '../options.ts';
import { loadSceneArgument, sceneHelp, sceneLoadOptions } from '../scene-source.ts';

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
      if (options.json) {
        context.print(JSON.stringify({ scene: scene.name, triangles: list.kindCounts.triangle, spheres: list.kindCounts.sphere, capsules: list.kindCounts.capsule, primitives: count, triangleBytes: perTriangle, layouts: layouts.map((l) => l.stats) }, null, 2));
        return;
      }
      const lines = [`${scene.name}: ${describePrimitives(list)} (${perTriangle} GPU bytes each)`];
      for (const { layout, bvh, statOptions, stats } of layouts) {
        lines.push(`${layout.name}: ${layout.description}`, formatBvhStats(bvh, statOptions).replace(/^/gm, '  '), `  nodes alone: ${stats.nodeBytesPerTriangle.toFixed(1)} bytes/triangle`);
      }
      context.print(lines.join('\n'));
    }),
  );
}
