/**
 * Runs fuzz cases for scripts/fuzz.ts, one message per case: { target, seed, index } in, the outcome
 * and the case's time out. Cases are regenerated here from their seed, so nothing large is sent.
 */
import { parentPort } from 'node:worker_threads';
import { caseSeed, Rng } from '../tests/fuzz/mutate.ts';
import { runInput, TARGETS } from '../tests/fuzz/targets.ts';

parentPort!.on('message', async (job: { target: string; seed: number; index: number }) => {
  const target = TARGETS.find((t) => t.id === job.target)!;
  let files;
  try {
    files = target.input(new Rng(caseSeed(job.seed, job.index)), job.index);
  } catch (e) {
    // A bug of the fuzzer itself, not of a loader: reported as a crash that says so.
    parentPort!.postMessage({ kind: 'crash', message: `the fuzzer's input generator failed: ${(e as Error).message}`, ms: 0, bytes: 0 });
    return;
  }
  // Building a crafted input can take seconds on a loaded machine: the clock starts after it.
  parentPort!.postMessage({ started: true });
  const start = performance.now();
  const outcome = await runInput(target, files);
  parentPort!.postMessage({ ...outcome, ms: performance.now() - start, bytes: files.reduce((n, f) => n + f.bytes.length, 0) });
});
