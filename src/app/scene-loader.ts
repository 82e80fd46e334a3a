/**
 * The page's side of the scene worker: promises for opening file sets and loading scenes, with
 * progress callbacks. One worker for the page's lifetime (it keeps an open WAD's textures between maps).
 */
import { LanternError } from '../errors.ts';
import type { EnvironmentImage } from '../scene/environment.ts';
import type { PathedFile } from './dropped-files.ts';
import type { WorkerReply, WorkerRequest } from './scene-protocol.ts';
import type { FileSetSummary, LoadedScene, NamedBytes, ProgressListener, SceneRequest } from './scene-request.ts';

interface Pending {
  resolve(reply: WorkerReply): void;
  reject(error: Error): void;
  onProgress?: ProgressListener;
}

export class SceneLoader {
  private readonly worker: Worker;
  private readonly pending = new Map<number, Pending>();
  private nextId = 1;

  constructor() {
    this.worker = new Worker(new URL('./scene-worker.ts', import.meta.url), { type: 'module', name: 'lantern scenes' });
    this.worker.onmessage = (event: MessageEvent<WorkerReply>) => this.receive(event.data);
    this.worker.onerror = (event) => {
      event.preventDefault();
      this.failAll(new Error(`the scene worker failed: ${event.message || 'it could not start'}`));
    };
  }

  /**
   * Opens one scene's files, sorted by the registry: the main files in load order, and their
   * siblings named by their path relative to the main file's folder (a glTF names its textures so).
   */
  async openFiles(format: string, files: readonly File[], siblings: readonly PathedFile[], baseUrl?: string): Promise<FileSetSummary> {
    const read = (f: File, name: string): Promise<NamedBytes> => f.arrayBuffer().then((b) => ({ name, bytes: new Uint8Array(b) }));
    const [main, beside] = await Promise.all([Promise.all(files.map((f) => read(f, f.name))), Promise.all(siblings.map((f) => read(f.file, f.path)))]);
    const request = { format, files: main, siblings: beside, ...(baseUrl ? { baseUrl } : {}) };
    const reply = await this.send({ id: this.nextId++, type: 'open-files', request }, [...main, ...beside].map((f) => f.bytes.buffer as ArrayBuffer));
    if (reply.type !== 'opened') throw new Error(`unexpected reply '${reply.type}' from the scene worker`);
    return reply.summary;
  }

  async load(request: SceneRequest, onProgress?: ProgressListener): Promise<LoadedScene> {
    const reply = await this.send({ id: this.nextId++, type: 'load', request }, [], onProgress);
    if (reply.type !== 'loaded') throw new Error(`unexpected reply '${reply.type}' from the scene worker`);
    return reply.loaded;
  }

  /** Decodes an HDR panorama (.hdr or .exr) in the worker; a file of another kind is a LanternError naming it. */
  async decodeEnvironment(file: File): Promise<EnvironmentImage> {
    const bytes = new Uint8Array(await file.arrayBuffer());
    const reply = await this.send({ id: this.nextId++, type: 'decode-environment', file: { name: file.name, bytes } }, [bytes.buffer]);
    if (reply.type !== 'environment-decoded') throw new Error(`unexpected reply '${reply.type}' from the scene worker`);
    return reply.image;
  }

  terminate(): void {
    this.worker.terminate();
    this.failAll(new Error('the scene worker was stopped'));
  }

  private send(message: WorkerRequest, transfer: Transferable[], onProgress?: ProgressListener): Promise<WorkerReply> {
    return new Promise((resolve, reject) => {
      this.pending.set(message.id, { resolve, reject, ...(onProgress ? { onProgress } : {}) });
      this.worker.postMessage(message, transfer);
    });
  }

  private receive(reply: WorkerReply): void {
    const pending = this.pending.get(reply.id);
    if (!pending) return;
    if (reply.type === 'progress') {
      pending.onProgress?.(reply.stage, reply.fraction);
      return;
    }
    this.pending.delete(reply.id);
    if (reply.type === 'error') {
      const { message, hint, user } = reply.error;
      pending.reject(user ? new LanternError(message, hint) : new Error(message));
    } else pending.resolve(reply);
  }

  private failAll(error: Error): void {
    for (const p of this.pending.values()) p.reject(error);
    this.pending.clear();
  }
}
