/**
 * The `lantern` command line. The only code (with the rest of src/cli) that touches node:*; it drives
 * the same Renderer as the browser page.
 */
// First: it notes when the bundle started to run (the start-up timeline of `render --timings`).
import { bundleEvaluated } from './process-clock.ts';
import type { Command } from 'commander';
import { createCliContext } from './context.ts';
import { isChunkServer, serveChunks } from './farm/chunk-server.ts';
import { isFrameWriterThread, runFrameWriterThread } from './frame-writer.ts';
import { buildProgram, LimitsRefused } from './program.ts';
import { isSceneThread, runSceneThread } from './scene-thread.ts';
import { exitWhenDrained } from './terminal-text.ts';

bundleEvaluated();

// The same bundle started as a worker loads a scene for the main thread (scene-thread.ts) or writes
// a frame sequence's files (frame-writer.ts); started
// by a farm worker as its chunk server, it renders chunk after chunk (farm/chunk-server.ts).
if (isSceneThread()) await runSceneThread();
else if (isFrameWriterThread()) runFrameWriterThread();
else if (isChunkServer()) await serveChunks();
else await runCommand();

async function runCommand(): Promise<void> {
  let program: Command | undefined;
  const context = createCliContext(() => Boolean(program?.opts().verbose));
  program = buildProgram(context);
  // A reader that goes away early (`lantern info x.wad | head`) is not an error of the command.
  for (const stream of [process.stdout, process.stderr]) stream.on('error', (e: NodeJS.ErrnoException) => { if (e.code !== 'EPIPE') throw e; });
  try {
    await program.parseAsync(process.argv);
  } catch (e) {
    if (!(e instanceof LimitsRefused)) throw e;
  }
  // Dawn keeps native threads alive: leave once the command is done and its output has drained.
  await exitWhenDrained(Number(process.exitCode ?? 0));
}
