/**
 * The farm on BullMQ (Redis): `farm submit` adds a flow, a parent "merge" job on the lantern-merge
 * queue waiting for one child per chunk on lantern-chunks; `farm worker` takes chunks (one process a
 * GPU) and merges; `farm status` reads the jobs' states; `farm cancel` stops a job.
 *
 * - Ids are deterministic: `<job name>-<hash of the job>` and `…-chunk-0003`, so submitting the same
 *   job again adds nothing (BullMQ keeps one job per id), and status finds every chunk by id.
 * - Retries: a failed chunk is tried again (5 attempts, exponential backoff from 2 s); after the
 *   last, its parent fails (failParentOnFailure).
 * - Stalls: a worker renews its chunk's lock every lockDuration / 2; a worker that dies stops, the
 *   lock expires, and another worker's stalled check puts the chunk back in the queue (a worker
 *   killed mid-chunk loses that chunk's time, not the job).
 * - Idempotence: a chunk whose outputs are in the shared folder is not rendered again
 *   (run-lantern.ts runChunk), and outputs are renamed into place whole.
 * - Cancellation: a key in Redis that workers check before a chunk and every second during one (the
 *   render child is ended), and the flow's waiting jobs are removed.
 */
import { hostname } from 'node:os';
import type { FlowProducer as FlowProducerType, Job, Queue as QueueType, Worker as WorkerType } from 'bullmq';
import { LanternError } from '../../errors.ts';
import { jobChunks, type Chunk, type FarmJob } from '../../farm/job.ts';
import { children, ChunkServer, jobKey, mergeJob, runChunk } from './run-lantern.ts';
import { acquireNodeGpu } from '../dawn.ts';
import { gpuIdentity, holdGpu, type LeaseClient } from './gpu-lease.ts';

export const CHUNK_QUEUE = 'lantern-chunks';
export const MERGE_QUEUE = 'lantern-merge';
const JOBS_KEY = 'lantern:farm:jobs';
const cancelKey = (key: string) => `lantern:farm:cancelled:${key}`;

export const CHUNK_ATTEMPTS = 5;
export const CHUNK_BACKOFF_MS = 2000;

interface ChunkData {
  readonly key: string;
  readonly job: FarmJob;
  readonly chunk: Chunk;
}
interface MergeData {
  readonly key: string;
  readonly job: FarmJob;
}

export { jobKey };

/** A Redis URL as BullMQ's connection options (redis://host:port/db; rediss:// for TLS). */
export function connectionOf(url: string): { host: string; port: number; db: number; password?: string; username?: string; tls?: object; maxRetriesPerRequest: null } {
  let u: URL;
  try {
    u = new URL(url);
  } catch {
    throw new LanternError(`--redis must be a URL such as redis://127.0.0.1:6379, not '${url}'`);
  }
  if (u.protocol !== 'redis:' && u.protocol !== 'rediss:') throw new LanternError(`--redis must be a redis:// or rediss:// URL, not '${url}'`);
  const db = u.pathname && u.pathname !== '/' ? Number(u.pathname.slice(1)) : 0;
  if (!Number.isInteger(db) || db < 0) throw new LanternError(`--redis: '${u.pathname.slice(1)}' is not a database number`);
  return {
    host: u.hostname || '127.0.0.1',
    port: u.port ? Number(u.port) : 6379,
    db,
    ...(u.password ? { password: decodeURIComponent(u.password) } : {}),
    ...(u.username ? { username: decodeURIComponent(u.username) } : {}),
    ...(u.protocol === 'rediss:' ? { tls: {} } : {}),
    // BullMQ's workers block on Redis: ioredis must not give up on a command.
    maxRetriesPerRequest: null,
  };
}

async function bullmq(): Promise<typeof import('bullmq')> {
  return import('bullmq');
}

