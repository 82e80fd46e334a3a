/**
 * Runs a chunk or a merge in a `lantern` child process of this same bundle: a chunk in the worker
 * slot's chunk server (chunk-server.ts: one process for chunk after chunk, keeping the device and the
 * scene), a merge there too or in a process of its own. A Dawn failure ends the chunk, not the worker; the
 * children see the worker's environment, so the adapter chosen for the worker (docs/farm.md, GPU
 * selection) is theirs.
 */
import { fork, spawn, type ChildProcess } from 'node:child_process';
import { createHash } from 'node:crypto';
import { existsSync, mkdirSync, readdirSync, readFileSync, rmSync } from 'node:fs';
import { writeFile } from '../output-files.ts';
import { LanternError } from '../../errors.ts';
import { chunkFiles, chunkOutputs, mergedOutputs } from './job-file.ts';
import { chunkRenderArgs, renderOptionArgs, type Chunk, type FarmJob } from '../../farm/job.ts';
import { readShardHeader } from '../shard-files.ts';
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
    const h = readShardHeader(shard);
    // Of this chunk's samples, and of this job's render (not one another job of the same name left).
    return h.start === chunk.values[0] && h.end === chunk.values[chunk.values.length - 1]! + 1 && JSON.stringify(h.render) === JSON.stringify([job.scene, ...renderOptionArgs(job)]);
  } catch {
    return false;
  }
}

/**
 * Renders one chunk into the job's folder (in the worker slot's chunk server, else in a process of
 * its own), unless its outputs are there already: a chunk done twice
 * (a retry after the first attempt's files were written, a stalled chunk handed out again) writes
 * the same files once, and files are renamed into place whole (output-files.ts writeFile).
 */
export async function runChunk(job: FarmJob, chunk: Chunk, signal?: AbortSignal, server?: ChunkServer): Promise<ChunkResult> {
  if (chunkDone(job, chunk)) return { adapter: '', seconds: 0, reused: true };
  const t0 = performance.now();
  const args = ['render', ...chunkRenderArgs(job, chunk, chunkFiles(job, chunk))];
  const report = await (server ? server.run(args, signal) : runLantern(args, signal));
  // The chunk's files are this job's now: another job of the same name that wrote them before is no
  // longer done there.
  const markers = resolve(job.output.folder, 'chunks');
  mkdirSync(markers, { recursive: true });
  const mine = `${jobKey(job)}-${chunk.id}.done`;
  for (const name of readdirSync(markers)) if (name !== mine && name.startsWith(`${job.name}-`) && name.endsWith(`-${chunk.id}.done`)) rmSync(resolve(markers, name), { force: true });
  writeFile(doneMarker(job, chunk), new TextEncoder().encode(jobKey(job)));
  return { adapter: String(report.adapter ?? ''), seconds: (performance.now() - t0) / 1000, reused: false };
}

/** Merges a Sample job's shards into its images (lantern merge, in the chunk server given, else in a child of its own); a Frame job has nothing to merge. */
export async function mergeJob(job: FarmJob, chunks: readonly Chunk[], signal?: AbortSignal, server?: ChunkServer): Promise<{ seconds: number; outputs: string[] }> {
  if (job.kind !== 'samples') return { seconds: 0, outputs: [] };
  const missing = chunks.filter((c) => !chunkDone(job, c));
  if (missing.length > 0) throw new LanternError(`job ${job.name}: ${missing.length} chunks have no shard yet (${missing.slice(0, 3).map((c) => c.id).join(', ')}${missing.length > 3 ? ', …' : ''})`);
  const out = mergedOutputs(job);
  const t0 = performance.now();
  const args = ['merge', ...chunks.map((c) => chunkFiles(job, c).shard!), ...(out.png ? ['--out', out.png] : []), ...(out.exr ? ['--exr', out.exr] : [])];
  await (server ? server.run(args, signal) : runLantern(args, signal));
  return { seconds: (performance.now() - t0) / 1000, outputs: [out.png, out.exr].filter((f): f is string => f !== undefined).map((f) => resolve(f)) };
}

/** Set in a chunk server's environment (chunk-server.ts isChunkServer). */
export const SERVER_ENV = 'LANTERN_CHUNK_SERVER';

/** A chunk server's request: a command line; and its reply: the printed report, or the one-line error. */
export interface ChunkRequest {
  readonly id: number;
  readonly args: readonly string[];
}
export type ChunkReply = { readonly id: number; readonly ok: true; readonly stdout: string } | { readonly id: number; readonly ok: false; readonly error: string };

/**
 * The worker's side: a chunk server started when first asked, asked one command at a time, and
 * started again after it ended. `children` hears of each process, so that a stopping worker ends it.
 */
export class ChunkServer {
  private child: ChildProcess | undefined;
  private nextId = 1;

  constructor(private readonly children: Set<ChildProcess>) {}

  /** Runs `lantern <args> --json` in the server and resolves with its JSON report; a failure rejects with its one line. */
  run(args: readonly string[], signal?: AbortSignal): Promise<Record<string, unknown>> {
    const child = (this.child ??= this.start());
    const id = this.nextId++;
    return new Promise((done, fail) => {
      // While a chunk runs, the server keeps this process alive; idle, it does not.
      child.ref();
      child.channel?.ref();
      const settle = (f: () => void) => {
        child.unref();
        child.channel?.unref();
        child.off('message', onMessage);
        child.off('exit', onExit);
        signal?.removeEventListener('abort', onAbort);
        f();
      };
      const onMessage = (reply: ChunkReply) => {
        if (reply.id !== id) return;
        settle(() => {
          if (!reply.ok) return fail(new Error(`lantern ${args[0]}: ${reply.error.replace(/^lantern: (error: )?/, '')}`));
          try {
            done(JSON.parse(reply.stdout) as Record<string, unknown>);
          } catch {
            fail(new Error(`lantern ${args[0]} printed no JSON report`));
          }
        });
      };
      const onExit = (code: number | null, sig: NodeJS.Signals | null) => settle(() => fail(new Error(`lantern ${args[0]}: the chunk server ${sig ? `was ended by ${sig}` : `exited with ${code}`}`)));
      // An ended chunk ends its server: the render stops where it is, and the next chunk starts afresh.
      const onAbort = () => this.stop();
      child.on('message', onMessage);
      child.on('exit', onExit);
      if (signal?.aborted) return onAbort();
      signal?.addEventListener('abort', onAbort);
      child.send({ id, args: [...args, '--json'] } satisfies ChunkRequest);
    });
  }

  /** Ends the server (its chunk, if one is running, fails). */
  stop(): void {
    this.child?.kill('SIGTERM');
    this.child = undefined;
  }

  private start(): ChildProcess {
    const child = fork(process.argv[1]!, [], { env: { ...process.env, [SERVER_ENV]: '1' }, stdio: ['ignore', 'ignore', 'ignore', 'ipc'] });
    this.children.add(child);
    child.once('exit', () => {
      this.children.delete(child);
      if (this.child === child) this.child = undefined;
    });
    // The server leaves when this process does; it must not keep it alive while idle.
    child.unref();
    child.channel?.unref();
    return child;
  }
}
