/** `lantern info <scene>`: what a scene holds and how its BVH came out; for a file of several scenes (a WAD), its parts. */
import type { Command } from 'commander';
import { formatBvhStats } from '../../bvh/stats.ts';
import { prepareScene } from '../../renderer/prepare.ts';
import type { CliContext } from '../context.ts';
import { withSceneOptions } from '../options.ts';
import { builtinScene } from '../../loaders/builtin/index.ts';
import type { Scene } from '../../scene/types.ts';
import { loadOptions, openSceneFiles, parseSceneArgument, sceneHelp } from '../scene-source.ts';

export function registerInfo(program: Command, context: CliContext): void {
  const command = program
    .command('info')
    .description('print what a scene holds and its BVH statistics, or the maps of a WAD (no GPU needed)')
    .argument('<scene>', `${sceneHelp()}; a WAD without #map lists its maps`)
    .option('--json', 'print as JSON');
  withSceneOptions(command).action((sceneArg: string, options: { json?: boolean; lightTable?: string }) =>
      context.run(async () => {
        const t0 = performance.now();
        const argument = parseSceneArgument(sceneArg);
        const sceneOptions = loadOptions({ onWarning: context.note, ...(options.lightTable ? { lightTablePath: options.lightTable } : {}) });
        let loaded: Scene;
        if (argument.kind === 'builtin') loaded = builtinScene(argument.name);
        else {
          const { format, opened, part } = await openSceneFiles(argument);
          // A file of several scenes named without one: list them rather than pick the first.
          const inventory = format.part && part === undefined ? opened.inventory?.() : undefined;
          if (inventory) {
            context.print(options.json ? JSON.stringify(inventory.json, null, 2) : inventory.lines.join('\n'));
            return;
          }
          loaded = await opened.scene(part, sceneOptions);
        }
        const prepared = prepareScene(loaded);
        const loadMs = performance.now() - t0;
        const { scene, triangles, bvh, packed } = prepared;
        if (options.json) {
          context.print(JSON.stringify({ scene: scene.name, meshes: scene.meshes.length, triangles: triangles.count, materials: scene.materials.length, textures: packed.counts.textures, lights: packed.counts.lights, loadMs, bvh: bvh.stats }, null, 2));
          return;
        }
        context.print(
          [
            `${scene.name}: ${triangles.count.toLocaleString('en-US')} triangles in ${scene.meshes.length} mesh(es), ${scene.materials.length} materials, ${packed.counts.textures} textures, ${packed.counts.lights.toLocaleString('en-US')} emissive triangles (loaded and prepared in ${loadMs.toFixed(1)} ms)`,
            formatBvhStats(bvh),
          ].join('\n'),
        );
      }),
    );
}