/** Checks that Redis answers within a few seconds: a wrong URL is one line, not a hang. */
async function reachable(queue: QueueType, url: string): Promise<void> {
  const client = await Promise.race([queue.client, new Promise<never>((_, fail) => setTimeout(() => fail(new Error('timeout')), 5000))]).catch(() => undefined);
  if (!client) {
    await queue.close().catch(() => undefined);
    throw new LanternError(`cannot reach Redis at ${url}`, 'Start redis-server, or give --redis the URL it listens on');
  }
}

/** Opens the chunk and merge queues on Redis at `url`, checks it answers, runs `use`, and closes both. */
async function withQueues<T>(url: string, use: (chunkQueue: QueueType, mergeQueue: QueueType) => Promise<T>): Promise<T> {
  const { Queue } = await bullmq();
  const connection = connectionOf(url);
  const chunkQueue = new Queue(CHUNK_QUEUE, { connection });
  const mergeQueue = new Queue(MERGE_QUEUE, { connection });
  try {
    await reachable(chunkQueue, url);
    return await use(chunkQueue, mergeQueue);
  } finally {
    await chunkQueue.close();
    await mergeQueue.close();
  }
}

export async function submit(job: FarmJob, url: string): Promise<{ key: string; chunks: number; added: boolean }> {
  const { FlowProducer, Queue } = await bullmq();
  const connection = connectionOf(url);
  const queue = new Queue(MERGE_QUEUE, { connection });
  await reachable(queue, url);
  const key = jobKey(job);
  const chunks = jobChunks(job);
  const existing = await queue.getJob(`${key}-merge`);
  const flow: FlowProducerType = new FlowProducer({ connection });
  try {
    if (!existing) {
      await flow.add({
        name: 'merge',
        queueName: MERGE_QUEUE,
        data: { key, job } satisfies MergeData,
        opts: { jobId: `${key}-merge`, attempts: 3, backoff: { type: 'exponential', delay: CHUNK_BACKOFF_MS } },
        children: chunks.map((chunk) => ({
          name: chunk.id,
          queueName: CHUNK_QUEUE,
          data: { key, job, chunk } satisfies ChunkData,
          opts: { jobId: `${key}-${chunk.id}`, attempts: CHUNK_ATTEMPTS, backoff: { type: 'exponential', delay: CHUNK_BACKOFF_MS }, failParentOnFailure: true },
        })),
      });
      const client = await queue.client;
      await client.hset(JOBS_KEY, { [key]: job.name });
      await client.del(cancelKey(key));
    }
    return { key, chunks: chunks.length, added: !existing };
  } finally {
    await flow.close();
    await queue.close();
  }
}

export interface WorkerOptions {
  readonly name: string;
  /** Seconds a chunk's lock lasts without renewal; a dead worker's chunk goes back after about this long. */
  readonly lockSeconds: number;
  readonly log: (line: string) => void;
  /** Stop after this many chunks (tests; 0: run until stopped). */
  readonly maxChunks?: number;
  /** Render on a GPU other workers render on too (they must say so as well): N workers on one GPU on purpose. */
  readonly shareGpu?: boolean;
}

