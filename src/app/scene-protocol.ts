/** Messages between the page (scene-loader.ts) and the scene worker (scene-worker.ts). */
import type { EnvironmentImage } from '../scene/environment.ts';
import type { FileSetSummary, LoadedScene, NamedBytes, OpenFilesRequest, SceneRequest } from './scene-request.ts';

export type WorkerRequest =
  | { readonly id: number; readonly type: 'open-files'; readonly request: OpenFilesRequest }
  | { readonly id: number; readonly type: 'load'; readonly request: SceneRequest }
  /** An HDR panorama (.hdr, .exr) to decode off the main thread. */
  | { readonly id: number; readonly type: 'decode-environment'; readonly file: NamedBytes };

export type WorkerReply =
  | { readonly id: number; readonly type: 'opened'; readonly summary: FileSetSummary }
  | { readonly id: number; readonly type: 'progress'; readonly stage: string; readonly fraction: number }
  | { readonly id: number; readonly type: 'loaded'; readonly loaded: LoadedScene }
  | { readonly id: number; readonly type: 'environment-decoded'; readonly image: EnvironmentImage }
  | { readonly id: number; readonly type: 'error'; readonly error: { readonly message: string; readonly hint?: string; readonly user: boolean } };
