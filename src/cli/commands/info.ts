/** `lantern info <scene>`: what a scene holds and how its BVH came out; for a WAD, its maps. */
import type { Command } from 'commander';
import { formatBvhStats } from '../../bvh/stats.ts';
import { summarizeMaps } from '../../loaders/doom/load.ts';
import { isDoomUri, parseDoomUri } from '../../loaders/doom/uri.ts';
import { prepareScene } from '../../renderer/prepare.ts';
import type { CliContext } from '../context.ts';
import { withSceneOptions } from '../options.ts';
import { loadSceneArgument, sceneHelp } from '../scene-source.ts';
import { openWads } from '../wad-files.ts';

export function registerInfo(program: Command, context: CliContext): void {
  const command = program
    .command('info')
    .description('print what a scene holds and its BVH statistics, or the maps of a WAD (no GPU needed)')
    .argument('<scene>', `${sceneHelp()}; a WAD without #map lists its maps`)
    .option('--json', 'print as JSON');
  withSceneOptions(command).action((sceneArg: string, options: { json?: boolean; lightTable?: string }) =>
      context.run(async () => {
        if (isDoomUri(sceneArg) && parseDoomUri(sceneArg).map === undefined) return listMaps(sceneArg, options.json ?? false, context);
        const t0 = performance.now();
        const prepared = prepareScene(loadSceneArgument(sceneArg, { onWarning: context.note, ...(options.lightTable ? { lightTablePath: options.lightTable } : {}) }));
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

function listMaps(uri: string, json: boolean, context: CliContext): void {
  const { stack } = openWads(uri);
  const maps = summarizeMaps(stack);
  if (json) {
    context.print(JSON.stringify({ wads: stack.files.map((f) => f.name), maps }, null, 2));
    return;
  }
  const n = (x: number | undefined) => (x ?? 0).toLocaleString('en-US').padStart(7);
  const lines = [`${stack.describe()}: ${maps.length} maps`, '  map        things  lines  sectors  triangles  textures'];
  for (const m of maps) {
    if (m.error) lines.push(`  ${m.name.padEnd(8)}  ${m.error}`);
    else {
      const failed = m.failures && m.failures.length > 0 ? `  (${m.failures.length} sectors not triangulated)` : '';
      lines.push(`  ${m.name.padEnd(8)} ${n(m.things)}${n(m.linedefs)}  ${n(m.sectors)}  ${n(m.triangles).padStart(9)}  ${n(m.textures).padStart(8)}${failed}`);
    }
  }
  context.print(lines.join('\n'));
}
