/** Messages between the page (scene-loader.ts) and the scene worker (scene-worker.ts). */
import type { LoadedScene, NamedBytes, SceneRequest, WadSummary } from './scene-request.ts';

export type WorkerRequest =
  | { readonly id: number; readonly type: 'open-wads'; readonly files: readonly NamedBytes[] }
  | { readonly id: number; readonly type: 'load'; readonly request: SceneRequest };

export type WorkerReply =
  | { readonly id: number; readonly type: 'wads'; readonly summary: WadSummary }
  | { readonly id: number; readonly type: 'progress'; readonly stage: string; readonly fraction: number }
  | { readonly id: number; readonly type: 'loaded'; readonly loaded: LoadedScene }
  | { readonly id: number; readonly type: 'error'; readonly error: { readonly message: string; readonly hint?: string; readonly user: boolean } };
