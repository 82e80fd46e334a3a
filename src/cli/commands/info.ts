/** `lantern info <scene>`: what a scene holds and how its BVH came out; for a file of several scenes (a WAD), its parts. */
import type { Command } from 'commander';
import { formatBvhStats } from '../../bvh/stats.ts';
import { prepareSceneAsync, type PreparedScene } from '../../renderer/prepare.ts';
import { nodeBvhPool } from '../bvh-workers.ts';
import type { CliContext } from '../context.ts';
import { withSceneOptions, type SceneOptionValues } from '../options.ts';
import { builtinScene } from '../../loaders/builtin/index.ts';
import type { Scene } from '../../scene/types.ts';
import { describePrimitives } from '../../scene/triangles.ts';
import { checkSceneOptionsApply, loadOptions, openSceneFiles, parseSceneArgument, sceneHelp, sceneLoadOptions } from '../scene-source.ts';

export function registerInfo(program: Command, context: CliContext): void {
  const command = program
    .command('info')
    .description('print what a scene holds and its BVH statistics, or the maps of a WAD (no GPU needed)')
    .argument('<scene>', `${sceneHelp()}; a WAD without #map lists its maps`)
    .option('--json', 'print as JSON');
  withSceneOptions(command).action((sceneArg: string, options: { json?: boolean } & SceneOptionValues) =>
      context.run(async () => {
        const t0 = performance.now();
        const argument = parseSceneArgument(sceneArg);
        const given = sceneLoadOptions(options, context.warn);
        if (argument.kind === 'builtin') checkSceneOptionsApply(given, undefined);
        const sceneOptions = loadOptions(given);
        let loaded: Scene;
        if (argument.kind === 'builtin') loaded = builtinScene(argument.name);
        else {
          const { format, opened, part } = await openSceneFiles(argument);
          checkSceneOptionsApply(given, format);
          // A file of several scenes named without one: list them rather than pick the first.
          const inventory = format.part && part === undefined ? opened.inventory?.(sceneOptions) : undefined;
          if (inventory) {
            context.print(options.json ? JSON.stringify(inventory.json, null, 2) : inventory.lines.join('\n'));
            return;
          }
          loaded = await opened.scene(part, sceneOptions);
        }
        const prepared = await prepareSceneAsync(loaded, undefined, { bvhPool: nodeBvhPool() });
        const loadMs = performance.now() - t0;
        const { scene, triangles, bvh, packed } = prepared;
        const summary = sceneSummary(prepared);
        if (options.json) {
          context.print(JSON.stringify({ scene: scene.name, meshes: scene.meshes.length, instances: scene.instances.length, triangles: triangles.kindCounts.triangle, spheres: triangles.kindCounts.sphere, capsules: triangles.kindCounts.capsule, primitives: triangles.count, bounds: worldBounds(bvh.bounds), ...summary, loadMs, bvh: bvh.stats, warnings: scene.warnings ?? [], notes: scene.lightingNote ? [scene.lightingNote] : [] }, null, 2));
          return;
        }
        const kinds = Object.entries(summary.materialKinds).map(([k, n]) => `${n} ${k}`).join(', ');
        const emissiveTriangles = packed.counts.emissiveTriangles - packed.counts.emissiveSpheres;
        const emitters = [
          ...(emissiveTriangles > 0 || packed.counts.emissiveSpheres === 0 ? [`${emissiveTriangles.toLocaleString('en-US')} emissive triangles`] : []),
          ...(packed.counts.emissiveSpheres > 0 ? [`${packed.counts.emissiveSpheres.toLocaleString('en-US')} emissive spheres`] : []),
        ].join(', ');
        const lights = [emitters, `${packed.counts.punctualLights} punctual lights`, `environment: ${summary.environment}`].join(', ');
        const mib = (b: number) => `${(b / 2 ** 20).toFixed(1)} MiB`;
        context.print(
          [
            `${scene.name}: ${describePrimitives(triangles)} in ${scene.meshes.length} mesh(es) placed by ${scene.instances.length} instance(s) (loaded and prepared in ${loadMs.toFixed(1)} ms)`,
            `materials: ${scene.materials.length} (${kinds})`,
            `lights: ${lights}`,
            // How it is lit and why (scene/default-light.ts): information, apart from the warnings on stderr.
            ...(scene.lightingNote ? [`lighting: ${scene.lightingNote}`] : []),
            ...(summary.sprites > 0 ? [`sprites: ${summary.sprites} (things drawn), ${summary.emittingSprites} of them emitting`] : []),
            `textures: ${packed.counts.textures}, on the GPU ${mib(summary.textureBytes)} (atlas pages with mip levels: ${packed.atlas.pages.length} sRGB + ${packed.linearAtlas.pages.length} linear)`,
            formatBvhStats(bvh),
          ].join('\n'),
        );
      }),
    );
}

/** The scene's world-space box: the BVH root's (node 0), min and max xyz. */
function worldBounds(bounds: Float32Array): { min: number[]; max: number[] } {
  return { min: [...bounds.subarray(0, 3)], max: [...bounds.subarray(3, 6)] };
}

/** What `info` reports beyond the BVH: materials by kind, the environment, the GPU memory of textures. */
function sceneSummary({ scene, packed }: PreparedScene) {
  const materialKinds: Record<string, number> = {};
  for (const m of scene.materials) materialKinds[m.kind] = (materialKinds[m.kind] ?? 0) + 1;
  const pageBytes = (a: typeof packed.atlas) => (a.rects.length === 0 ? 0 : a.pages.length * a.pageSize * a.pageSize * 4);
  return {
    materials: scene.materials.length,
    materialKinds,
    textures: packed.counts.textures,
    textureBytes: pageBytes(packed.atlas) + pageBytes(packed.linearAtlas),
    emissiveTriangles: packed.counts.emissiveTriangles,
    punctualLights: packed.counts.punctualLights,
    environment: scene.environment?.kind ?? 'none',
    ...spriteCounts(scene),
  };
}

/** Billboards (Doom's things drawn as sprites), and those whose images emit. */
function spriteCounts(scene: Scene): { sprites: number; emittingSprites: number } {
  const billboards = scene.dynamics?.billboards ?? [];
  const emits = (material: number) => scene.materials[material]?.emission.some((c) => c > 0) ?? false;
  return { sprites: billboards.length, emittingSprites: billboards.filter((b) => b.frames.some((f) => f.images.some((i) => emits(i.material)))).length };
}
