/**
 * The farm's chunk server: a `lantern` child of a worker (one a worker slot) that renders the
 * worker's chunks one after another in one process, instead of a process a chunk. It keeps the GPU
 * device and the job's scene as loaded (session-cache.ts) from chunk to chunk; each chunk
 * still gets a fresh Renderer and its own copy of the scene, so its files are those a fresh process
 * writes, byte for byte. What it saves a chunk: the process start, Dawn's start, the scene's load
 * and BVH, and the pipeline compiles (a device makes again a pipeline it made before at no cost).
 *
 * The worker side (run-lantern.ts ChunkServer) speaks to it over Node's IPC channel: a request is a command
 * line (`render …  --json`), the reply its printed report or its one-line error. A Dawn or internal
 * failure ends the server after its reply, and the next chunk starts a fresh one; an ended chunk
 * (cancellation) kills it. The server leaves when its worker goes away, even killed.
 */
import { LanternError } from '../../errors.ts';
import type { CliContext } from '../context.ts';
import { buildProgram, LimitsRefused } from '../program.ts';
import type { SessionCache } from '../session-cache.ts';
import { escapeControls } from '../terminal-text.ts';
import { SERVER_ENV, type ChunkReply as Reply, type ChunkRequest as Request } from './run-lantern.ts';

/** Whether this process was started as a chunk server (by ChunkServer, with its IPC channel). */
export function isChunkServer(): boolean {
  return process.env[SERVER_ENV] === '1' && typeof process.send === 'function';
}

/** Serves chunk requests one at a time until the worker goes away. */
export async function serveChunks(): Promise<void> {
  // Not inherited by what this process starts.
  delete process.env[SERVER_ENV];
  const sessions: SessionCache = {};
  let queue = Promise.resolve();
  const gone = new Promise<void>((resolve) => process.once('disconnect', resolve));
  const send = process.send!.bind(process);
  process.on('message', (request: Request) => {
    queue = queue.then(async () => {
      const { reply, internal } = await runRequest(request, sessions);
      // A GPU or internal failure leaves nothing to trust: the next chunk gets a fresh process.
      send(reply, undefined, {}, () => {
        if (internal) process.disconnect?.();
      });
    });
  });
  await gone;
  // The worker is gone (done, or killed): so is its GPU work.
  process.exit(0);
}

async function runRequest(request: Request, sessions: SessionCache): Promise<{ reply: Reply; internal: boolean }> {
  const printed: string[] = [];
  let failure: string | undefined;
  let internal = false;
  const context: CliContext = {
    verbose: () => false,
    argv: [process.argv[0]!, process.argv[1]!, ...request.args],
    sessions,
    print: (line) => printed.push(line),
    note: (line) => process.stderr.write(`lantern: ${escapeControls(line, { keepLines: true })}\n`),
    warn: (line) => process.stderr.write(`lantern: warning: ${escapeControls(line, { keepLines: true })}\n`),
    dawnOutput: () => {},
    async run(body) {
      try {
        await body();
      } catch (e) {
        if (e instanceof LanternError) failure = e.userMessage;
        else {
          failure = `internal error: ${(e as Error)?.message ?? String(e)}`;
          internal = true;
        }
      }
    },
  };
  // Usage errors end the request, not the process, and are its reply.
  const program = buildProgram(context, {
    failed: () => failure !== undefined,
    configure: (p) => p.exitOverride().configureOutput({ writeOut: () => {}, writeErr: (text) => (failure ??= text.trim().split('\n')[0]!.replace(/^error: /, '')) }),
  });
  try {
    await program.parseAsync([...context.argv]);
  } catch (e) {
    if (!(e instanceof LimitsRefused)) failure ??= (e as Error).message.replace(/^error: /, '');
  }
  return { reply: failure === undefined ? { id: request.id, ok: true, stdout: printed.join('\n') } : { id: request.id, ok: false, error: failure }, internal };
}
