/**
 * The long fuzz run: `npm run fuzz -- --minutes N [--seed S] [--targets wad,ply] [--out dir]
 * [--timeout-s 20] [--memory-mb 2048] [--cases N]`.
 *
 * The targets of tests/fuzz/targets.ts take turns, one case at a time, each in a worker thread of
 * its own: a case that runs past --timeout-s is a hang (its worker is terminated and replaced), one
 * that grows the process by more than --memory-mb (sampled every 20 ms) or runs the worker out of
 * heap is a memory failure, one that throws anything but a LanternError is a crash. Each failing
 * input is saved under --out/<target>/ as a reproducer (open it with `lantern info`), beside a
 * .txt saying what happened and the case's seed. At the end a table in the columns, with the
 * peak memory per class, goes to stdout (--json: as JSON).
 */
import { mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { Worker } from 'node:worker_threads';
import { caseSeed, Rng } from '../tests/fuzz/mutate.ts';
import { TARGETS, type FuzzTarget } from '../tests/fuzz/targets.ts';

interface Options {
  minutes: number;
  seed: number;
  targets: FuzzTarget[];
  out: string;
  timeoutMs: number;
  memoryBytes: number;
  cases: number;
  json: boolean;
}

function parseArgs(argv: readonly string[]): Options {
  const o: Options = { minutes: 1, seed: 1, targets: [...TARGETS], out: 'fuzz-findings', timeoutMs: 20_000, memoryBytes: 2 * 2 ** 30, cases: Infinity, json: false };
  for (let i = 0; i < argv.length; i++) {
    const flag = argv[i]!;
    const value = () => {
      const v = argv[++i];
      if (v === undefined) fail(`${flag} needs a value`);
      return v!;
    };
    const number = () => {
      const v = Number(value());
      if (!(v > 0)) fail(`${flag} needs a positive number`);
      return v;
    };
    if (flag === '--minutes') o.minutes = number();
    else if (flag === '--seed') o.seed = Math.floor(number());
    else if (flag === '--out') o.out = value();
    else if (flag === '--timeout-s') o.timeoutMs = number() * 1000;
    else if (flag === '--memory-mb') o.memoryBytes = number() * 2 ** 20;
    else if (flag === '--cases') o.cases = Math.floor(number());
    else if (flag === '--json') o.json = true;
    else if (flag === '--targets') {
      const ids = value().split(',');
      const unknown = ids.filter((id) => !TARGETS.some((t) => t.id === id));
      if (unknown.length > 0) fail(`unknown target ${unknown.join(', ')}; targets are ${TARGETS.map((t) => t.id).join(', ')}`);
      o.targets = TARGETS.filter((t) => ids.includes(t.id));
    } else fail(`unknown option ${flag}; options are --minutes, --seed, --targets, --out, --timeout-s, --memory-mb, --cases, --json`);
  }
  return o;
}

function fail(message: string): never {
  process.stderr.write(`fuzz: ${message}\n`);
  process.exit(2);
}

interface Tally {
  inputs: number;
  clean: number;
  crash: number;
  hang: number;
  memory: number;
  peakBytes: number;
  slowestMs: number;
}

type Result = { kind: 'ok' | 'clean' | 'crash'; message?: string; ms: number } | { kind: 'hang' | 'memory'; message: string; ms: number };

/** Beside this bundle (a constant, so the bundler leaves the URL alone, as in cli/bvh-workers.ts). */
const WORKER_FILE = './fuzz-worker.mjs';

/** A worker per target, replaced after a hang or a heap overflow. */
class CaseRunner {
  private worker: Worker | undefined;

  constructor(private readonly heapMb: number) {}

  /** `sample` returns true once the case is over its memory limit: it is stopped there, before it takes the machine. */
  run(target: string, seed: number, index: number, timeoutMs: number, onStart: () => void, sample: () => boolean): Promise<Result> {
    this.worker ??= new Worker(new URL(WORKER_FILE, import.meta.url), { resourceLimits: { maxOldGenerationSizeMb: this.heapMb } });
    const worker = this.worker;
    const start = performance.now();
    return new Promise((resolve) => {
      let started = false;
      const sampler = setInterval(() => {
        if (!started || !sample()) return;
        this.worker = undefined;
        void worker.terminate();
        done({ kind: 'memory', message: 'stopped when it passed the memory limit', ms: performance.now() - start });
      }, 20);
      const done = (r: Result) => {
        clearInterval(sampler);
        clearTimeout(timer);
        worker.off('message', onMessage);
        worker.off('error', onError);
        resolve(r);
      };
      let timer: ReturnType<typeof setTimeout> | undefined;
      const onMessage = (m: Result | { started: true }) => {
        if (!('started' in m)) return done(m);
        // The input is built: from here the case has timeoutMs, and its memory is measured from here.
        onStart();
        started = true;
        timer = setTimeout(() => {
          this.worker = undefined;
          void worker.terminate();
          done({ kind: 'hang', message: `still running after ${timeoutMs / 1000} s`, ms: timeoutMs });
        }, timeoutMs);
      };
      const onError = (e: Error & { code?: string }) => {
        this.worker = undefined;
        const memory = e.code === 'ERR_WORKER_OUT_OF_MEMORY';
        done({ kind: memory ? 'memory' : 'crash', message: `${e.name}: ${e.message}`, ms: performance.now() - start });
      };
      worker.on('message', onMessage);
      worker.on('error', onError);
      worker.postMessage({ target, seed, index });
    });
  }

  async close(): Promise<void> {
    await this.worker?.terminate();
  }
}

async function main(): Promise<void> {
  const o = parseArgs(process.argv.slice(2));
  const deadline = Date.now() + o.minutes * 60_000;
  const tallies = new Map<FuzzTarget, Tally>(o.targets.map((t) => [t, { inputs: 0, clean: 0, crash: 0, hang: 0, memory: 0, peakBytes: 0, slowestMs: 0 }]));
  // The worker's heap may grow past the memory limit so that the sampled growth, not V8, reports it.
  const runners = new Map(o.targets.map((t) => [t, new CaseRunner(Math.ceil((o.memoryBytes * 2) / 2 ** 20))]));
  process.stderr.write(`fuzz: seed ${o.seed}, ${o.minutes} min, targets ${o.targets.map((t) => t.id).join(', ')}\n`);
  let active = o.targets.filter(() => true);
  while (Date.now() < deadline && active.length > 0) {
    for (const target of active) {
      if (Date.now() >= deadline) break;
      const tally = tallies.get(target)!;
      const index = tally.inputs;
      let baseline = process.memoryUsage().rss;
      let peak = 0;
      const onStart = () => {
        baseline = process.memoryUsage().rss;
      };
      const result = await runners.get(target)!.run(target.id, o.seed, index, o.timeoutMs, onStart, () => {
        peak = Math.max(peak, process.memoryUsage().rss - baseline);
        return peak > o.memoryBytes;
      });
      tally.inputs++;
      tally.peakBytes = Math.max(tally.peakBytes, peak);
      tally.slowestMs = Math.max(tally.slowestMs, result.ms);
      let kind = result.kind;
      if ((kind === 'ok' || kind === 'clean') && peak > o.memoryBytes) kind = 'memory';
      if (kind === 'ok' || kind === 'clean') tally.clean++;
      else {
        tally[kind]++;
        save(o, target, index, kind, result.message ?? `grew the process by ${(peak / 2 ** 20).toFixed(0)} MB`);
      }
    }
    active = active.filter((t) => tallies.get(t)!.inputs < Math.min(o.cases, t.count ?? Infinity));
  }
  await Promise.all([...runners.values()].map((r) => r.close()));
  report(o, tallies);
}

function save(o: Options, target: FuzzTarget, index: number, kind: string, message: string): void {
  const dir = join(o.out, target.id);
  mkdirSync(dir, { recursive: true });
  const stem = `${kind}-seed${o.seed}-case${index}`;
  try {
    const files = target.input(new Rng(caseSeed(o.seed, index)), index);
    files.forEach((f) => writeFileSync(join(dir, `${stem}-${f.name.replace(/[^\w.-]+/g, '_')}`), f.bytes));
  } catch (e) {
    message += ` (the input could not be rebuilt: ${(e as Error).message})`;
  }
  writeFileSync(join(dir, `${stem}.txt`), `${target.label}\nseed ${o.seed}, case ${index}: ${kind}\n${message}\n`);
  process.stderr.write(`fuzz: ${target.id} case ${index}: ${kind}: ${message}\n`);
}

function report(o: Options, tallies: Map<FuzzTarget, Tally>): void {
  const rows = [...tallies].map(([t, s]) => ({ class: t.label, id: t.id, ...s }));
  if (o.json) {
    process.stdout.write(`${JSON.stringify({ seed: o.seed, minutes: o.minutes, rows }, null, 2)}\n`);
    return;
  }
  const mb = (b: number) => `${Math.round(b / 2 ** 20).toLocaleString('en-US')} MB`;
  const lines = [
    `| input class | inputs | ok or clean error | crash | hang (> ${o.timeoutMs / 1000} s) | memory > ${mb(o.memoryBytes)} | peak memory | slowest case |`,
    '|---|---|---|---|---|---|---|---|',
    ...rows.map((r) => `| ${r.class} | ${r.inputs.toLocaleString('en-US')} | ${r.clean.toLocaleString('en-US')} | ${r.crash} | ${r.hang} | ${r.memory} | ${mb(r.peakBytes)} | ${(r.slowestMs / 1000).toFixed(2)} s |`),
  ];
  process.stdout.write(`${lines.join('\n')}\n`);
}

await main();
