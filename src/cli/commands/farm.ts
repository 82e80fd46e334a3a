/**
 * `lantern farm`: a render split into chunks (a job file: docs/farm.md) run on local worker
 * processes (`farm run job.json --local N`) or through BullMQ on Redis (`farm submit`, `farm
 * worker`, `farm status`, `farm cancel`).
 */
import type { Command } from 'commander';
import type { CliContext } from '../context.ts';
import { integerOption } from '../options.ts';
import { readJobFile } from '../farm/job-file.ts';
import { runLocal } from '../farm/local.ts';
import { cancel, defaultWorkerName, progressBar, runWorker, status, submit } from '../farm/queue.ts';
import { InvalidArgumentError } from 'commander';

const REDIS_HELP = 'the Redis server, such as redis://127.0.0.1:6379 (Debian: apt-get install redis-server)';

function redisOption(value: string): string {
  if (!/^rediss?:\/\//.test(value)) throw new InvalidArgumentError(`--redis must be a redis:// URL, not '${value}'.`);
  return value;
}

export function registerFarm(program: Command, context: CliContext): void {
  const farm = program.command('farm').description('split a render into chunks over worker processes and machines, merged exactly (docs/farm.md)');
  farm
    .command('run')
    .description('run a job on N local worker processes, without Redis')
    .argument('<job.json>', 'the job file')
    .requiredOption('--local <n>', 'worker processes on this machine', integerOption('--local', 1, 64))
    .option('--json', 'print what was done as JSON')
    .action((file: string, o: { local: number; json?: boolean }) =>
      context.run(async () => {
        const job = readJobFile(file);
        const report = await runLocal(job, o.local, (line) => context.note(line));
        if (o.json) context.print(JSON.stringify({ job: job.name, ...report }, null, 2));
        else context.print(`job ${job.name}: ${report.chunks} chunks (${report.rendered} rendered, ${report.reused} already done, ${report.retries} retries) on ${o.local} workers in ${report.seconds.toFixed(2)} s${report.outputs.length ? `, merged in ${report.mergeSeconds.toFixed(2)} s -> ${report.outputs.join(' and ')}` : ` -> ${job.output.folder}`}`);
      }),
    );
  farm
    .command('submit')
    .description('put a job on the queue: its chunks, and a merge job that waits for them (BullMQ flow); the same job again adds nothing')
    .argument('<job.json>', 'the job file (its output folder must be at the same path on every worker: a shared folder)')
    .requiredOption('--redis <url>', REDIS_HELP, redisOption)
    .action((file: string, o: { redis: string }) =>
      context.run(async () => {
        const job = readJobFile(file);
        const r = await submit(job, o.redis);
        context.print(r.added ? `submitted ${r.key}: ${r.chunks} chunks and a merge on ${o.redis} -> ${job.output.folder}` : `${r.key} is already on ${o.redis} (the same job): nothing added`);
      }),
    );
  farm
    .command('worker')
    .description('take chunks (and merges) from the queue until stopped (SIGINT/SIGTERM); run one a GPU')
    .requiredOption('--redis <url>', REDIS_HELP, redisOption)
    .option('--name <name>', 'how status names this worker (default host:pid)')
    .option('--lock-seconds <s>', "a chunk's lock without renewal: a dead worker's chunk is handed out again after about this long", integerOption('--lock-seconds', 1, 3600), 30)
    .option('--max-chunks <n>', 'leave after this many chunks', integerOption('--max-chunks', 1, 1_000_000))
    .option('--share-gpu', 'render on a GPU that other workers started with --share-gpu render on too (by default a second worker on one GPU is refused)')
    .action((o: { redis: string; name?: string; lockSeconds: number; maxChunks?: number; shareGpu?: boolean }) =>
      context.run(() => runWorker(o.redis, { name: o.name ?? defaultWorkerName(), lockSeconds: o.lockSeconds, log: (line) => context.note(line), ...(o.maxChunks ? { maxChunks: o.maxChunks } : {}), ...(o.shareGpu ? { shareGpu: true } : {}) })),
    );
  farm
    .command('status')
    .description('chunks done, rate, time left and which worker holds which chunk, for each job on the queue')
    .requiredOption('--redis <url>', REDIS_HELP, redisOption)
    .option('--job <key>', 'only this job (its key, or its name)')
    .option('--json', 'print as JSON')
    .action((o: { redis: string; job?: string; json?: boolean }) =>
      context.run(async () => {
        const jobs = await status(o.redis, o.job);
        if (o.json) return context.print(JSON.stringify(jobs, null, 2));
        if (jobs.length === 0) return context.print(`no farm jobs on ${o.redis}`);
        for (const j of jobs) {
          const per = j.frameRate !== undefined ? ` (${j.frameRate.toPrecision(3)} frames/s)` : j.sampleRate !== undefined ? ` (${j.sampleRate.toPrecision(3)} spp/s)` : '';
          const rate = j.rate !== undefined ? `, ${j.rate.toFixed(3)} chunks/s${per}, ${j.etaSeconds! > 0 ? `${j.etaSeconds!.toFixed(0)} s left` : 'all rendered'}` : '';
          context.print(`${j.key} ${progressBar(j.done, j.chunks)}${j.failed ? `, ${j.failed} failed` : ''}${rate}; merge ${j.merge}${j.cancelled ? ' (cancelled)' : ''}${j.outputs.length ? ` -> ${j.outputs.join(' and ')}` : ''}`);
          for (const a of j.active) context.print(`  ${a.chunk} on ${a.worker} for ${a.seconds.toFixed(0)} s`);
        }
      }),
    );
  farm
    .command('cancel')
    .description('stop a job: its waiting chunks are removed and workers end its running ones')
    .argument('<key>', 'the job key farm submit printed (name-hash)')
    .requiredOption('--redis <url>', REDIS_HELP, redisOption)
    .action((key: string, o: { redis: string }) =>
      context.run(async () => {
        const removed = await cancel(o.redis, key);
        context.print(`cancelled ${key}: ${removed} waiting chunks removed; running ones end within a second`);
      }),
    );
}
