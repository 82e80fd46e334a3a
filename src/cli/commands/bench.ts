/** `lantern bench <scene>`: BVH build, traversal and path-tracing throughput, GPU-timed. */
import type { Command } from 'commander';
import { runBenchmark } from '../../renderer/benchmark.ts';
import type { CliContext } from '../context.ts';
import { mergeSettings } from '../../renderer/settings-schema.ts';
import type { SettingEntry } from '../../renderer/settings-schema.ts';
import { integerOption, withImageOptions, withSceneOptions } from '../options.ts';
import { environmentFromOptions, withEnvironmentOptions, type EnvironmentOptions } from '../environment-option.ts';
import { settingsFromOptions, withSettingOptions } from '../setting-options.ts';
import { sceneHelp } from '../scene-source.ts';
import { openSession } from '../session.ts';

interface BenchOptions extends EnvironmentOptions, Readonly<Record<string, unknown>> {
  width: number;
  height: number;
  repeats: number;
  lightTable?: string;
  json?: boolean;
}

/** The settings that change what path tracing costs: those that change the estimate. */
const benchSetting = (entry: SettingEntry) => entry.spec.restarts;

export function registerBench(program: Command, context: CliContext): void {
  const command = program
    .command('bench')
    .description('measure BVH build time, ray throughput (primary and diffuse rays) and path-tracing speed')
    .argument('<scene>', sceneHelp());
  withSettingOptions(withEnvironmentOptions(withSceneOptions(withImageOptions(command, { width: 1920, height: 1080 }))), benchSetting)
    .option('-r, --repeats <n>', 'timed repetitions of each measurement', integerOption('--repeats', 1, 1000), 10)
    .option('--json', 'print the figures as JSON')
    .action((sceneArg: string, options: BenchOptions) => context.run(() => bench(sceneArg, options, context)));
}

async function bench(sceneArg: string, o: BenchOptions, context: CliContext): Promise<void> {
  const { renderer, prepared, loadMs } = await openSession(sceneArg, context.note, o.lightTable, environmentFromOptions(o));
  await renderer.resize(o.width, o.height);
  renderer.updateSettings(mergeSettings(renderer.settings, settingsFromOptions(o, benchSetting)));
  if (renderer.settings.spectral) await renderer.enableSpectral();
  const result = await runBenchmark(renderer, { repeats: o.repeats });
  const s = prepared.bvh.stats;
  const report = {
    scene: prepared.scene.name,
    triangles: prepared.triangles.count,
    lights: prepared.packed.counts.lights,
    loadMs,
    spectral: renderer.settings.spectral,
    bvh: { buildMs: s.buildMs, nodes: s.nodeCount, leaves: s.leafCount, maxDepth: s.maxDepth, sahCost: s.sahCost },
    ...result,
  };
  renderer.destroy();
  if (o.json) {
    context.print(JSON.stringify(report, null, 2));
    return;
  }
  const f = (x: number, digits = 1) => x.toFixed(digits);
  const p = result.pathTracing;
  context.print(
    [
      `Lantern bench: ${report.scene} at ${o.width}×${o.height} on ${result.adapter} (${result.timing === 'gpu-timestamps' ? 'GPU timestamps' : 'wall clock'}, median of ${o.repeats})`,
      `  triangles       ${report.triangles.toLocaleString('en-US')} (${report.lights} emissive)`,
      `  BVH build       ${f(s.buildMs)} ms: ${s.nodeCount.toLocaleString('en-US')} nodes, depth ${s.maxDepth}, SAH cost ${f(s.sahCost, 2)}`,
      `  primary rays    ${f(result.primary.mraysPerSecond)} Mrays/s (${f(result.primary.ms, 3)} ms)`,
      `  diffuse rays    ${f(result.diffuse.mraysPerSecond)} Mrays/s (${f(result.diffuse.ms, 3)} ms)`,
      `  path tracing    ${report.spectral ? '(spectral) ' : ''}${f(p.samplesPerSecond / 1e6, 2)} M samples/s (${f(p.msPerSample, 3)} ms per spp), ${f(p.mraysPerSecond)} Mrays/s at ${p.maxBounces} bounces (${f(p.raysPerPath, 2)} rays per path)`,
    ].join('\n'),
  );
}
