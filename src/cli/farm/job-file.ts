/**
 * A farm job file read for the CLI: farm/job.ts's checks, then paths made absolute (relative ones
 * are the job file's folder's: the output folder, the camera path, environment and light table, a
 * scene file), and `render`'s options checked by parsing the chunk's command line as `render`
 * parses it (one line for a bad name or value), before any worker starts.
 */
import { existsSync } from 'node:fs';
import { dirname, isAbsolute, resolve } from 'node:path';
import { Command } from 'commander';
import { LanternError } from '../../errors.ts';
import { chunkRenderArgs, jobChunks, parseJob, type Chunk, type FarmJob } from '../../farm/job.ts';
import type { CliContext } from '../context.ts';
import { registerRender } from '../commands/render.ts';
import { readJsonFile } from '../user-files.ts';

/** Render options whose values are files. */
const FILE_OPTIONS = ['path', 'env', 'light-table'];

export function readJobFile(path: string): FarmJob {
  const job = parseJob(readJsonFile(path, 'job'));
  const base = dirname(resolve(path));
  const at = (p: string) => (isAbsolute(p) ? p : resolve(base, p));
  const render: Record<string, string | number | boolean> = { ...job.render };
  for (const key of FILE_OPTIONS) if (typeof render[key] === 'string' && render[key] !== 'none') render[key] = at(render[key] as string);
  // A scene file beside the job (model.glb, iwad.wad#E1M1); built-in names and installed maps stay names.
  const [file, part] = job.scene.split('#') as [string, string | undefined];
  const scene = !isAbsolute(file) && existsSync(resolve(base, file)) ? `${resolve(base, file)}${part !== undefined ? `#${part}` : ''}` : job.scene;
  const resolved: FarmJob = { ...job, scene, render, output: { ...job.output, folder: at(job.output.folder) } };
  checkRenderArgs(resolved);
  return resolved;
}

/** Parses the first chunk's `render` command line as `render` would, running nothing. */
function checkRenderArgs(job: FarmJob): void {
  const program = new Command().exitOverride();
  let message = '';
  program.configureOutput({ writeErr: (text) => (message += text), writeOut: () => {} });
  const idle: CliContext = { verbose: () => false, argv: [], print: () => {}, note: () => {}, warn: () => {}, dawnOutput: () => {}, run: async () => {} };
  registerRender(program, idle);
  const first = jobChunks(job)[0]!;
  try {
    program.parse(['render', ...chunkRenderArgs(job, first, chunkFiles(job, first))], { from: 'user' });
  } catch {
    throw new LanternError(`job: its render options do not parse: ${(message.split('\n')[0] ?? '').replace(/^error: /, '')}`, 'Give "render" the long names and values `lantern render` takes');
  }
}

/** Where a chunk's outputs go in the job's folder: a Sample chunk's shard, a Frame chunk's frame folders. */
export function chunkFiles(job: FarmJob, chunk: Chunk): { shard?: string; pngFolder?: string; exrFolder?: string } {
  const folder = job.output.folder;
  if (job.kind === 'samples') return { shard: resolve(folder, 'shards', `${job.name}-${chunk.id}.shard`) };
  return { ...(job.output.png ? { pngFolder: resolve(folder, job.output.png) } : {}), ...(job.output.exr ? { exrFolder: resolve(folder, job.output.exr) } : {}) };
}

/** The files a chunk leaves when done (a shard, or its frames' files). */
export function chunkOutputs(job: FarmJob, chunk: Chunk): string[] {
  const f = chunkFiles(job, chunk);
  if (f.shard) return [f.shard];
  const name = (v: number) => `frame-${String(v).padStart(4, '0')}`;
  return chunk.values.flatMap((v) => [...(f.pngFolder ? [resolve(f.pngFolder, `${name(v)}.png`)] : []), ...(f.exrFolder ? [resolve(f.exrFolder, `${name(v)}.exr`)] : [])]);
}

/** The merged image's files of a Sample job. */
export function mergedOutputs(job: FarmJob): { png?: string; exr?: string } {
  return { ...(job.output.png ? { png: resolve(job.output.folder, job.output.png) } : {}), ...(job.output.exr ? { exr: resolve(job.output.folder, job.output.exr) } : {}) };
}
