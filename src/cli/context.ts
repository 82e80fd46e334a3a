/** What every command shares: output, notes on stderr, and the one place errors are reported. */
import { LanternError } from '../errors.ts';

export interface CliContext {
  readonly verbose: () => boolean;
  print(line: string): void;
  note(line: string): void;
  /** Runs a command body; reports failures as one line (a stack trace with --verbose) and sets the exit code. */
  run(body: () => Promise<void>): Promise<void>;
}

export const EXIT_USER_ERROR = 1;
export const EXIT_INTERNAL_ERROR = 70;

export function createCliContext(verbose: () => boolean): CliContext {
  return {
    verbose,
    print: (line) => process.stdout.write(`${line}\n`),
    note: (line) => process.stderr.write(`lantern: ${line}\n`),
    async run(body) {
      try {
        await body();
      } catch (e) {
        if (e instanceof LanternError) {
          process.stderr.write(`lantern: error: ${e.userMessage}\n`);
          process.exitCode = EXIT_USER_ERROR;
        } else {
          process.stderr.write(`lantern: internal error: ${(e as Error)?.message ?? String(e)}${verbose() ? '' : ' (run with --verbose for details)'}\n`);
          process.exitCode = EXIT_INTERNAL_ERROR;
        }
        if (verbose() && e instanceof Error && e.stack) process.stderr.write(`${e.stack}\n`);
      }
    },
  };
}
