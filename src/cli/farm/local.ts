/**
 * `lantern farm run job.json --local N`: the job's chunks on N local worker processes (each slot's
 * chunk server), no Redis (one machine, CI). Chunks go out in order to whichever slot is free; a failed chunk is tried again
 * after a backoff (1 s, 2 s, 4 s; as the queue's retries), then the job fails; the shards are merged
 * once all chunks are done.
 */
import type { Chunk, FarmJob } from '../../farm/job.ts';
import { jobChunks } from '../../farm/job.ts';
import { LanternError } from '../../errors.ts';
import { children, ChunkServer, mergeJob, runChunk } from './run-lantern.ts';

export const CHUNK_ATTEMPTS = 4;
export const BACKOFF_MS = 1000;

export interface LocalRunReport {
  readonly chunks: number;
  readonly rendered: number;
  readonly reused: number;
  readonly retries: number;
  readonly seconds: number;
  readonly mergeSeconds: number;
  readonly adapters: readonly string[];
  readonly outputs: readonly string[];
}

export async function runLocal(job: FarmJob, workers: number, log: (line: string) => void): Promise<LocalRunReport> {
  const chunks = jobChunks(job);
  const t0 = performance.now();
  let next = 0;
  let rendered = 0, reused = 0, retries = 0;
  const adapters = new Set<string>();
  const abort = new AbortController();
  // Each slot's chunks render in its own chunk server; the merge runs in the server of the slot
  // that finished last, which has the device and the scene ready.
  const servers = Array.from({ length: Math.min(workers, chunks.length) }, () => new ChunkServer(children));
  let lastDone = 0;
  const slot = async (k: number): Promise<void> => {
    await slotChunks(k, servers[k]!);
    lastDone = k;
  };
  const slotChunks = async (k: number, server: ChunkServer): Promise<void> => {
    while (next < chunks.length && !abort.signal.aborted) {
      const chunk: Chunk = chunks[next++]!;
      for (let attempt = 1; ; attempt++) {
        try {
          const r = await runChunk(job, chunk, abort.signal, server);
          if (r.reused) reused++;
          else rendered++;
          if (r.adapter) adapters.add(r.adapter);
          log(`worker ${k}: ${chunk.id} (${chunk.values[0]}-${chunk.values[chunk.values.length - 1]}) ${r.reused ? 'already done' : `in ${r.seconds.toFixed(2)} s on ${r.adapter}`}`);
          break;
        } catch (e) {
          if (abort.signal.aborted) return;
          if (attempt >= CHUNK_ATTEMPTS) {
            abort.abort();
            throw new LanternError(`job ${job.name}: ${chunk.id} failed ${attempt} times, the last: ${(e as Error).message}`);
          }
          retries++;
          const wait = BACKOFF_MS * 2 ** (attempt - 1);
          log(`worker ${k}: ${chunk.id} failed (${(e as Error).message}); again in ${wait / 1000} s`);
          await new Promise((r) => setTimeout(r, wait));
        }
      }
    }
  };
  let merged: Awaited<ReturnType<typeof mergeJob>>;
  try {
    await Promise.all(servers.map((_, k) => slot(k)));
    merged = await mergeJob(job, chunks, undefined, servers[lastDone]);
  } finally {
    for (const server of servers) server.stop();
  }
  return { chunks: chunks.length, rendered, reused, retries, seconds: (performance.now() - t0) / 1000, mergeSeconds: merged.seconds, adapters: [...adapters], outputs: merged.outputs };
}
