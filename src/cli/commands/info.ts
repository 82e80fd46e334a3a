/** `lantern info <scene>`: what a scene holds and how its BVH came out. */
import type { Command } from 'commander';
import { formatBvhStats } from '../../bvh/stats.ts';
import { prepareScene } from '../../renderer/prepare.ts';
import type { CliContext } from '../context.ts';
import { loadSceneArgument, sceneHelp } from '../scene-source.ts';

export function registerInfo(program: Command, context: CliContext): void {
  program
    .command('info')
    .description('print triangle, material and light counts and BVH statistics (no GPU needed)')
    .argument('<scene>', sceneHelp())
    .option('--json', 'print as JSON')
    .action((sceneArg: string, options: { json?: boolean }) =>
      context.run(async () => {
        const t0 = performance.now();
        const prepared = prepareScene(loadSceneArgument(sceneArg, context.note));
        const loadMs = performance.now() - t0;
        const { scene, triangles, bvh, packed } = prepared;
        if (options.json) {
          context.print(JSON.stringify({ scene: scene.name, meshes: scene.meshes.length, triangles: triangles.count, materials: scene.materials.length, lights: packed.counts.lights, loadMs, bvh: bvh.stats }, null, 2));
          return;
        }
        context.print(
          [
            `${scene.name}: ${triangles.count.toLocaleString('en-US')} triangles in ${scene.meshes.length} mesh(es), ${scene.materials.length} materials, ${packed.counts.lights} emissive triangles (loaded and prepared in ${loadMs.toFixed(1)} ms)`,
            formatBvhStats(bvh),
          ].join('\n'),
        );
      }),
    );
}
