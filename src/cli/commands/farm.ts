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
}
