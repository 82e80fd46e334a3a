/** `lantern convert <scene> -o file.glb`: the built scene as binary glTF 2.0. */
import type { Command } from 'commander';
import { LanternError } from '../../errors.ts';
import { sceneToGlb } from '../../exporters/glb.ts';
import { validateScene } from '../../scene/validate.ts';
import type { CliContext } from '../context.ts';
import { numberOption, pathOption, withSceneOptions, type SceneOptionValues } from '../options.ts';
import { checkOutputPath, writeFile } from '../output-files.ts';
import { loadSceneArgument, sceneHelp, sceneLoadOptions } from '../scene-source.ts';

export function registerConvert(program: Command, context: CliContext): void {
  const command = program
    .command('convert')
    .description('write the built scene as binary glTF 2.0 (.glb) with embedded PNG textures, for Blender or any glTF viewer')
    .argument('<scene>', sceneHelp())
    .requiredOption('-o, --out <file.glb>', 'where to write the .glb', pathOption('--out'))
    .option('--meters-per-unit <m>', "scale of one scene unit in metres (default: the scene's own, e.g. 1/32 for Doom maps)", numberOption('--meters-per-unit', 1e-9, 1e9));
  withSceneOptions(command).action((sceneArg: string, o: { out: string; metersPerUnit?: number } & SceneOptionValues) =>
      context.run(async () => {
        if (!o.out.toLowerCase().endsWith('.glb')) throw new LanternError(`--out must name a .glb file, not '${o.out}'`);
        checkOutputPath('--out', o.out, 'file');
        const scene = await loadSceneArgument(sceneArg, sceneLoadOptions(o, context.warn));
        validateScene(scene);
        const glb = await sceneToGlb(scene, { generator: 'Lantern', ...(o.metersPerUnit !== undefined ? { metersPerUnit: o.metersPerUnit } : {}) });
        writeFile(o.out, glb);
        const triangles = scene.meshes.reduce((n, m) => n + m.indices.length / 3, 0);
        const analytic = scene.meshes.reduce((n, m) => n + (m.spheres?.radii.length ?? 0) + (m.capsules?.radii.length ?? 0), 0);
        // glTF has no spheres: say that they went out as triangles (exporters/glb.ts tessellates them).
        const shapes = analytic > 0 ? ` + ${analytic.toLocaleString('en-US')} spheres and capsules (tessellated)` : '';
        context.print(`${scene.name}: ${triangles.toLocaleString('en-US')} triangles${shapes}, ${scene.materials.length} materials, ${scene.textures?.length ?? 0} textures -> ${o.out} (${(glb.length / 2 ** 20).toFixed(1)} MiB)`);
      }),
    );
}
