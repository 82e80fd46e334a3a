/**
 * The scene worker: parses WADs and meshes, builds the BVH and packs the scene off the main thread,
 * so that the page keeps drawing (and the progress bar keeps moving) while a level loads. Protocol:
 * scene-protocol.ts. Errors travel back as message + hint and become LanternErrors again.
 */
import { LanternError } from '../errors.ts';
import { SceneRequests, transferables } from './scene-request.ts';
import type { WorkerReply, WorkerRequest } from './scene-protocol.ts';

const requests = new SceneRequests();
const post = (reply: WorkerReply, transfer: Transferable[] = []) => (self as unknown as Worker).postMessage(reply, transfer);

self.onmessage = (event: MessageEvent<WorkerRequest>) => {
  const message = event.data;
  const { id } = message;
  try {
    if (message.type === 'open-wads') {
      post({ id, type: 'wads', summary: requests.openWads(message.files) });
    } else {
      const loaded = requests.load(message.request, (stage, fraction) => post({ id, type: 'progress', stage, fraction }));
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
