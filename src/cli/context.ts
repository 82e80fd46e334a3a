/**
 * What every command shares: output, notes on stderr, and the one place errors are reported. All
 * three escape control characters (terminal-text.ts): names quoted from files appear in them.
 */
import { LanternError } from '../errors.ts';
import { escapeControls } from './terminal-text.ts';
import type { SessionCache } from './session-cache.ts';

export interface CliContext {
  readonly verbose: () => boolean;
  print(line: string): void;
  /** Information on stderr: `lantern: line`. */
  note(line: string): void;
  /** A warning on stderr (what a loader worked around): `lantern: warning: line`, apart from information. */
  warn(line: string): void;
  /** Dawn's and the Vulkan loader's own output (their look for a GPU): on stderr with --verbose only. */
  dawnOutput(text: string): void;
  /** The command line the command runs (process.argv, or a chunk's in the farm's chunk server). */
  readonly argv: readonly string[];
  /** What a long-lived process keeps between commands (session-cache.ts); none in a one-command process. */
  readonly sessions?: SessionCache;
  /** Runs a command body; reports failures as one line (a stack trace with --verbose) and sets the exit code. */
  run(body: () => Promise<void>): Promise<void>;
}

export const EXIT_USER_ERROR = 1;
export const EXIT_INTERNAL_ERROR = 70;

export function createCliContext(verbose: () => boolean): CliContext {
  return {
    verbose,
    argv: process.argv,
    print: (line) => process.stdout.write(`${escapeControls(line, { keepLines: true })}\n`),
    note: (line) => process.stderr.write(`lantern: ${escapeControls(line, { keepLines: true })}\n`),
    warn: (line) => process.stderr.write(`lantern: warning: ${escapeControls(line, { keepLines: true })}\n`),
    dawnOutput: (text) => {
      if (verbose()) process.stderr.write(escapeControls(text, { keepLines: true }));
    },
    async run(body) {
      try {
        await body();
      } catch (e) {
        if (e instanceof LanternError) {
          // One line whatever the message quotes.
          process.stderr.write(`lantern: error: ${escapeControls(e.userMessage)}\n`);
          process.exitCode = EXIT_USER_ERROR;
        } else {
          process.stderr.write(`lantern: internal error: ${escapeControls((e as Error)?.message ?? String(e))}${verbose() ? '' : ' (run with --verbose for details)'}\n`);
          process.exitCode = EXIT_INTERNAL_ERROR;
        }
        if (verbose() && e instanceof Error && e.stack) process.stderr.write(`${escapeControls(e.stack, { keepLines: true })}\n`);
      }
    },
  };
}
