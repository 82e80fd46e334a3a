import { describe, expect, it } from 'vitest';
import { compileComputePipeline, compileProgress, compileRenderPipeline, observeCompiles, setCompileConcurrency, type CompileProgress } from './pipeline-compiles.ts';
import { observeStages, type StageSpan } from './stage-log.ts';

/** A device whose pipelines are ready when the test says so: `finish(label)` resolves (or fails) that one. */
function fakeDevice() {
  const waiting = new Map<string, { resolve: (p: object) => void; reject: (e: Error) => void }>();
  const started: string[] = [];
  const create = (d: { label?: string }) =>
    new Promise<object>((resolve, reject) => {
      started.push(d.label!);
      waiting.set(d.label!, { resolve, reject });
    });
  const device = { createComputePipelineAsync: create, createRenderPipelineAsync: create } as unknown as GPUDevice;
  const settle = () => new Promise((r) => setTimeout(r, 0));
  return {
    device,
    started,
    async finish(label: string, error?: Error) {
      const w = waiting.get(label)!;
      if (error) w.reject(error);
      else w.resolve({ label });
      await settle();
    },
    settle,
  };
}

const compute = (device: GPUDevice, label: string, constants: Record<string, number> = {}) =>
  compileComputePipeline(device, { label, layout: 'auto', compute: { module: {} as GPUShaderModule, entryPoint: 'main', constants } });

describe('pipeline compiles: counted, timed, so many at a time', () => {
  it('counts what a batch needs and what is done, telling listeners each step', async () => {
    const f = fakeDevice();
    const seen: CompileProgress[] = [];
    observeCompiles(f.device, (p) => seen.push(p));
    const a = compute(f.device, 'a', { X: 1 });
    const b = compileRenderPipeline(f.device, { label: 'b', layout: 'auto', vertex: { module: {} as GPUShaderModule } });
    await f.settle();
    expect(compileProgress(f.device)).toMatchObject({ needed: 2, done: 0, concurrency: Infinity });
    expect(compileProgress(f.device).compiles.map((c) => c.key)).toEqual(['a X=1', 'b']);
    await f.finish('b');
    expect(compileProgress(f.device)).toMatchObject({ needed: 2, done: 1 });
    await f.finish('a');
    expect(await a).toEqual({ label: 'a' });
    expect(await b).toEqual({ label: 'b' });
    expect(seen.map((p) => `${p.done}/${p.needed}`)).toEqual(['0/1', '0/1', '0/2', '0/2', '1/2', '2/2']);
    const done = compileProgress(f.device).compiles;
    expect(done.every((c) => c.startMs !== undefined && c.endMs !== undefined && c.endMs >= c.startMs && c.startMs >= c.requestedMs)).toBe(true);
    // A request after the batch completed begins the next one.
    const c = compute(f.device, 'c');
    await f.settle();
    expect(compileProgress(f.device)).toMatchObject({ needed: 1, done: 0 });
    await f.finish('c');
    await c;
  });

  it('compiles at most the limit at a time, in the order asked, and counts a failure as done', async () => {
    const f = fakeDevice();
    setCompileConcurrency(f.device, 2);
    const spans: StageSpan[] = [];
    observeStages(f.device, (s) => spans.push(s));
    const labels = ['p1', 'p2', 'p3', 'p4', 'p5'];
    const compiles = labels.map((l) => compute(f.device, l));
    await f.settle();
    expect(f.started).toEqual(['p1', 'p2']);
    const running = () => compileProgress(f.device).compiles.filter((c) => c.startMs !== undefined && c.endMs === undefined).map((c) => c.label);
    expect(running()).toEqual(['p1', 'p2']);
    await f.finish('p2');
    expect(f.started).toEqual(['p1', 'p2', 'p3']);
    const failed = expect(compiles[0]).rejects.toThrow(/no such entry point/);
    await f.finish('p1', new Error('no such entry point'));
    await failed;
    expect(f.started).toEqual(['p1', 'p2', 'p3', 'p4']);
    expect(compileProgress(f.device)).toMatchObject({ needed: 5, done: 2 });
    // Raising the limit starts what waits at once.
    setCompileConcurrency(f.device, 3);
    await f.settle();
    expect(f.started).toEqual(labels);
    for (const l of ['p3', 'p4', 'p5']) await f.finish(l);
    await Promise.all(compiles.slice(1));
    expect(compileProgress(f.device)).toMatchObject({ needed: 5, done: 5 });
    // Each compile is a stage span from when it started compiling (not when it was queued).
    expect(spans.map((s) => s.stage)).toEqual(['pipeline p2', 'pipeline p1', 'pipeline p3', 'pipeline p4', 'pipeline p5']);
    const p4 = compileProgress(f.device).compiles.find((c) => c.label === 'p4')!;
    expect(spans[3]!.startMs).toBe(p4.startMs);
    expect(() => setCompileConcurrency(f.device, 0)).toThrow(/at least 1/);
  });
});
