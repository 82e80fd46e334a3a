import { describe, expect, it } from 'vitest';
import { LanternError } from '../errors.ts';
import { buildBvh } from './build.ts';
import { buildBvhParallel, runSubtreeTask, SubtreeWorkerPool, type SubtreePort, type SubtreeReply, type SubtreeTask } from './build-parallel.ts';
import { movingTestScene, randomSoup, uvSphere } from './test-scenes.ts';
import { buildStaticBvh, buildStaticBvhWith } from './levels.ts';
import { flattenTriangles } from '../scene/triangles.ts';
import { prepareScene, prepareSceneAsync } from '../renderer/prepare.ts';
import type { Bvh } from './types.ts';
import { checkBvh } from './validate.ts';

/**
 * Workers on this thread: each task is structured-cloned on the way in and out as postMessage
 * would (its buffers detached from the sender) and answered in a later macrotask, odd workers
 * after even ones, so tasks finish out of order as they do with real threads.
 */
function inProcessPool(size: number, log?: number[], splitOnly?: { tasks: number }): SubtreeWorkerPool {
  let spawned = 0;
  return new SubtreeWorkerPool(size, (): SubtreePort => {
    const me = spawned++;
    let reply: (r: SubtreeReply) => void = () => {};
    return {
      post(task: SubtreeTask, transfer: ArrayBuffer[]) {
        const copy = structuredClone(task, { transfer });
        log?.push(me);
        const answer = () => {
          const { reply: r, transfer: back } = runSubtreeTask(copy);
          if (splitOnly && 'deferred' in r && r.deferred.length > 0) splitOnly.tasks++;
          reply(structuredClone(r, { transfer: back }));
        };
        if (me % 2 === 0) setImmediate(answer);
        else setTimeout(answer, 1);
      },
      listen(onReply) {
        reply = onReply;
      },
      terminate() {},
    };
  });
}

/** The first index where two arrays' bytes differ, -1 if none (and lengths equal). Bit-exact: -0, NaN and all. */
function firstDifference(a: ArrayBufferView, b: ArrayBufferView): number {
  if (a.byteLength !== b.byteLength) return Math.min(a.byteLength, b.byteLength);
  const x = new Uint8Array(a.buffer, a.byteOffset, a.byteLength), y = new Uint8Array(b.buffer, b.byteOffset, b.byteLength);
  for (let i = 0; i < x.length; i++) if (x[i] !== y[i]) return i;
  return -1;
}

function expectSameTree(a: Bvh, b: Bvh): void {
  expect(a.nodeCount).toBe(b.nodeCount);
  for (const key of ['bounds', 'leftFirst', 'triCount', 'triIndices'] as const) expect(firstDifference(a[key], b[key]), key).toBe(-1);
  const { buildMs: _a, workers: _wa, ...sa } = a.stats;
  const { buildMs: _b, workers: _wb, ...sb } = b.stats;
  expect(sa).toEqual(sb);
}