/** Runs a worker until SIGINT / SIGTERM: chunks one at a time, and merges when a job's chunks are all done. */
export async function runWorker(url: string, o: WorkerOptions): Promise<void> {
  const { Worker, Queue, UnrecoverableError } = await bullmq();
  const connection = connectionOf(url);
  const probe = new Queue(CHUNK_QUEUE, { connection });
  await reachable(probe, url);
  const client = await probe.client;
  const cancelled = async (key: string) => (await client.get(cancelKey(key))) !== null;
  const watch = (key: string, abort: AbortController) => {
    const timer = setInterval(() => {
      cancelled(key).then((c) => c && abort.abort(), () => undefined);
    }, 1000);
    return () => clearInterval(timer);
  };
  // The adapter this process's environment gives (its chunks' render children inherit it): logged,
  // so that two workers on one GPU show (docs/farm.md, GPU selection).
  const gpu = await acquireNodeGpu({ onNote: () => {} });
  const identity = gpuIdentity(gpu.adapterName);
  gpu.device.destroy();
  // One worker a GPU, unless they share it on purpose (gpu-lease.ts): a second one is refused here.
  let release: () => Promise<void>;
  try {
    release = await holdGpu(client as unknown as LeaseClient, identity, o.name, o.shareGpu ?? false);
  } catch (e) {
    await probe.close();
    throw e;
  }
  o.log(`${o.name}: adapter ${gpu.adapterName}, GPU known as ${identity.described}${o.shareGpu ? ', shared with other workers (--share-gpu)' : ''}`);
  const lockDuration = o.lockSeconds * 1000;
  const settings = { connection, concurrency: 1, lockDuration, stalledInterval: lockDuration, maxStalledCount: 3, name: o.name };
  let done = 0;
  // Its chunks render one after another in one chunk server, which keeps the device and the scene.
  const server = new ChunkServer(children);
  const stopped = new Promise<void>((resolve) => {
    const stop = () => resolve();
    process.once('SIGINT', stop);
    process.once('SIGTERM', stop);
  });
  let finish: () => void = () => {};
  const enough = new Promise<void>((resolve) => (finish = resolve));
  const chunks: WorkerType = new Worker(
    CHUNK_QUEUE,
    async (bj: Job<ChunkData>) => {
      const { key, job, chunk } = bj.data;
      if (await cancelled(key)) throw new UnrecoverableError(`job ${key} was cancelled`);
      o.log(`${o.name}: ${key} ${chunk.id} (${chunk.values[0]}-${chunk.values[chunk.values.length - 1]}), attempt ${bj.attemptsMade + 1}`);
      const abort = new AbortController();
      const unwatch = watch(key, abort);
      try {
        const r = await runChunk(job, chunk, abort.signal, server);
        o.log(`${o.name}: ${key} ${chunk.id} ${r.reused ? 'already done (its files were there)' : `done in ${r.seconds.toFixed(2)} s on adapter ${r.adapter}`}`);
        return { adapter: r.adapter, seconds: r.seconds, reused: r.reused, worker: o.name };
      } catch (e) {
        if (abort.signal.aborted) throw new UnrecoverableError(`job ${key} was cancelled`);
        throw e;
      } finally {
        unwatch();
        if (o.maxChunks && ++done >= o.maxChunks) finish();
      }
    },
    settings,
  );
  const merges: WorkerType = new Worker(
    MERGE_QUEUE,
    async (bj: Job<MergeData>) => {
      const { key, job } = bj.data;
      if (await cancelled(key)) throw new UnrecoverableError(`job ${key} was cancelled`);
      const r = await mergeJob(job, jobChunks(job), undefined, server);
      o.log(`${o.name}: ${key} merged in ${r.seconds.toFixed(2)} s${r.outputs.length ? ` -> ${r.outputs.join(' and ')}` : ''}`);
      return { seconds: r.seconds, outputs: r.outputs, worker: o.name };
    },
    settings,
  );
  for (const w of [chunks, merges]) {
    w.on('failed', (bj, e) => {
      if (!bj) return;
      bj.getState().then((state) => o.log(`${o.name}: ${bj.id} failed: ${e.message}${state === 'failed' ? '' : ' (will be retried)'}`), () => undefined);
    });
  }
  o.log(`${o.name}: waiting for chunks on ${url} (${CHUNK_QUEUE}, lock ${o.lockSeconds} s)`);
  await Promise.race([stopped, enough]);
  server.stop();
  for (const child of children) child.kill('SIGTERM');
  await Promise.all([chunks.close(), merges.close()]);
  await release();
  await probe.close();
}

