/** Messages between the page (scene-loader.ts) and the scene worker (scene-worker.ts). */
import type { FileSetSummary, LoadedScene, OpenFilesRequest, SceneRequest } from './scene-request.ts';

export type WorkerRequest =
  | { readonly id: number; readonly type: 'open-files'; readonly request: OpenFilesRequest }
  | { readonly id: number; readonly type: 'load'; readonly request: SceneRequest };

export type WorkerReply =
  | { readonly id: number; readonly type: 'opened'; readonly summary: FileSetSummary }
  | { readonly id: number; readonly type: 'progress'; readonly stage: string; readonly fraction: number }
  | { readonly id: number; readonly type: 'loaded'; readonly loaded: LoadedScene }
  | { readonly id: number; readonly type: 'error'; readonly error: { readonly message: string; readonly hint?: string; readonly user: boolean } };
