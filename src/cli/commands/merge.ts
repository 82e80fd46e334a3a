/**
 * `lantern merge shard... [--out x.png] [--exr x.exr]`: adds the shards' per-pixel sums in sample
 * order (farm/shard.ts mergeShards: float32 after each addition, as one process's accumulation adds
 * its dispatches), then shows the estimate as `render` does: the same command line (recorded in the
 * shards) sets up the scene, camera, settings and exposure, and the sums divided once by the sample
 * count are tone-mapped by the same GPU pass (PNG) or written as linear radiance (EXR).
 */
import { Command } from 'commander';
import { LanternError } from '../../errors.ts';
import { mergeShards, type Merged } from '../../farm/shard.ts';
import type { CliContext } from '../context.ts';
import { checkOutputPath, encodeExrNative, writeFile } from '../output-files.ts';
import { accumulationEstimate } from '../../renderer/image-readback.ts';
import { pathOption } from '../options.ts';
import { readShard, readShardHeader } from '../shard-files.ts';
import { registerRender } from './render.ts';

interface MergeOptions {
  out?: string;
  exr?: string;
  json?: boolean;
}

export function registerMerge(program: Command, context: CliContext): void {
  program
    .command('merge')
    .description("add farm shards' per-pixel sums (render --samples … --shard) and write the image one render of all their samples gives")
    .argument('<shards...>', 'the .shard files (any order; together one run of samples without gaps or overlaps)')
    .option('-o, --out <file.png>', 'write the tone-mapped image as PNG', pathOption('--out'))
    .option('--exr <file.exr>', 'write the linear radiance estimate as OpenEXR (float32 RGB)', pathOption('--exr'))
    .option('--json', 'print what was merged as JSON')
    .action((shards: string[], o: MergeOptions) => context.run(() => merge(shards, o, context)));
}

/**
 * Reads and adds the shards: every file's header, from its first bytes, is checked before any adding;
 * then each file is read whole once, in sample order, for its sums, so one shard's sums are in memory
 * at a time (a 4K shard is 127 MiB).
 */
export function readAndMerge(files: readonly string[]): Merged {
  return mergeShards(files.map((name) => ({ name, header: readShardHeader(name), sums: () => readShard(name).sums })));
}

/** Writes the merged estimate as `render` of its command line would; resolves with the adapter that tone-mapped it. */
export async function writeMerged(merged: Merged, outputs: { png?: string; exr?: string }, context: CliContext): Promise<string> {
  let adapter = '';
  const inner = new Command().exitOverride();
  inner.configureOutput({ writeErr: () => {}, writeOut: () => {} });
  const args = [...merged.render, ...(outputs.png ? ['--out', outputs.png] : []), ...(outputs.exr ? ['--exr', outputs.exr] : [])];
  // The render runs as its own command line (in a chunk server, it finds the chunks' scene kept).
  registerRender(inner, { ...context, argv: [...context.argv.slice(0, 2), 'render', ...args] }, { sums: merged.sums, samples: merged.end - merged.start, done: (_files, name) => (adapter = name) });
  try {
    await inner.parseAsync(['render', ...args], { from: 'user' });
  } catch (e) {
    throw new LanternError(`the shards' render command line no longer parses: ${(e as Error).message.replace(/^error: /, '')}`, 'Merge with the Lantern that wrote the shards');
  }
  if (process.exitCode) throw new LanternError('merge: writing the merged image failed (see above)');
  return adapter;
}

async function merge(files: string[], o: MergeOptions, context: CliContext): Promise<void> {
  if (!o.out && !o.exr) throw new LanternError('merge needs --out file.png and/or --exr file.exr', 'Name where the merged image goes');
  if (o.out) checkOutputPath('--out', o.out, 'file');
  if (o.exr) checkOutputPath('--exr', o.exr, 'file');
  const t0 = performance.now();
  const merged = readAndMerge(files);
  const addMs = performance.now() - t0;
  // The EXR is the sums divided once, on the CPU by the function the GPU read-back uses: no GPU needed.
  // The PNG's tone map (and its exposure) is render's own GPU pass.
  if (o.exr) {
    const estimate = accumulationEstimate(merged.sums, merged.width, merged.height, merged.end - merged.start);
    writeFile(o.exr, await encodeExrNative(merged.width, merged.height, estimate.radiance));
  }
  const adapter = o.out ? await writeMerged(merged, { png: o.out }, context) : 'the CPU';
  const seconds = (performance.now() - t0) / 1000;
  const outputs = { ...(o.out ? { png: o.out } : {}), ...(o.exr ? { exr: o.exr } : {}) };
  if (o.json) {
    context.print(JSON.stringify({ shards: files.length, width: merged.width, height: merged.height, samples: { first: merged.start, last: merged.end - 1 }, render: merged.render, addMs, seconds, adapter, outputs }, null, 2));
  } else {
    context.print(`merged ${files.length} shards: ${merged.width}×${merged.height}, samples ${merged.start}-${merged.end - 1} (${merged.end - merged.start} spp), added in ${addMs.toFixed(1)} ms, written in ${seconds.toFixed(2)} s on ${adapter} -> ${Object.values(outputs).join(' and ')}`);
  }
}