export interface JobStatus {
  readonly key: string;
  readonly chunks: number;
  readonly done: number;
  readonly failed: number;
  readonly active: readonly { readonly chunk: string; readonly worker: string; readonly seconds: number }[];
  /** Chunks a second since the first started, and the seconds left at that rate. */
  readonly rate?: number;
  /** Frames a second (a Frame job) or samples a second (a Sample job) at that rate. */
  readonly frameRate?: number;
  readonly sampleRate?: number;
  readonly etaSeconds?: number;
  readonly merge: string;
  readonly cancelled: boolean;
  readonly outputs: readonly string[];
}

export async function status(url: string, only?: string): Promise<JobStatus[]> {
  return withQueues(url, async (chunkQueue, mergeQueue) => {
    const client = await chunkQueue.client;
    const keys = Object.keys(await client.hgetall(JOBS_KEY)).filter((k) => !only || k === only || k.startsWith(`${only}-`)).sort();
    const out: JobStatus[] = [];
    for (const key of keys) {
      const parent = await mergeQueue.getJob(`${key}-merge`);
      if (!parent) continue;
      const job = (parent.data as MergeData).job;
      const chunks = jobChunks(job);
      let done = 0, failed = 0, first = Infinity, last = 0;
      const active: { chunk: string; worker: string; seconds: number }[] = [];
      for (const c of chunks) {
        const bj = await chunkQueue.getJob(`${key}-${c.id}`);
        const state = bj ? await bj.getState() : 'unknown';
        if (bj?.processedOn) first = Math.min(first, bj.processedOn);
        if (state === 'completed') {
          done++;
          last = Math.max(last, bj!.finishedOn ?? 0);
        } else if (state === 'failed') failed++;
        else if (state === 'active') active.push({ chunk: c.id, worker: bj!.processedBy ?? '?', seconds: (Date.now() - (bj!.processedOn ?? Date.now())) / 1000 });
      }
      const elapsed = done > 0 ? ((active.length > 0 ? Date.now() : last) - first) / 1000 : 0;
      const rate = done > 0 && elapsed > 0 ? done / elapsed : undefined;
      const mergeState = await parent.getState();
      const outputs = mergeState === 'completed' ? ((parent.returnvalue as { outputs?: string[] } | undefined)?.outputs ?? []) : [];
      out.push({
        key,
        chunks: chunks.length,
        done,
        failed,
        active,
        ...(rate !== undefined ? { rate, [job.kind === 'frames' ? 'frameRate' : 'sampleRate']: (rate * job.values.length) / chunks.length, etaSeconds: (chunks.length - done) / rate } : {}),
        merge: mergeState,
        cancelled: (await client.get(cancelKey(key))) !== null,
        outputs,
      });
    }
    return out;
  });
}

/** Marks a job cancelled (workers end its running chunks) and removes its waiting jobs. */
export async function cancel(url: string, key: string): Promise<number> {
  return withQueues(url, async (chunkQueue, mergeQueue) => {
    const client = await chunkQueue.client;
    const parent = await mergeQueue.getJob(`${key}-merge`);
    if (!parent) throw new LanternError(`no farm job ${key} on this Redis`, 'See `lantern farm status --redis URL` for the jobs it holds');
    await client.set(cancelKey(key), '1');
    let removed = 0;
    for (const c of jobChunks((parent.data as MergeData).job)) {
      const bj = await chunkQueue.getJob(`${key}-${c.id}`);
      if (bj && ['waiting', 'delayed', 'prioritized', 'waiting-children'].includes(await bj.getState())) {
        await bj.remove().then(() => removed++, () => undefined);
      }
    }
    return removed;
  });
}

/** A text progress bar: [##########..........] 8/16. */
export function progressBar(done: number, total: number, width = 20): string {
  const n = total > 0 ? Math.round((done / total) * width) : 0;
  return `[${'#'.repeat(n)}${'.'.repeat(width - n)}] ${done}/${total}`;
}

export const defaultWorkerName = (): string => `${hostname()}:${process.pid}`;
