/**
 * The `lantern` program: every command registered on one commander program, for a context (how the
 * commands print and report errors). main.ts runs it once on process.argv; the farm's chunk server
 * (farm/chunk-server.ts) builds one per chunk.
 */
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
import type { CliContext } from './context.ts';
import { escapeControls } from './terminal-text.ts';

export interface ProgramOptions {
  /** Whether the context has reported a failure (the size limits are checked before any action). */
  readonly failed?: () => boolean;
  /** Settings the commands inherit (exitOverride, configureOutput), applied before they are added. */
  readonly configure?: (program: Command) => void;
}

/** The program, its global options and every command. */
export function buildProgram(context: CliContext, options: ProgramOptions = {}): Command {
  const failed = options.failed ?? (() => Boolean(process.exitCode));
  const program = new Command();
  program
    .name('lantern')
    .description('Lantern: a WebGPU path tracer, headless')
    .option('-v, --verbose', "show stack traces and details on errors, and Dawn's own diagnostics (its look for a GPU driver)")
    .option(`${LIMITS_OPTION} <list>`, `raise the size limits on input files, name=value,… (${LIMIT_NAMES.join(', ')}); also ${LIMITS_ENV}`)
    .showHelpAfterError('(run with --help for usage)')
    // Usage errors quote the command line, which may hold anything a script passed on.
    .configureOutput({ writeErr: (text) => process.stderr.write(escapeControls(text, { keepLines: true })) });
  options.configure?.(program);
  // The size limits (budgets.ts) are set before any file is read; a bad list stops here, in one line.
  program.hook('preAction', async () => {
    await context.run(async () => applyLimitsOption(program.opts().limits));
    if (failed()) throw new LimitsRefused();
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
  return program;
}

/** Thrown by the program when its --limits were refused (already reported by the context): no command runs. */
export class LimitsRefused extends Error {
  constructor() {
    super('the size limits were refused');
  }
}
