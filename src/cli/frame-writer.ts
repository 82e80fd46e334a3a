/**
 * Writes a frame sequence's files on worker threads of this bundle while the GPU renders the next
 * frames (render --frames): a 1080p frame's PNG takes longer to filter and compress than the GPU
 * takes to render it, so a sequence written in the render's thread kept the GPU idle most of the
 * time (E1M1, 240 frames at 1080p, 4 spp: 0.63 s a frame on the H200, docs/farm.md). The encoders
 * are the ones a still's files use (PNG through Node's zlib, EXR), so a file's bytes do not depend
 * on the thread that wrote it. At most two frames a thread wait, so memory stays bounded.
 *
 * Run from sources (tests), where there is no bundle to start a thread from, or with
 * LANTERN_START_THREADS=0, files are written in the calling thread.
 */
import { availableParallelism } from 'node:os';
import { isMainThread, parentPort, Worker, workerData } from 'node:worker_threads';
import { LanternError } from '../errors.ts';
import { encodeExr } from '../image/exr.ts';
import { encodePng } from '../image/png.ts';
import { nativeExrDeflate, nativeZlib, writeFile } from './output-files.ts';
import { bundlePath } from './scene-thread.ts';

const ROLE = 'lantern-frame-writer';

type FrameFile = { readonly path: string; readonly width: number; readonly height: number } & ({ readonly kind: 'png'; readonly rgba: Uint8Array } | { readonly kind: 'exr'; readonly radiance: Float32Array });
type WriteReply = { readonly id: number; readonly error?: string };

function writeFrameFile(f: FrameFile): void {
  writeFile(f.path, f.kind === 'png' ? encodePng(f.width, f.height, f.rgba, nativeZlib) : encodeExr(f.width, f.height, f.radiance, {}, nativeExrDeflate));
}

/** Whether this thread is one of a FrameWriter's. */
export function isFrameWriterThread(): boolean {
  return !isMainThread && (workerData as { role?: string } | undefined)?.role === ROLE;
}

/** A writer thread: writes what it is sent until the writer ends it. */
export function runFrameWriterThread(): void {
  const port = parentPort!;
  port.on('message', (m: { id: number; file: FrameFile }) => {
    try {
      writeFrameFile(m.file);
      port.postMessage({ id: m.id } satisfies WriteReply);
    } catch (e) {
      port.postMessage({ id: m.id, error: e instanceof LanternError ? e.userMessage : (e as Error).message } satisfies WriteReply);
    }
  });
}

export class FrameWriter {
  private readonly threads: Worker[] = [];
  private readonly pending = new Set<number>();
  private readonly waiting: (() => void)[] = [];
  private nextId = 0;
  private next = 0;
  private failure: string | undefined;

  constructor(threads = Math.max(1, Math.min(4, availableParallelism() - 1))) {
    const bundle = bundlePath();
    if (!bundle) return;
    for (let k = 0; k < threads; k++) {
      const thread = new Worker(bundle, { workerData: { role: ROLE } });
      thread.on('message', (reply: WriteReply) => {
        if (reply.error !== undefined) this.failure ??= reply.error;
        this.pending.delete(reply.id);
        this.waiting.shift()?.();
      });
      // A thread that dies fails the sequence: nothing waits for what it held.
      const lost = (why: string) => {
        this.failure ??= `a frame-writing thread stopped: ${why}`;
        this.pending.clear();
        for (const wake of this.waiting.splice(0)) wake();
      };
      thread.on('error', (e: Error) => lost(e.message));
      thread.on('exit', (code) => {
        if (this.threads.includes(thread)) lost(`exit code ${code}`);
      });
      this.threads.push(thread);
    }
  }

  /** Hands a file to a thread (a PNG's pixels are moved there: not usable after), waiting while enough are queued. */
  async write(file: FrameFile): Promise<void> {
    this.throwFailure();
    if (this.threads.length === 0) return writeFrameFile(file);
    while (this.pending.size >= 2 * this.threads.length) await new Promise<void>((r) => this.waiting.push(r));
    this.throwFailure();
    const id = this.nextId++;
    this.pending.add(id);
    // A PNG's pixels move to the thread; an EXR's radiance is copied (the caller compares frames with it).
    const moved = file.kind === 'png' && file.rgba.buffer instanceof ArrayBuffer && file.rgba.byteLength === file.rgba.buffer.byteLength ? [file.rgba.buffer] : [];
    this.threads[this.next++ % this.threads.length]!.postMessage({ id, file }, moved);
  }

  /** Waits for every file handed over, ends the threads, and throws the first write's error. */
  async close(): Promise<void> {
    while (this.pending.size > 0 && this.threads.length > 0) await new Promise<void>((r) => this.waiting.push(r));
    const threads = this.threads.splice(0);
    await Promise.all(threads.map((t) => t.terminate()));
    this.throwFailure();
  }

  private throwFailure(): void {
    if (this.failure !== undefined) throw new LanternError(this.failure);
  }
}
