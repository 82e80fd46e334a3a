/**
 * The `lantern` command line. The only code (with the rest of src/cli) that touches node:*; it drives
 * the same Renderer as the browser page.
 */
// First: it notes when the bundle started to run (the start-up timeline of `render --timings`).
import { bundleEvaluated } from './process-clock.ts';
import { Command } from 'commander';
import { applyLimitsOption, LIMIT_NAMES, LIMITS_ENV, LIMITS_OPTION } from '../budgets.ts';
import { registerBench } from './commands/bench.ts';
import { registerBenchMatrix } from './commands/bench-matrix.ts';
import { registerBvhStats } from './commands/bvh-stats.ts';
import { registerConvert } from './commands/convert.ts';
import { registerDiff } from './commands/diff.ts';
import { registerInfo } from './commands/info.ts';
import { registerFarm } from './commands/farm.ts';
import { registerMerge } from './commands/merge.ts';
import { registerRender } from './commands/render.ts';
import { registerTextures } from './commands/textures.ts';
import { registerView } from './commands/view.ts';
import { createCliContext } from './context.ts';
import { isSceneThread, runSceneThread } from './scene-thread.ts';
import { escapeControls, exitWhenDrained } from './terminal-text.ts';

bundleEvaluated();

// The same bundle started as a worker loads a scene for the main thread (scene-thread.ts).
if (isSceneThread()) await runSceneThread();
else await runCommand();

async function runCommand(): Promise<void> {
  const program = new Command();
  const context = createCliContext(() => Boolean(program.opts().verbose));

  program
    .name('lantern')
    .description('Lantern: a WebGPU path tracer, headless')
    .option('-v, --verbose', "show stack traces and details on errors, and Dawn's own diagnostics (its look for a GPU driver)")
    .option(`${LIMITS_OPTION} <list>`, `raise the size limits on input files, name=value,… (${LIMIT_NAMES.join(', ')}); also ${LIMITS_ENV}`)
    .showHelpAfterError('(run with --help for usage)')
    // Usage errors quote the command line, which may hold anything a script passed on.
    .configureOutput({ writeErr: (text) => process.stderr.write(escapeControls(text, { keepLines: true })) });
  // The size limits (budgets.ts) are set before any file is read; a bad list stops here, in one line.
  program.hook('preAction', async () => {
    await context.run(async () => applyLimitsOption(program.opts().limits));
    if (process.exitCode) process.exit(process.exitCode);
  });

  registerRender(program, context);
  registerBench(program, context);
  registerBenchMatrix(program, context);
  registerInfo(program, context);
  registerBvhStats(program, context);
  registerConvert(program, context);
  registerTextures(program, context);
  registerView(program, context);
  registerDiff(program, context);
  registerMerge(program, context);
  registerFarm(program, context);

  // A reader that goes away early (`lantern info x.wad | head`) is not an error of the command.
  for (const stream of [process.stdout, process.stderr]) stream.on('error', (e: NodeJS.ErrnoException) => { if (e.code !== 'EPIPE') throw e; });
  await program.parseAsync(process.argv);
  // Dawn keeps native threads alive: leave once the command is done and its output has drained.
  await exitWhenDrained(Number(process.exitCode ?? 0));
}
