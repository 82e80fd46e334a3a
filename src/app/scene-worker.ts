/**
 * The scene worker: opens files of any registered format (WADs, meshes, glTF), decodes HDR environment maps, builds the BVH and packs the scene off the main thread,
 * so that the page keeps drawing (and the progress bar keeps moving) while a level loads. Protocol:
 * scene-protocol.ts. Errors travel back as message + hint and become LanternErrors again.
 */
import { LanternError } from '../errors.ts';
import { loadEnvironmentImage } from '../loaders/environment-image.ts';
import { SceneRequests, transferables } from './scene-request.ts';
import { webBvhPool } from './bvh-workers.ts';
import type { WorkerReply, WorkerRequest } from './scene-protocol.ts';

/** Siblings of a served file (a glTF's textures), fetched beside it; a 404 is a missing file, not an error. */
async function fetchFile(url: string): Promise<Uint8Array | undefined> {
  const response = await fetch(url);
  if (response.status === 404) return undefined;
  if (!response.ok) throw new LanternError(`cannot fetch '${url}': HTTP ${response.status}`);
  return new Uint8Array(await response.arrayBuffer());
}

// BVH build workers, started by the first scene big enough to use them.
const requests = new SceneRequests(fetchFile, webBvhPool);
const post = (reply: WorkerReply, transfer: Transferable[] = []) => (self as unknown as Worker).postMessage(reply, transfer);

self.onmessage = async (event: MessageEvent<WorkerRequest>) => {
  const message = event.data;
  const { id } = message;
  try {
    if (message.type === 'open-files') {
      post({ id, type: 'opened', summary: await requests.openFiles(message.request) });
    } else if (message.type === 'decode-environment') {
      // A 4k panorama takes a moment to decode: here, the page keeps drawing meanwhile.
      const image = loadEnvironmentImage(message.file.bytes, message.file.name);
      post({ id, type: 'environment-decoded', image }, [image.rgb.buffer as ArrayBuffer]);
    } else {
      const loaded = await requests.load(message.request, (stage, fraction) => post({ id, type: 'progress', stage, fraction }));
      // The freshly built arrays move to the page without a copy; the scene itself is copied, since
      // the worker keeps its textures for the next map of the same WAD.
      const { triangles, bvh, packed } = loaded.prepared;
      post({ id, type: 'loaded', loaded }, transferables({ triangles, bvh, packed }));
    }
  } catch (e) {
    const error = e instanceof LanternError ? { message: e.message, ...(e.hint ? { hint: e.hint } : {}), user: true } : { message: (e as Error)?.message ?? String(e), user: false };
    post({ id, type: 'error', error });
  }
};