describe('buildBvhParallel', () => {
  const soup = randomSoup(4000, 21);
  const single = buildBvh(soup);

  // Tasks down to a few primitives (leaves and exact-sweep nodes as subtree roots) up to a quarter of the input.
  for (const [workers, taskPrimitives] of [[2, 7], [3, 60], [4, 900], [2, 1000]] as const) {
    it(`gives the single-thread tree bit for bit: ${workers} workers, tasks of <= ${taskPrimitives}`, async () => {
      const log: number[] = [];
      const splitOnly = { tasks: 0 };
      const bvh = await buildBvhParallel(soup, {}, undefined, inProcessPool(workers, log, splitOnly), { minPrimitives: 0, taskPrimitives });
      checkBvh(bvh, soup, 60);
      expectSameTree(bvh, single);
      // The tasks really went out, to every worker, and workers split big ones for the others.
      expect(log.length).toBeGreaterThan(workers);
      expect(new Set(log).size).toBe(workers);
      expect(splitOnly.tasks).toBeGreaterThan(0);
      expect(bvh.stats.workers).toBe(workers);
      expect(single.stats.workers).toBeUndefined();
    });
  }

  it('matches with other build options and a mesh with many equal-size triangles', async () => {
    const sphere = uvSphere(48, 96);
    for (const options of [{ bins: 5, maxLeafSize: 2 }, { maxDepth: 9 }, { traversalCost: 3, intersectionCost: 0.5 }]) {
      const bvh = await buildBvhParallel(sphere, options, undefined, inProcessPool(3), { minPrimitives: 0, taskPrimitives: 150 });
      checkBvh(bvh, sphere, options.maxDepth ?? 60);
      expectSameTree(bvh, buildBvh(sphere, options));
    }
  });

  it("builds a scene's static world (moving instances left out) as buildStaticBvh does", async () => {
    const scene = movingTestScene();
    const triangles = flattenTriangles(scene);
    const pool = inProcessPool(2);
    const parallel = await buildStaticBvhWith(scene, triangles, (positions, kinds) => buildBvhParallel(positions, {}, kinds, pool, { minPrimitives: 0, taskPrimitives: 40 }));
    expectSameTree(parallel, buildStaticBvh(scene, triangles));
    // And prepareSceneAsync (which keeps a scene this small on its own thread) prepares what prepareScene does.
    const [a, b] = [prepareScene(scene), await prepareSceneAsync(scene, undefined, { bvhPool: pool })];
    expectSameTree(b.bvh, a.bvh);
    expect(firstDifference(new Uint8Array(b.packed.bvh_nodes), new Uint8Array(a.packed.bvh_nodes))).toBe(-1);
  });

  it('stays on the calling thread for small inputs or fewer than two workers', async () => {
    const log: number[] = [];
    expectSameTree(await buildBvhParallel(soup, {}, undefined, inProcessPool(4, log)), single);
    expectSameTree(await buildBvhParallel(soup, {}, undefined, inProcessPool(1, log), { minPrimitives: 0 }), single);
    expectSameTree(await buildBvhParallel(soup, {}, undefined, undefined, { minPrimitives: 0 }), single);
    expect(log).toEqual([]);
  });

  it('falls back to the calling thread when a worker fails, and then leaves that pool alone', async () => {
    let posts = 0;
    const pool = new SubtreeWorkerPool(2, () => {
      let fail: (e: Error) => void = () => {};
      return { post: () => (posts++, setTimeout(() => fail(new Error('out of memory')))), listen: (_r, f) => (fail = f), terminate() {} };
    });
    expectSameTree(await buildBvhParallel(soup, {}, undefined, pool, { minPrimitives: 0, taskPrimitives: 500 }), single);
    const tried = posts;
    expect(tried).toBeGreaterThan(0);
    await expect(pool.build({} as SubtreeTask)).rejects.toThrow(/BVH build worker failed: out of memory/);
    expectSameTree(await buildBvhParallel(soup, {}, undefined, pool, { minPrimitives: 0 }), single);
    expect(posts).toBe(tried);
    expect(() => new SubtreeWorkerPool(0, () => { throw new Error('unused'); })).toThrow(LanternError);
    // Workers that cannot even start (a page that may not start nested workers).
    const unstartable = new SubtreeWorkerPool(3, () => { throw new Error('SecurityError'); });
    expectSameTree(await buildBvhParallel(soup, {}, undefined, unstartable, { minPrimitives: 0 }), single);
    await expect(unstartable.build({} as SubtreeTask)).rejects.toThrow(/cannot start a BVH build worker: SecurityError/);
  });

  it('reports an error inside a worker build as an error, not a fallback', async () => {
    const pool = new SubtreeWorkerPool(2, () => {
      let reply: (r: SubtreeReply) => void = () => {};
      return { post: (task: SubtreeTask) => setTimeout(() => reply({ id: task.id, error: 'partition put 3 triangles left' })), listen: (r) => (reply = r), terminate() {} };
    });
    await expect(buildBvhParallel(soup, {}, undefined, pool, { minPrimitives: 0 })).rejects.toThrow(/BVH build worker: partition put 3/);
  });
});
