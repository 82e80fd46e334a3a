/**
 * Runs a chunk or a merge as a `lantern` child process of this same bundle: each chunk gets a fresh
 * process (a Dawn failure ends the chunk, not the worker), and sees the worker's environment, so the
 * adapter chosen for the worker (docs/farm.md, GPU selection) is the chunk's.
 */
import { spawn, type ChildProcess } from 'node:child_process';
import { createHash } from 'node:crypto';
import { existsSync, mkdirSync, readdirSync, readFileSync, rmSync } from 'node:fs';
import { writeFile } from '../output-files.ts';
import { LanternError } from '../../errors.ts';
import { chunkFiles, chunkOutputs, mergedOutputs } from './job-file.ts';
import { chunkRenderArgs, renderOptionArgs, type Chunk, type FarmJob } from '../../farm/job.ts';
import { decodeShard } from '../../farm/shard.ts';
import { readUserFile } from '../user-files.ts';
import { resolve } from 'node:path';

export interface ChunkResult {
  readonly adapter: string;
  readonly seconds: number;
  /** True when its outputs were already there (the chunk done before): nothing was rendered. */
  readonly reused: boolean;
}

/** The running child processes, so that a worker told to stop can end them. */
export const children = new Set<ChildProcess>();

/** Runs `lantern <args> --json` and resolves with its JSON report; a non-zero exit rejects with its last error line. */
export function runLantern(args: readonly string[], signal?: AbortSignal): Promise<Record<string, unknown>> {
  return new Promise((done, fail) => {
    const child = spawn(process.execPath, [process.argv[1]!, ...args, '--json'], { stdio: ['ignore', 'pipe', 'pipe'], ...(signal ? { signal } : {}) });
    children.add(child);
    let out = '';
    let err = '';
    child.stdout!.on('data', (d: Buffer) => (out += d.toString()));
    child.stderr!.on('data', (d: Buffer) => (err += d.toString()));
    child.on('error', (e) => {
      children.delete(child);
      fail(e);
    });
    child.on('close', (code, sig) => {
      children.delete(child);
      if (code === 0) {
        try {
          done(JSON.parse(out) as Record<string, unknown>);
        } catch {
          fail(new Error(`lantern ${args[0]} printed no JSON report`));
        }
        return;
      }
      const line = err.trim().split('\n').filter((l) => l.includes('error')).pop() ?? err.trim().split('\n').pop() ?? '';
      fail(new Error(`lantern ${args[0]} ${sig ? `was ended by ${sig}` : `exited with ${code}`}${line ? `: ${line.replace(/^lantern: /, '')}` : ''}`));
    });
  });
}

/** The job's key: its name and the first 12 hex digits of the SHA-256 of its JSON (same job, same key). */
export function jobKey(job: FarmJob): string {
  return `${job.name}-${createHash('sha256').update(JSON.stringify(job)).digest('hex').slice(0, 12)}`;
}

/**
 * The file that says a chunk of this job (this key: its name and content) is done. Outputs left in
 * the folder by another job of the same name (another seed, another size) have no such file here,
 * so they are rendered again rather than taken.
 */
const doneMarker = (job: FarmJob, chunk: Chunk): string => resolve(job.output.folder, 'chunks', `${jobKey(job)}-${chunk.id}.done`);

/** Whether a chunk of this job is done: its marker there, its outputs all there, a shard whole and of this chunk. */
export function chunkDone(job: FarmJob, chunk: Chunk): boolean {
  const files = chunkOutputs(job, chunk);
  const marker = doneMarker(job, chunk);
  if (!existsSync(marker) || readFileSync(marker, 'utf8') !== jobKey(job)) return false;
  if (!files.every((f) => existsSync(f))) return false;
  const shard = chunkFiles(job, chunk).shard;
  if (!shard) return true;
  try {
    const h = decodeShard(readUserFile(shard), shard).header;
    // Of this chunk's samples, and of this job's render (not one another job of the same name left).
    return h.start === chunk.values[0] && h.end === chunk.values[chunk.values.length - 1]! + 1 && JSON.stringify(h.render) === JSON.stringify([job.scene, ...renderOptionArgs(job)]);
  } catch {
    return false;
  }
}

/**
 * Renders one chunk into the job's folder, unless its outputs are there already: a chunk done twice
 * (a retry after the first attempt's files were written, a stalled chunk handed out again) writes
 * the same files once, and files are renamed into place whole (output-files.ts writeFile).
 */
export async function runChunk(job: FarmJob, chunk: Chunk, signal?: AbortSignal): Promise<ChunkResult> {
  if (chunkDone(job, chunk)) return { adapter: '', seconds: 0, reused: true };
  const t0 = performance.now();
  const report = await runLantern(['render', ...chunkRenderArgs(job, chunk, chunkFiles(job, chunk))], signal);
  // The chunk's files are this job's now: another job of the same name that wrote them before is no
  // longer done there.
  const markers = resolve(job.output.folder, 'chunks');
  mkdirSync(markers, { recursive: true });
  const mine = `${jobKey(job)}-${chunk.id}.done`;
  for (const name of readdirSync(markers)) if (name !== mine && name.startsWith(`${job.name}-`) && name.endsWith(`-${chunk.id}.done`)) rmSync(resolve(markers, name), { force: true });
  writeFile(doneMarker(job, chunk), new TextEncoder().encode(jobKey(job)));
  return { adapter: String(report.adapter ?? ''), seconds: (performance.now() - t0) / 1000, reused: false };
}

/** Merges a Sample job's shards into its images (lantern merge as a child); a Frame job has nothing to merge. */
export async function mergeJob(job: FarmJob, chunks: readonly Chunk[], signal?: AbortSignal): Promise<{ seconds: number; outputs: string[] }> {
  if (job.kind !== 'samples') return { seconds: 0, outputs: [] };
  const missing = chunks.filter((c) => !chunkDone(job, c));
  if (missing.length > 0) throw new LanternError(`job ${job.name}: ${missing.length} chunks have no shard yet (${missing.slice(0, 3).map((c) => c.id).join(', ')}${missing.length > 3 ? ', …' : ''})`);
  const out = mergedOutputs(job);
  const t0 = performance.now();
  await runLantern(['merge', ...chunks.map((c) => chunkFiles(job, c).shard!), ...(out.png ? ['--out', out.png] : []), ...(out.exr ? ['--exr', out.exr] : [])], signal);
  return { seconds: (performance.now() - t0) / 1000, outputs: [out.png, out.exr].filter((f): f is string => f !== undefined).map((f) => resolve(f)) };
}
